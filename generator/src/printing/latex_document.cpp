#include "pfgen/printing/latex_document.hpp"

#include "pfgen/printing/equation_report.hpp"
#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"

namespace pfgen {
namespace {

std::string bmatrix(const LatexPrinter& printer, const ExMatrix& m) {
  std::string out = "\\begin{bmatrix}";
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t j = 0; j < m[i].size(); ++j) out += (j ? " & " : "") + printer.print(m[i][j]);
    out += i + 1 < m.size() ? " \\\\ " : "";
  }
  return out + "\\end{bmatrix}";
}

// "name &= [matrix]" when it fits the page, else one aligned line per nonzero entry (cut in turn
// when long), so that every term of a dense model's f and g is on the page.
// `label` heads the whole matrix ("G = g g^{T}"), `name` its entries (G_{1,2}).
std::string matrix_lines(const LatexPrinter& printer, const std::string& label, const std::string& name,
                         const ExMatrix& m) {
  const std::string whole = bmatrix(printer, m);
  if (latex_width(label) + 1.8 + latex_width(whole) <= kLatexLineWidth) return label + " &= " + whole;
  const bool vector = !m.empty() && m[0].size() == 1;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m[i].size(); ++j) {
      if (m[i][j].is_zero()) continue;
      const std::string index = vector ? std::to_string(i + 1) : std::to_string(i + 1) + "," + std::to_string(j + 1);
      lines.push_back(latex_align_lines(name + "_{" + index + "}", printer.print(m[i][j])));
    }
  if (lines.empty()) return name + " &= 0";
  std::string out;
  for (std::size_t k = 0; k < lines.size(); ++k) out += lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "");
  if (lines.size() < m.size() * m[0].size()) out += " \\\\\n&\\text{(other entries of $" + name + "$ are 0)}";
  return out;
}

ExMatrix column(const ExVector& v) {
  ExMatrix out;
  for (const auto& e : v) out.push_back({e});
  return out;
}

template <class T>
ExMatrix numeric_matrix(const std::vector<std::vector<T>>& m) {
  ExMatrix out;
  for (const auto& row : m) out.push_back(ExVector(row.begin(), row.end()));
  return out;
}

std::string model_section(const Model& model) {
  LatexPrinter printer;
  std::string out = "\\section*{Model \\texttt{" + latex_escape_text(model.name) + "}}\n";
  out += "State $x = (";
  for (std::size_t i = 0; i < model.n(); ++i) out += (i ? ", " : "") + printer.name(model.state_names[i]);
  out += ")$, time $" + printer.name(model.time.get_name()) + "$";
  if (!model.parameters.empty()) {
    out += ", parameters ";
    for (std::size_t k = 0; k < model.parameters.size(); ++k)
      out += std::string(k ? ", " : "") + "$" + printer.name(model.parameters[k].name) + " = " +
             printer.print(model.parameters[k].default_value) + "$";
    out += " (kept symbolic below)";
  }
  // A delayed observation sees the state h ago (docs/theory.md §2.6).
  const bool delayed = model.observation.is_delayed();
  out += std::string(".\n\\[ dx = f\\,dt + g\\,dW_1, \\qquad dy = (A_0 + A ") + (delayed ? "x(t-h)" : "x") +
         ")\\,dt + B\\,dW_2 \\]\n";
  out += "\\begin{align*}\n" + matrix_lines(printer, "f", "f", column(model.drift)) + " \\\\\n";
  if (model.diffusion.g) {
    out += matrix_lines(printer, "g", "g", *model.diffusion.g) + " \\\\\n";
  } else {
    out += matrix_lines(printer, "G = g g^{T}", "G", model.diffusion.G) + " \\\\\n";
  }
  if (model.additive_diffusion) {
    const Diffusion& d = *model.additive_diffusion;
    out += (d.g ? matrix_lines(printer, "g_{\\mathrm{add}}", "g^{\\mathrm{add}}", *d.g) : matrix_lines(printer, "G_{\\mathrm{add}}", "G^{\\mathrm{add}}", d.G)) +
           " \\\\\n";
  }
  if (model.observation.is_sampled()) {
    const SampledObservation& sampled = model.observation.sampled();
    const std::string observation_line = bmatrix(printer, column(sampled.C0)) + ", \\quad C = " +
                                         bmatrix(printer, sampled.C) + ", \\quad U_v = " + bmatrix(printer, sampled.Uv) +
                                         ", \\quad T = " + printer.print(sampled.period);
    if (latex_width("C_0 = " + observation_line) <= kLatexLineWidth)
      out += "C_0 &= " + observation_line;
    else
      out += matrix_lines(printer, "C_0", "C_0", column(sampled.C0)) + " \\\\\n" +
             matrix_lines(printer, "C", "C", sampled.C) + " \\\\\n" + matrix_lines(printer, "U_v", "U_v", sampled.Uv) +
             " \\\\\nT &= " + printer.print(sampled.period);
  } else {
    const ContinuousObservation& observation = model.observation.rate();
    const std::string delay = delayed ? ", \\quad h = " + printer.print(model.observation.delay()) : "";
    const std::string observation_line = bmatrix(printer, column(observation.A0)) + ", \\quad A = " +
                                         bmatrix(printer, observation.A) + ", \\quad B = " + bmatrix(printer, observation.B) +
                                         delay;
    if (latex_width("A_0 = " + observation_line) <= kLatexLineWidth)
      out += "A_0 &= " + observation_line;
    else
      out += matrix_lines(printer, "A_0", "A_0", column(observation.A0)) + " \\\\\n" +
             matrix_lines(printer, "A", "A", observation.A) + " \\\\\n" + matrix_lines(printer, "B", "B", observation.B) +
             (delayed ? " \\\\\nh &= " + printer.print(model.observation.delay()) : "");
  }
  if (model.initial) {
    const InitialConditions& ic = *model.initial;
    out += " \\\\\n";
    if (!ic.x0.empty()) out += "x_0 &= " + bmatrix(printer, column(ExVector(ic.x0.begin(), ic.x0.end()))) + ", \\quad ";
    else out += "&";
    out += "m_0 = " + bmatrix(printer, column(ExVector(ic.m0.begin(), ic.m0.end()))) +
           ", \\quad P_0 = " + bmatrix(printer, numeric_matrix(ic.P0));
  }
  out += "\n\\end{align*}\n";
  return out;
}

}  // namespace

std::string latex_document(const Model& model, const std::vector<FilterEquations>& filters) {
  std::string out;
  out += "% Generated by pfgen " PFGEN_VERSION " from model " + model.name + ". Do not edit.\n";
  out += "\\documentclass[10pt]{article}\n\\usepackage[margin=2cm]{geometry}\n\\usepackage{amsmath}\n";
  out += "\\allowdisplaybreaks\n\\begin{document}\n";
  out += "\\title{Filter equations for \\texttt{" + latex_escape_text(model.name) + "}}\n";
  out += "\\author{pfgen " PFGEN_VERSION "}\n\\date{}\n\\maketitle\n";
  out += model_section(model);
  bool any_user_filter = false;
  for (const auto& eq : filters) any_user_filter = any_user_filter || eq.is_user_filter();
  if (model.observation.is_sampled())
    out += "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state and $P_{ij}$ the error covariance. "
           "Between samples $m$ and $P$ follow the prediction; at each sample $y$ the Kalman update with "
           "$S = C P C^{T} + U_v U_v^{T}$ and $K = P C^{T} S^{-1}$ applies.";
  else if (model.observation.is_delayed())
    out += "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state, $P_{ij}$ the error covariance, "
           "$K$ the gain and $dy_{r}$ the observation increments; the innovation compares $dy$ with the estimate "
           "$m(t-h)$ of the delayed state. Each $dP$ is written as $E[(x-m)f^{T}] + E[f(x-m)^{T}]$, then the "
           "diffusion term, then the correction $-K A \\Phi^{*} P$ (with $\\Phi^{*} = I$ for the filters without "
           "$\\Phi^{*}$), without merging like terms across the three parts.";
  else
    out += "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state, $P_{ij}$ the error covariance, "
           "$K$ the gain $P A^{T}(B B^{T})^{-1}$ and $dy_{r}$ the observation increments. Each $dP$ is written as "
           "$E[(x-m)f^{T}] + E[f(x-m)^{T}]$, then the diffusion term, then $-P A^{T}(B B^{T})^{-1} A P$, "
           "without merging like terms across the three parts.";
  if (any_user_filter)
    out += " A filter defined in the model file has its $dm$, $K$ and $dP$ as given there, not derived by pfgen.";
  out += "\n";
  for (const auto& eq : filters) {
    out += "\\section*{Filter \\texttt{" + latex_escape_text(eq.name) + "}}\n";
    const bool has_stop = !eq.description.empty() && eq.description.back() == '.';
    out += latex_escape_text(eq.description) + (has_stop ? "\n\n" : ".\n\n");
    out += equations_latex(eq);
  }
  out += "\\end{document}\n";
  return out;
}

}  // namespace pfgen
