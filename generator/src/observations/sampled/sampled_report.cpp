// The sampled observation y_k = C0 + C x(t_k) + Uv v_k in the reports: a sampled filter's
// prediction between samples and its update at each sample, shown apart, as text, LaTeX and JSON;
// and its lines in the standalone document and the coefficient form.
#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/number_format.hpp"
#include "pfgen/notation/rich_text.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "pfgen/printing/latex_matrix.hpp"
#include "pfgen/printing/moment_report.hpp"
#include "pfgen/printing/noise_report.hpp"
#include "pfgen/printing/observation_report.hpp"
#include "pfgen/printing/report_parts.hpp"

namespace pfgen {
namespace {

// A moment filter's moments at a sample: those of the law of x + K (y - C0 - C x - v), v ~ N(0, R)
// (sampled_moment_update.hpp), or with a polynomial c those of Abar z - K v (closure_sampled_update.hpp), one line
// per order.
std::vector<std::string> moment_update_lines(const FilterVariables& vars, const SampledUpdate& u) {
  std::vector<std::string> lines;
  if (u.closed_law) {
    lines.push_back("P <- Abar Z2 Abar^T + K R K^T");
    lines.push_back("M3_ijl <- sum_abc Abar_ia Abar_jb Abar_lc Z3_abc");
    if (vars.order() >= 4)
      lines.push_back("M4_ijlq <- sum_abcd Abar_ia Abar_jb Abar_lc Abar_qd Z4_abcd + U_ij Q_lq + U_il Q_jq + U_iq Q_jl + "
                      "U_jl Q_iq + U_jq Q_il + U_lq Q_ij + Q_ij Q_lq + Q_il Q_jq + Q_iq Q_jl");
    return lines;
  }
  lines.push_back("P <- (I - K C) P (I - K C)^T + K R K^T");
  if (vars.higher_moments().empty()) return lines;
  lines.push_back("M3_ijl <- sum_abc A_ia A_jb A_lc M3_abc");
  if (vars.order() >= 4)
    lines.push_back("M4_ijlq <- sum_abcd A_ia A_jb A_lc A_qd M4_abcd + U_ij Q_lq + U_il Q_jq + U_iq Q_jl + U_jl Q_iq + "
                    "U_jq Q_il + U_lq Q_ij + Q_ij Q_lq + Q_il Q_jq + Q_iq Q_jl");
  return lines;
}

std::string moment_update_where(const FilterVariables& vars, const SampledUpdate& u) {
  if (u.closed_law)
    return std::string("Abar = [I - K C, -K]") + (vars.order() >= 4 ? ", U = Abar Z2 Abar^T, Q = K R K^T" : "") +
           ": the moments of the law of x + K (y - c(x) - v) = m+ + Abar z - K v, v ~ N(0, R), z = (x - m, d), d = c(x) "
           "- h - C (x - m); Z the joint moments of z, the filter's P and M where all indices are x - m's";
  return std::string("A = I - K C") + (vars.order() >= 4 ? ", U = A P A^T, Q = K R K^T" : "") +
         ": the moments of the law of x + K (y - C0 - C x - v), v ~ N(0, R)";
}

// The update's lines after m's: P's, then the higher moments' and where their symbols come from.
std::string moment_update_text(const FilterVariables& vars, const SampledUpdate& u) {
  std::string out;
  for (const std::string& line : moment_update_lines(vars, u)) out += line + "\n";
  return vars.higher_moments().empty() ? out : out + "  (" + moment_update_where(vars, u) + ")\n";
}

std::string moment_update_formula(const FilterVariables& vars, const SampledUpdate& u) {
  std::string out;
  const std::vector<std::string> lines = moment_update_lines(vars, u);
  for (std::size_t k = 1; k < lines.size(); ++k) out += lines[k] + "; ";
  return out + moment_update_where(vars, u);
}

std::vector<std::string> moment_update_latex(const FilterVariables& vars, const SampledUpdate& u) {
  std::vector<std::string> lines;
  if (vars.higher_moments().empty()) return lines;
  const std::string A = u.closed_law ? "\\bar{A}" : "A", mu = u.closed_law ? "Z" : "\\mu";
  auto product = [&](const std::string& indices) {
    std::string out;
    for (std::size_t k = 0; k < indices.size(); ++k)
      out += (k ? " " : "") + A + "_{" + indices.substr(k, 1) + std::string("abcd").substr(k, 1) + "}";
    return out;
  };
  lines.push_back("\\mu_{ijl} &\\leftarrow \\textstyle\\sum_{abc} " + product("ijl") + "\\, " + mu + "_{abc}" +
                  (u.closed_law ? ", \\quad \\bar{A} = [I - K C, \\ -K]" : ", \\quad A = I - K C"));
  if (vars.order() >= 4)
    lines.push_back("\\mu_{ijlq} &\\leftarrow \\textstyle\\sum_{abcd} " + product("ijlq") + "\\, " + mu + "_{abcd} + "
                    "\\sum_{6} U_{ij} Q_{lq} + \\sum_{3} Q_{ij} Q_{lq}, \\quad U = " + A + " " +
                    (u.closed_law ? "Z" : "P") + " " + A + "^{T}, \\ Q = K R K^{T}");
  return lines;
}

// A joint moment of z = (x - m, d) (n + r entries) with these ascending 0-based indices: "Z3_113", "Z_{113}".
std::string joint_name(const std::vector<std::size_t>& t, std::size_t columns, bool latex) {
  std::string indices;
  for (std::size_t k = 0; k < t.size(); ++k)
    indices += (k && columns >= 10 ? (latex ? "," : "_") : "") + std::to_string(t[k] + 1);
  return latex ? "Z_{" + indices + "}" : "Z" + std::to_string(t.size()) + "_" + indices;
}

std::vector<ReportPart> P_parts(const FilterEquations& eq, std::size_t u) { return {{&eq.P_moment[u]}, {&eq.P_diffusion[u]}}; }

std::string index2(std::size_t i, std::size_t j) { return std::to_string(i + 1) + std::to_string(j + 1); }

std::string substep_phrase(const SampledUpdate& u) {
  return std::to_string(u.substeps) + (u.substeps == 1 ? " sub-step" : " sub-steps");
}

// Why the prediction takes u.substeps (observations/sampled/substep_choice.hpp): chosen from the
// prediction at the prior, or given and fewer than that rule asks for, between `open` and `close`;
// empty otherwise.
std::string substep_reason(const SampledUpdate& u, const std::string& open, const std::string& close) {
  const std::string rule = "the prediction at the prior: rate " + three_digits(u.prior_rate) +
                           " per unit of time, first period to 1 %";
  if (u.substeps_chosen) return open + "chosen from " + rule + "; the model's substeps sets them" + close;
  if (u.advised_substeps > static_cast<double>(u.substeps))
    return open + "fewer than the " + three_digits(u.advised_substeps) + " asked for by " + rule + close;
  return {};
}

// What the samples' rate changes in their report, one part per value of the rate, chosen once
// (sample_rate_report) as the derivation chooses its part (sampled_observation_derivation): the
// samples as written, the update's words (how it reads C and R) and its JSON, the document's lines.
class SampleRateReport {
 public:
  virtual ~SampleRateReport() = default;
  virtual std::string samples_text(const Model& model, TextPrinter& printer) const = 0;  // after "y_k = "
  virtual std::string update_text(const SampledUpdate& u) const = 0;
  virtual std::string update_latex(const SampledUpdate& u) const = 0;
  virtual void add_update_json(const Model& model, const SampledUpdate& u, TextPrinter& printer, Json& update) const = 0;
  virtual std::string equation_latex() const = 0;
  virtual std::string matrices_latex(const Model& model, LatexPrinter& printer, const std::string& period) const = 0;
};

// Samples C0 + C x(t_k) + Uv v_k: the Kalman update in Joseph form.
class AffineSampleReport final : public SampleRateReport {
 public:
  std::string samples_text(const Model&, TextPrinter&) const override { return "C0 + C x(t_k) + Uv v_k"; }
  std::string update_text(const SampledUpdate&) const override { return "R = Uv Uv^T (Joseph form)"; }
  std::string update_latex(const SampledUpdate&) const override { return "$R = U_v U_v^{T}$, Joseph form"; }
  void add_update_json(const Model&, const SampledUpdate&, TextPrinter&, Json&) const override {}
  std::string equation_latex() const override { return "y_k = C_0 + C\\,x(t_k) + U_v v_k"; }
  std::string matrices_latex(const Model& model, LatexPrinter& printer, const std::string& period) const override {
    const AffineRate& sampled = *model.observation.rate().affine();
    const std::string observation_line = bmatrix(printer, column(sampled.A0)) + ", \\quad C = " +
                                         bmatrix(printer, sampled.A) + ", \\quad U_v = " + bmatrix(printer, sampled.B) +
                                         ", \\quad T = " + period;
    if (latex_width("C_0 = " + observation_line) <= kLatexLineWidth) return "C_0 &= " + observation_line;
    return matrix_lines(printer, "C_0", "C_0", column(sampled.A0)) + " \\\\\n" +
           matrix_lines(printer, "C", "C", sampled.A) + " \\\\\n" + matrix_lines(printer, "U_v", "U_v", sampled.B) +
           " \\\\\nT &= " + period;
  }
};

// Samples c(x(t_k)) + Uv v_k through rows c: the update reads C and R as the moments give them (the
// Joseph form's, equal to P - K S K^T), or linearised at m.
class RowSampleReport final : public SampleRateReport {
 public:
  std::string samples_text(const Model& model, TextPrinter& printer) const override {
    std::string out = "c(x(t_k)) + Uv v_k, c = (";
    for (std::size_t a = 0; a < model.observation.rate().rows().size(); ++a)
      out += (a ? ", " : "") + printer.print(model.observation.rate().rows()[a]);
    return out + ")";
  }
  std::string update_text(const SampledUpdate& u) const override {
    if (u.closed_law)
      return "moment matching under the closed law: h = E[c], PCt = Cov(x, c), Pyy = Cov(c) + Uv Uv^T, C = E[J_c], "
             "R = Uv Uv^T, z = (x - m, d), d = c(x) - h - C (x - m)";
    return u.at_mean ? "linearised at m: h = c(m), C = J_c(m), R = Uv Uv^T (Joseph form)"
                     : "Gaussian moment matching: h = E[c], C = E[J_c], R = Cov(c) - C P C^T + Uv Uv^T (Joseph form, "
                       "equal to P - K S K^T)";
  }
  std::string update_latex(const SampledUpdate& u) const override {
    if (u.closed_law)
      return "moment matching under the closed law: $h = E[c]$, $P C^{T} = \\mathrm{Cov}(x, c)$, $S = \\mathrm{Cov}(c) + "
             "U_v U_v^{T}$, $C = E[J_c]$, $R = U_v U_v^{T}$, $Z$ the joint moments of $z = (x - m, d)$, "
             "$d = c(x) - h - C (x - m)$";
    return u.at_mean ? "linearised at $m$: $h = c(m)$, $C = J_c(m)$, $R = U_v U_v^{T}$, Joseph form"
                     : "Gaussian moment matching: $h = E[c]$, $C = E[J_c]$, $R = \\mathrm{Cov}(c) - C P C^{T} + U_v U_v^{T}$, "
                       "Joseph form, equal to $P - K S K^{T}$";
  }
  void add_update_json(const Model& model, const SampledUpdate& u, TextPrinter& printer, Json& update) const override {
    Json c = Json::array();
    for (const GiNaC::ex& entry : model.observation.rate().rows()) c.push(Json::string(printer.print(entry)));
    update.add("c", c);
    update.add("form", Json::string(update_text(u)));
  }
  std::string equation_latex() const override { return "y_k = c(x(t_k)) + U_v v_k"; }
  std::string matrices_latex(const Model& model, LatexPrinter& printer, const std::string& period) const override {
    const ObservationRate& rate = model.observation.rate();
    return matrix_lines(printer, "c", "c", column(rate.rows())) + " \\\\\n" +
           matrix_lines(printer, "U_v", "U_v", rate.noise()) + " \\\\\nT &= " + period;
  }
};

const SampleRateReport& sample_rate_report(const ObservationRate& rate) {
  static const AffineSampleReport affine;
  static const RowSampleReport rows;
  if (rate.affine()) return affine;
  return rows;
}

std::string sampled_equations_text(const Model& model, const FilterEquations& eq) {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  std::string out;
  out += "model: " + model.name + "\n";
  out += noise_text(model);
  out += "filter: " + eq.name + " (" + rich_text_plain(eq.description) + ")\n";
  out += "exactness: " + exactness_text(eq.exactness);
  out += "\nvariables: ";
  for (std::size_t i = 0; i < n; ++i)
    out += (i ? ", " : "") + vars.text_name(vars.m(i)) + " = E[" + model.state_names[i] + "]";
  out += "; P = covariance of (";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + model.state_names[i];
  out += ")\n";
  out += higher_moments_header_text(eq);
  const SampleRateReport& rate = sample_rate_report(model.observation.rate());
  out += "observation: sampled every T = " + printer.print(u.period) + ", y_k = " + rate.samples_text(model, printer) + "; " +
         substep_phrase(u) + " of dt = T/" + std::to_string(u.substeps) + " between samples" +
         substep_reason(u, " (", ")") + "\n\n";
  if (eq.P_euler.empty()) {
    out += "prediction between samples (no observation term; dP terms: [" + moment_terms_text(eq) + "] + [diffusion]):\n";
    for (std::size_t i = 0; i < n; ++i)
      out += "dm" + std::to_string(i + 1) + " = (" + writer.print(eq.m_drift[i]) + ") dt\n";
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j)
        out += "d" + vars.text_name(vars.P(i, j)) + " = (" + join_parts(writer, P_parts(eq, vars.upper_index(i, j))) +
               ") dt\n";
    for (std::size_t q = 0; q < eq.higher_drift.size(); ++q)
      out += "d" + vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q)) + " = (" +
             writer.print(eq.higher_drift[q]) + ") dt\n";
  } else {
    out += "prediction over one sub-step dt (exact moments of x + f dt + g sqrt(dt) xi; dP terms: [" +
           moment_terms_text(eq) + "] + [diffusion], then Cov(f)):\n";
    for (std::size_t i = 0; i < n; ++i) {
      const std::string m = vars.text_name(vars.m(i));
      out += m + "' = " + m + " + (" + writer.print(eq.m_drift[i]) + ") dt\n";
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) {
        const std::size_t k = vars.upper_index(i, j);
        const std::string P = vars.text_name(vars.P(i, j));
        out += P + "' = " + P + " + (" + join_parts(writer, P_parts(eq, k)) + ") dt + (" +
               writer.print(eq.P_euler[k]) + ") dt^2\n";
      }
  }
  out += "\nupdate at each sample y = (";
  for (std::size_t a = 0; a < r; ++a) out += (a ? ", " : "") + std::string("y") + std::to_string(a + 1);
  out += "), " + rate.update_text(u) + ":\n";
  for (std::size_t a = 0; a < r; ++a)
    out += "h" + std::to_string(a + 1) + " = " + writer.print(eq.predicted_observation[a]) + "\n";
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a)
      out += "PCt" + index2(i, a) + " = " + writer.print(u.PCt[i][a]) + "\n";
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b)
      out += "Pyy" + index2(a, b) + " = " + writer.print(u.S[u.upper_index(a, b)]) + "\n";
  for (std::size_t q = 0; q < u.joint.size(); ++q)
    out += joint_name(u.joint_indices[q], n + r, false) + " = " + writer.print(u.joint[q]) + "\n";
  out += "K = PCt Pyy^-1\n";
  out += "m <- m + K (y - h)\n";
  out += moment_update_text(vars, u);
  out += "C = [";
  for (std::size_t a = 0; a < r; ++a) {
    out += a ? "; " : "";
    for (std::size_t k = 0; k < n; ++k) out += (k ? ", " : "") + writer.print(u.C[a][k]);
  }
  out += "], R = [";
  for (std::size_t a = 0; a < r; ++a) {
    out += a ? "; " : "";
    for (std::size_t b = 0; b < r; ++b) out += (b ? ", " : "") + writer.print(u.R[u.upper_index(a, b)]);
  }
  return out + "]\n" + realisability_text(eq, writer);
}

std::string sampled_equations_latex(const Model& model, const FilterEquations& eq) {
  LatexPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.latex_name(v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  std::string out = exactness_latex(eq.exactness);
  auto block = [&](const std::vector<std::string>& lines) {
    std::string text = "\\begin{align*}\n";
    for (std::size_t k = 0; k < lines.size(); ++k) text += lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "\n");
    return text + "\\end{align*}\n";
  };
  std::vector<std::string> prediction;
  const bool euler = !eq.P_euler.empty();
  out += euler ? "\\paragraph{Prediction over one sub-step $\\Delta = T/" + std::to_string(u.substeps) +
                     "$} (exact moments of $x + f\\Delta + g\\sqrt{\\Delta}\\,\\xi$" +
                     substep_reason(u, "; ", "") + "):\n"
               : "\\paragraph{Prediction between samples} ($" + std::to_string(u.substeps) +
                     "$ sub-steps per period $T = " + printer.print(u.period) + "$, no observation term" +
                     substep_reason(u, "; ", "") + "):\n";
  for (std::size_t i = 0; i < n; ++i) {
    const std::string m = vars.latex_name(vars.m(i));
    prediction.push_back(euler ? latex_align_lines(m + "'", m + " + \\left(" + writer.print(eq.m_drift[i]) + "\\right)\\Delta")
                               : latex_align_lines("\\frac{d" + m + "}{dt}", writer.print(eq.m_drift[i])));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t k = vars.upper_index(i, j);
      const std::string P = vars.latex_name(vars.P(i, j));
      prediction.push_back(euler ? latex_align_lines(P + "'", P + " + \\left(" + join_parts(writer, P_parts(eq, k)) +
                                                                  "\\right)\\Delta + \\left(" + writer.print(eq.P_euler[k]) +
                                                                  "\\right)\\Delta^{2}")
                                 : latex_align_lines("\\frac{d" + P + "}{dt}", join_parts(writer, P_parts(eq, k))));
    }
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q)
    prediction.push_back(latex_align_lines(
        "\\frac{d" + vars.latex_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q)) + "}{dt}",
        writer.print(eq.higher_drift[q])));
  out += block(prediction);
  out += "\\paragraph{Update at each sample} (" + sample_rate_report(model.observation.rate()).update_latex(u) + "):\n";
  std::vector<std::string> update;
  for (std::size_t a = 0; a < r; ++a)
    update.push_back(latex_align_lines("h_{" + std::to_string(a + 1) + "}", writer.print(eq.predicted_observation[a])));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < r; ++a)
      update.push_back(latex_align_lines("(P C^{T})_{" + std::to_string(i + 1) + "," + std::to_string(a + 1) + "}",
                                         writer.print(u.PCt[i][a])));
  for (std::size_t a = 0; a < r; ++a)
    for (std::size_t b = a; b < r; ++b)
      update.push_back(latex_align_lines("S_{" + std::to_string(a + 1) + "," + std::to_string(b + 1) + "}",
                                         writer.print(u.S[u.upper_index(a, b)])));
  for (std::size_t q = 0; q < u.joint.size(); ++q)
    update.push_back(latex_align_lines(joint_name(u.joint_indices[q], n + r, true), writer.print(u.joint[q])));
  update.push_back(u.closed_law ? "K &= P C^{T} S^{-1}, \\quad m \\leftarrow m + K (y - h), \\quad "
                                  "P \\leftarrow \\bar{A} Z \\bar{A}^{T} + K R K^{T}"
                                : "K &= P C^{T} S^{-1}, \\quad m \\leftarrow m + K (y - h), \\quad "
                                  "P \\leftarrow (I - K C) P (I - K C)^{T} + K R K^{T}");
  for (std::string& line : moment_update_latex(vars, u)) update.push_back(std::move(line));
  out += block(update);
  return out + realisability_latex(eq, writer);
}

Json sampled_equations_json(const Model& model, const FilterEquations& eq) {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();
  const SampledUpdate& u = eq.update;
  const std::size_t r = u.r();
  auto text = [&](const Polynomial& p) { return Json::string(writer.print(p)); };
  auto full = [&](const std::vector<Polynomial>& upper, std::size_t size, auto index) {
    Json rows = Json::array();
    for (std::size_t i = 0; i < size; ++i) {
      Json row = Json::array();
      for (std::size_t j = 0; j < size; ++j) row.push(text(upper[index(i, j)]));
      rows.push(row);
    }
    return rows;
  };
  auto P_index = [&](std::size_t i, std::size_t j) { return vars.upper_index(i, j); };
  auto S_index = [&](std::size_t a, std::size_t b) { return u.upper_index(a, b); };

  const Json exactness = exactness_json(eq.exactness);
  Json variables = Json::array();
  for (std::size_t v = 0; v < vars.count(); ++v) variables.push(Json::string(vars.text_name(static_cast<std::uint32_t>(v))));

  Json prediction = Json::object();
  prediction.add("form", Json::string(eq.P_euler.empty() ? "ode" : "euler-map"));
  Json m_drift = Json::array();
  for (const auto& p : eq.m_drift) m_drift.push(text(p));
  prediction.add("m_drift", m_drift);
  std::vector<Polynomial> P_drift;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) P_drift.push_back(eq.P_drift(i, j));
  prediction.add("P_drift", full(P_drift, n, P_index));
  if (!eq.P_euler.empty()) prediction.add("P_dt2", full(eq.P_euler, n, P_index));

  Json update = Json::object();
  Json h = Json::array();
  for (const auto& p : eq.predicted_observation) h.push(text(p));
  update.add("predicted_observation", h);
  Json PCt = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    Json row = Json::array();
    for (std::size_t a = 0; a < r; ++a) row.push(text(u.PCt[i][a]));
    PCt.push(row);
  }
  update.add("PCt", PCt);
  update.add("S", full(u.S, r, S_index));
  update.add("gain", Json::string("PCt S^-1"));
  update.add("covariance", Json::string(u.closed_law ? "Abar Z2 Abar^T + K R K^T" : "(I - K C) P (I - K C)^T + K R K^T"));
  if (!vars.higher_moments().empty()) update.add("moments", Json::string(moment_update_formula(vars, u)));
  if (u.closed_law) {
    Json joint = Json::object();
    for (std::size_t q = 0; q < u.joint.size(); ++q) joint.add(joint_name(u.joint_indices[q], n + r, false), text(u.joint[q]));
    update.add("joint_moments", joint);
  }
  Json C = Json::array();
  for (std::size_t a = 0; a < r; ++a) {
    Json row = Json::array();
    for (std::size_t k = 0; k < n; ++k) row.push(text(u.C[a][k]));
    C.push(row);
  }
  update.add("C", C);
  update.add("R", full(u.R, r, S_index));
  sample_rate_report(model.observation.rate()).add_update_json(model, u, printer, update);

  Json out = Json::object();
  out.add("model", Json::string(model.name));
  add_noise_json(model, out);
  out.add("filter", Json::string(eq.name));
  out.add("description", Json::string(rich_text_plain(eq.description)));
  out.add("exactness", exactness);
  out.add("variables", variables);
  out.add("period", Json::string(printer.print(u.period)));
  out.add("substeps", Json::integer(u.substeps));
  out.add("substeps_chosen", Json::boolean(u.substeps_chosen));
  out.add("prediction", prediction);
  out.add("update", update);
  add_moments_json(eq, writer, out);
  return out;
}

class SampledReport final : public ObservationReport, public ObservationStatement {
 public:
  // The whole report at once: a sampled filter's is small (its update is written out per sample
  // output, not per term of a large model's P equations).
  std::string text(const Model& model, const FilterEquations& eq, std::ostream*) const override {
    return sampled_equations_text(model, eq);
  }
  std::string latex(const Model& model, const FilterEquations& eq) const override {
    return sampled_equations_latex(model, eq);
  }
  Json json(const Model& model, const FilterEquations& eq) const override { return sampled_equations_json(model, eq); }

  // The samples' equation beside dx's, their matrices (or c) below it.
  std::string equation_latex(const Model& model) const override {
    return sample_rate_report(model.observation.rate()).equation_latex();
  }

  std::string matrices_latex(const Model& model) const override {
    LatexPrinter printer;
    const std::string period = printer.print(model.observation.samples()->period);
    return sample_rate_report(model.observation.rate()).matrices_latex(model, printer, period);
  }

  std::string notation_latex() const override {
    return "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state and $P_{ij}$ the error covariance. "
           "Between samples $m$ and $P$ follow the prediction; at each sample $y$ the Kalman update with "
           "$S = C P C^{T} + U_v U_v^{T}$ and $K = P C^{T} S^{-1}$ applies.";
  }

  std::string coefficients_text(const Model&) const override {
    return "observation: sampled, y_k = C0 + C x(t_k) + Uv v_k; it has no rate E + E1 x, its C0 and C are shown\n";
  }

  std::string coefficients_latex(const Model&) const override {
    return "The observation is sampled, $y_k = C_0 + C x(t_k) + U_v v_k$: it has no rate $E + E_{1} x$; "
           "its $C_0$ and $C$ are shown.";
  }

  CoefficientNames coefficient_names() const override { return {"C0", "C", "C_{0}", "C", "C"}; }

  void add_coefficients_json(const Model&, Json&) const override {}
};

const SampledReport& sampled_part() {
  static const SampledReport part;
  return part;
}

}  // namespace

const ObservationReport& sampled_observation_report() { return sampled_part(); }

const ObservationStatement& sampled_observation_statement() { return sampled_part(); }

}  // namespace pfgen
