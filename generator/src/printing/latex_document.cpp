#include "pfgen/printing/latex_document.hpp"

#include "pfgen/printing/coefficient_report.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/rich_text.hpp"
#include "pfgen/printing/latex_matrix.hpp"
#include "pfgen/printing/noise_report.hpp"

namespace pfgen {
namespace {

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
  // With Stratonovich noise f is the drift as written; the Ito drift follows the model (noise_report).
  const bool stratonovich = model.noise == NoiseCalculus::Stratonovich;
  out += std::string(".\n\\[ dx = f\\,dt + g") + (stratonovich ? " \\circ " : "\\,") +
         "dW_1, \\qquad dy = (A_0 + A " + (delayed ? "x(t-h)" : "x") + ")\\,dt + B\\,dW_2 \\]\n";
  out += "\\begin{align*}\n" + matrix_lines(printer, "f", "f", column(stratonovich ? model.stated_drift : model.drift)) +
         " \\\\\n";
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
    const ExMatrix x0 = column(ExVector(ic.x0.begin(), ic.x0.end())), m0 = column(ExVector(ic.m0.begin(), ic.m0.end()));
    const ExMatrix P0 = numeric_matrix(ic.P0);
    std::string line = ic.x0.empty() ? "&" : "x_0 &= " + bmatrix(printer, x0) + ", \\quad ";
    line += "m_0 = " + bmatrix(printer, m0) + ", \\quad P_0 = " + bmatrix(printer, P0);
    // A P0 of more than amsmath's 10 matrix columns (16 states) cannot be one bmatrix, nor fit a
    // line: then x0, m0 and P0 are written as the matrices above are, entry by entry where too wide.
    if (model.n() <= 10)
      out += line;
    else
      out += (ic.x0.empty() ? "" : matrix_lines(printer, "x_0", "(x_0)", x0) + " \\\\\n") +
             matrix_lines(printer, "m_0", "(m_0)", m0) + " \\\\\n" + matrix_lines(printer, "P_0", "(P_0)", P0);
  }
  out += "\n\\end{align*}\n";
  return out + noise_latex(model);
}

// The document ends with a filter's last display. \allowdisplaybreaks lets TeX break a page
// between any two of its rows, so a document could end on a page holding one or two rows. The
// last two row breaks of that display are made \\* (no page break there): its last three rows
// (or all of a shorter one, which then keeps the line before it, \predisplaypenalty) share the
// last page. Page breaks elsewhere are TeX's as before.
void keep_last_rows_together(std::string& document) {
  const std::size_t end = document.rfind("\\end{align*}");
  if (end == std::string::npos) return;
  const std::size_t begin = document.rfind("\\begin{align*}", end);
  if (begin == std::string::npos) return;
  const std::string row_break = " \\\\\n";
  std::size_t at = end;
  for (int k = 0; k < 2; ++k) {
    at = document.rfind(row_break, at - 1);
    if (at == std::string::npos || at < begin) return;
    document.insert(at + 3, "*");
  }
}

}  // namespace

std::string latex_document(const Model& model, const std::vector<FilterEquations>& filters, bool coefficients) {
  std::string out;
  out += "% Generated by pfgen " PFGEN_VERSION " from model " + model.name + ". Do not edit.\n";
  out += "\\documentclass[10pt]{article}\n\\usepackage[margin=2cm]{geometry}\n\\usepackage{amsmath}\n";
  out += "\\allowdisplaybreaks\n\\begin{document}\n";
  out += "\\title{Filter equations for \\texttt{" + latex_escape_text(model.name) + "}}\n";
  out += "\\author{pfgen " PFGEN_VERSION "}\n\\date{}\n\\maketitle\n";
  out += model_section(model);
  if (coefficients)
    out += "\\section*{Coefficient form}\n" +
           coefficients_latex(model, extract_drift_coefficients(model), extract_observation_coefficients(model));
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
    const std::string plain = rich_text_plain(eq.description);
    const bool has_stop = !plain.empty() && plain.back() == '.';
    out += rich_text_latex(eq.description) + (has_stop ? "\n\n" : ".\n\n");
    out += equations_latex(eq);
  }
  keep_last_rows_together(out);
  out += "\\end{document}\n";
  return out;
}

}  // namespace pfgen
