#include "pfgen/printing/rate_report.hpp"

#include <ostream>
#include <sstream>

#include "pfgen/derivation/unscented.hpp"
#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/rich_text.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "pfgen/printing/definitions_report.hpp"
#include "pfgen/printing/moment_report.hpp"
#include "pfgen/printing/noise_report.hpp"
#include "pfgen/printing/report_parts.hpp"
#include "pfgen/printing/risk_report.hpp"

namespace pfgen {
namespace {

std::vector<ReportPart> P_parts(const FilterEquations& eq, std::size_t u) {
  return {{&eq.P_moment[u]}, {&eq.P_diffusion[u]}, {&eq.P_correction[u], true}};
}

bool is_single_term(const Polynomial& p) { return p.terms().size() <= 1; }

// The ukf's points and weights (docs/theory.md §2.8) and its dP terms, sums over the points.
std::string sigma_point_header_text(const FilterEquations& eq, const std::string& correction_words) {
  const SigmaPointWeights w = sigma_point_weights(eq.n());
  std::ostringstream c, w0, wi;
  c << w.c;
  w0 << w.w0;
  wi << w.w;
  return "sigma points: X_0 = m, X_j = m + sqrt(" + c.str() + ") L_j, X_(n+j) = m - sqrt(" + c.str() +
         ") L_j (j = 1.." + std::to_string(eq.n()) + ", L_j column j of L, L L^T = P: the definitions below); weights w_0 = " +
         w0.str() + ", w_i = " + wi.str() + "\n" +
         "dP terms: [sum_i w_i ((X_i-m) f(X_i)^T + f(X_i) (X_i-m)^T)] + [sum_i w_i g(X_i) g(X_i)^T] - [" +
         correction_words + "]\n\n";
}

// The same in LaTeX, before the equations.
std::string sigma_point_paragraph_latex(const FilterEquations& eq, const std::string& correction) {
  const SigmaPointWeights w = sigma_point_weights(eq.n());
  const LatexPrinter printer;
  const std::string c = printer.print(w.c);
  return "\\noindent Unscented filter: sigma points $X_0 = m$, $X_j = m + \\sqrt{" + c + "}\\,L_j$, $X_{n+j} = m - \\sqrt{" +
         c + "}\\,L_j$ ($j = 1, \\ldots, " + std::to_string(eq.n()) +
         "$; $L_j$ the $j$-th column of the Cholesky factor $L$ of $P$, $L L^T = P$, whose entries are defined "
         "below), weights $w_0 = " + printer.print(w.w0) + "$, $w_i = " + printer.print(w.w) +
         "$; $dP/dt = \\sum_i w_i \\left((X_i - m) f(X_i)^T + f(X_i) (X_i - m)^T + g(X_i) g(X_i)^T\\right) - " +
         correction + "$.\n\n";
}

// The words for dP's observation term: a moment filter's cross-covariance C = E[(x-m) h^T] holds the higher
// moments, so it is no P E[J_h]^T.
std::string closure_correction_words(const FilterEquations& eq, const std::string& module_words) {
  return eq.kind && uses_cumulant_closure(*eq.kind) ? "C (B B^T)^-1 C^T, C = E[(x-m) h^T]" : module_words;
}

// The variables line (m = E[x], P its covariance), the observation's header lines and which terms
// make up dP.
std::string mean_square_header_text(const Model& model, const FilterEquations& eq, const std::string& observation_lines,
                                    const std::string& correction_words) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  std::string out = "variables: ";
  for (std::size_t i = 0; i < n; ++i)
    out += (i ? ", " : "") + vars.text_name(vars.m(i)) + " = E[" + model.state_names[i] + "]";
  out += "; P = covariance of (";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + model.state_names[i];
  out += ")\n";
  out += higher_moments_header_text(eq);
  out += observation_lines;
  if (eq.kind && uses_sigma_points(*eq.kind)) return out + sigma_point_header_text(eq, correction_words);
  out += eq.is_user_filter() ? "dP terms: as given in the model file\n\n"
                              : "dP terms: [" + moment_terms_text(eq) + "] + [diffusion] - [" +
                                    closure_correction_words(eq, correction_words) + "]\n\n";
  return out;
}

// A polynomial observation's dP_ij has a dy term: L_ij,r, named after P_ij ("L11_1", "L1_10_1"; in
// LaTeX "L_{11,1}"). Whether entry u has any (empty P_gain: no entry has).
bool has_P_gain(const FilterEquations& eq, std::size_t u) {
  if (eq.P_gain.empty()) return false;
  for (const Polynomial& L : eq.P_gain[u])
    if (!L.is_zero()) return true;
  return false;
}

std::string L_text_name(const FilterVariables& vars, std::size_t i, std::size_t j, std::size_t r) {
  return "L" + vars.text_name(vars.P(i, j)).substr(1) + "_" + std::to_string(r + 1);
}

std::string L_latex_name(const FilterVariables& vars, std::size_t i, std::size_t j, std::size_t r) {
  const std::string P = vars.latex_name(vars.P(i, j));  // "P_{11}"
  return "L_{" + P.substr(3, P.size() - 4) + "," + std::to_string(r + 1) + "}";
}

// A higher moment's dy term: L, then its name without the M ("L3_112_1"; LaTeX "L^{\mu}_{112,1}").
std::string moment_L_text_name(const FilterVariables& vars, std::uint32_t v, std::size_t r) {
  return "L" + vars.text_name(v).substr(1) + "_" + std::to_string(r + 1);
}

std::string moment_L_latex_name(const FilterVariables& vars, std::uint32_t v, std::size_t r) {
  const std::string mu = vars.latex_name(v);  // "\mu_{112}"
  return "L^{\\mu}_{" + mu.substr(5, mu.size() - 6) + "," + std::to_string(r + 1) + "}";
}

bool has_gain(const std::vector<std::vector<Polynomial>>& gains, std::size_t q) {
  if (gains.empty()) return false;
  for (const Polynomial& L : gains[q])
    if (!L.is_zero()) return true;
  return false;
}

// With a sink, `out` is written to it whenever it passes a megabyte.
void drain(std::string& out, std::ostream* sink) {
  if (sink == nullptr || out.size() < (1u << 20)) return;
  sink->write(out.data(), static_cast<std::streamsize>(out.size()));
  out.clear();
}

}  // namespace

std::string RateReport::sigma_point_correction_latex(const FilterEquations&) const { return "P A^T (B B^T)^{-1} A P"; }
std::string RateReport::header_text(const FilterEquations&) const { return {}; }
std::string RateReport::trailing_text(const FilterEquations&) const { return {}; }
std::string RateReport::paragraph_latex(const FilterEquations&) const { return {}; }
std::vector<std::string> RateReport::trailing_latex(const FilterEquations&) const { return {}; }
void RateReport::add_json(const FilterEquations&, Json&) const {}

std::string RateReport::text(const Model& model, const FilterEquations& eq, std::ostream* sink) const {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();
  const std::vector<Polynomial>& h = eq.predicted_observation;

  std::string out;
  out += "model: " + model.name + "\n";
  out += noise_text(model);
  out += "filter: " + eq.name + " (" + rich_text_plain(eq.description) + ")\n";
  out += "exactness: " + exactness_text(eq.exactness) + "\n";
  out += is_risk_sensitive_report(eq)
             ? risk_header_text(model, eq)
             : mean_square_header_text(model, eq, header_text(eq), correction_words_text(eq));
  out += definitions_text(eq);
  // Each innovation "(dyr - h dt)" printed once: every dm line, and a dP line with a dy term, reads it.
  std::vector<std::string> innovation;
  for (std::size_t r = 0; r < eq.p; ++r) {
    const std::string predicted = writer.print(h[r]);
    innovation.push_back(" (dy" + std::to_string(r + 1) + " - " +
                         (is_single_term(h[r]) ? predicted : "(" + predicted + ")") + " dt)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    out += "dm" + std::to_string(i + 1) + " = (";
    writer.append(out, eq.m_drift[i]);
    out += ") dt";
    for (std::size_t r = 0; r < eq.p; ++r)
      out += " + K" + std::to_string(i + 1) + "_" + std::to_string(r + 1) + innovation[r];
    out += "\n";
    drain(out, sink);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < eq.p; ++r) {
      out += "K" + std::to_string(i + 1) + "_" + std::to_string(r + 1) + " = " + writer.print(eq.gain[i][r]) + "\n";
      drain(out, sink);
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t u = vars.upper_index(i, j);
      out += "d" + vars.text_name(vars.P(i, j)) + " = (";
      append_parts(out, writer, P_parts(eq, u));
      out += ") dt";
      if (has_P_gain(eq, u))
        for (std::size_t r = 0; r < eq.p; ++r)
          if (!eq.P_gain[u][r].is_zero()) out += " + " + L_text_name(vars, i, j, r) + innovation[r];
      out += "\n";
      drain(out, sink);
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      if (has_P_gain(eq, vars.upper_index(i, j)))
        for (std::size_t r = 0; r < eq.p; ++r)
          if (!eq.P_gain[vars.upper_index(i, j)][r].is_zero()) {
            out += L_text_name(vars, i, j, r) + " = " + writer.print(eq.P_gain[vars.upper_index(i, j)][r]) + "\n";
            drain(out, sink);
          }
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q) {
    const std::uint32_t v = vars.first_higher_moment() + static_cast<std::uint32_t>(q);
    out += "d" + vars.text_name(v) + " = (";
    writer.append(out, eq.higher_drift[q]);
    out += ") dt";
    for (std::size_t r = 0; r < eq.p && has_gain(eq.higher_gain, q); ++r)
      if (!eq.higher_gain[q][r].is_zero()) out += " + " + moment_L_text_name(vars, v, r) + innovation[r];
    out += "\n";
    drain(out, sink);
  }
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q)
    for (std::size_t r = 0; r < eq.p && has_gain(eq.higher_gain, q); ++r)
      if (!eq.higher_gain[q][r].is_zero()) {
        const std::uint32_t v = vars.first_higher_moment() + static_cast<std::uint32_t>(q);
        out += moment_L_text_name(vars, v, r) + " = " + writer.print(eq.higher_gain[q][r]) + "\n";
        drain(out, sink);
      }
  out += realisability_text(eq, writer);
  out += trailing_text(eq);
  return out;
}

std::string RateReport::latex(const Model&, const FilterEquations& eq) const {
  LatexPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return latex_variable_name(vars, v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();
  const std::vector<Polynomial>& h = eq.predicted_observation;
  auto K = [](std::size_t i, std::size_t r) { return "K_{" + std::to_string(i + 1) + "," + std::to_string(r + 1) + "}"; };

  std::string out = exactness_latex(eq.exactness);
  out += paragraph_latex(eq);
  if (is_risk_sensitive_report(eq)) out += risk_paragraph_latex(eq);
  if (eq.kind && uses_sigma_points(*eq.kind)) out += sigma_point_paragraph_latex(eq, sigma_point_correction_latex(eq));
  out += "\\begin{align*}\n";
  // Each right-hand side is cut into lines that fit the page (latex_line_breaker).
  std::vector<std::string> lines = definitions_latex_lines(eq);
  // Each innovation printed once, for the dm lines and any dP line with a dy term.
  std::vector<std::string> innovation;
  for (std::size_t r = 0; r < eq.p; ++r) {
    const std::string predicted = writer.print(h[r]);
    innovation.push_back("\\left(dy_{" + std::to_string(r + 1) + "} - " +
                         (is_single_term(h[r]) ? predicted : "\\left(" + predicted + "\\right)") + "\\,dt\\right)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::string rhs = "\\left(" + writer.print(eq.m_drift[i]) + "\\right)dt";
    for (std::size_t r = 0; r < eq.p; ++r) rhs += " + " + K(i, r) + innovation[r];
    lines.push_back(latex_align_lines("dm_{" + std::to_string(i + 1) + "}", rhs));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < eq.p; ++r) lines.push_back(latex_align_lines(K(i, r), writer.print(eq.gain[i][r])));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      const std::size_t u = vars.upper_index(i, j);
      if (!has_P_gain(eq, u)) {
        lines.push_back(latex_align_lines("\\frac{d" + vars.latex_name(vars.P(i, j)) + "}{dt}",
                                          join_parts(writer, P_parts(eq, u))));
        continue;
      }
      // With a dy term dP is not a rate: written as dm is.
      std::string rhs = "\\left(" + join_parts(writer, P_parts(eq, u)) + "\\right)dt";
      for (std::size_t r = 0; r < eq.p; ++r)
        if (!eq.P_gain[u][r].is_zero()) rhs += " + " + L_latex_name(vars, i, j, r) + innovation[r];
      lines.push_back(latex_align_lines("d" + vars.latex_name(vars.P(i, j)), rhs));
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j)
      if (has_P_gain(eq, vars.upper_index(i, j)))
        for (std::size_t r = 0; r < eq.p; ++r)
          if (!eq.P_gain[vars.upper_index(i, j)][r].is_zero())
            lines.push_back(latex_align_lines(L_latex_name(vars, i, j, r), writer.print(eq.P_gain[vars.upper_index(i, j)][r])));
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q) {
    const std::uint32_t v = vars.first_higher_moment() + static_cast<std::uint32_t>(q);
    if (!has_gain(eq.higher_gain, q)) {
      lines.push_back(latex_align_lines("\\frac{d" + vars.latex_name(v) + "}{dt}", writer.print(eq.higher_drift[q])));
      continue;
    }
    std::string rhs = "\\left(" + writer.print(eq.higher_drift[q]) + "\\right)dt";
    for (std::size_t r = 0; r < eq.p; ++r)
      if (!eq.higher_gain[q][r].is_zero()) rhs += " + " + moment_L_latex_name(vars, v, r) + innovation[r];
    lines.push_back(latex_align_lines("d" + vars.latex_name(v), rhs));
  }
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q)
    for (std::size_t r = 0; r < eq.p && has_gain(eq.higher_gain, q); ++r)
      if (!eq.higher_gain[q][r].is_zero())
        lines.push_back(latex_align_lines(
            moment_L_latex_name(vars, vars.first_higher_moment() + static_cast<std::uint32_t>(q), r),
            writer.print(eq.higher_gain[q][r])));
  for (std::string& line : trailing_latex(eq)) lines.push_back(std::move(line));
  for (std::size_t k = 0; k < lines.size(); ++k) out += lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "\n");
  out += "\\end{align*}\n";
  out += realisability_latex(eq, writer);
  return out;
}

Json RateReport::json(const Model& model, const FilterEquations& eq) const {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  PolynomialWriter writer(printer, name);
  const std::size_t n = eq.n();

  const Json exactness = exactness_json(eq.exactness);

  Json variables = Json::array();
  for (std::size_t v = 0; v < vars.count(); ++v) variables.push(Json::string(vars.text_name(static_cast<std::uint32_t>(v))));
  Json m_drift = Json::array();
  for (const auto& p : eq.m_drift) m_drift.push(Json::string(writer.print(p)));
  Json gain = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    Json row = Json::array();
    for (std::size_t r = 0; r < eq.p; ++r) row.push(Json::string(writer.print(eq.gain[i][r])));
    gain.push(row);
  }
  // P is symmetric and P_drift(i, j) is P_drift(j, i): each entry of the upper triangle is
  // summed and printed once, then written in both places of the full matrix.
  std::vector<Json> P_upper(n * (n + 1) / 2);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      std::string text;  // P_drift(i, j), merged as FilterEquations::P_drift sums it
      writer.append_sum(text, P_parts(eq, vars.upper_index(i, j)));
      P_upper[vars.upper_index(i, j)] = Json::string(std::move(text));
    }
  Json P_drift = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    Json row = Json::array();
    for (std::size_t j = 0; j < n; ++j) row.push(P_upper[vars.upper_index(i, j)]);
    P_drift.push(row);
  }
  Json predicted = Json::array();
  for (const auto& h : eq.predicted_observation) predicted.push(Json::string(writer.print(h)));

  Json out = Json::object();
  out.add("model", Json::string(model.name));
  add_noise_json(model, out);
  out.add("filter", Json::string(eq.name));
  out.add("description", Json::string(rich_text_plain(eq.description)));
  out.add("exactness", exactness);
  out.add("variables", variables);
  add_definitions_json(eq, out);
  out.add("m_drift", m_drift);
  out.add("gain", gain);
  out.add("predicted_observation", predicted);
  out.add("P_drift", P_drift);
  if (!eq.P_gain.empty()) {  // a polynomial observation's: per observation r, dP's coefficients of dy_r - E[h_r] dt
    Json P_gain = Json::array();
    for (std::size_t r = 0; r < eq.p; ++r) {
      Json matrix = Json::array();
      for (std::size_t i = 0; i < n; ++i) {
        Json row = Json::array();
        for (std::size_t j = 0; j < n; ++j) row.push(Json::string(writer.print(eq.P_gain[vars.upper_index(i, j)][r])));
        matrix.push(row);
      }
      P_gain.push(matrix);
    }
    out.add("P_gain", P_gain);
  }
  add_moments_json(eq, writer, out);  // a moment filter's central moments of order >= 3, in the state's order
  add_json(eq, out);
  if (is_risk_sensitive_report(eq)) add_risk_json(eq, out);
  return out;
}

}  // namespace pfgen
