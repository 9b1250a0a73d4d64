#include "pfgen/printing/moment_report.hpp"

namespace pfgen {

std::string higher_moments_header_text(const FilterEquations& eq) {
  if (eq.variables.higher_moments().empty()) return {};
  const std::string k = std::to_string(eq.variables.order());
  std::string out = "central moments: M3_ijl = E[(x-m)_i (x-m)_j (x-m)_l]";
  if (eq.variables.order() >= 4) out += ", M4_ijlq = E[(x-m)_i (x-m)_j (x-m)_l (x-m)_q]";
  out += eq.variables.order() >= 4 ? " (i <= j <= l <= q)" : " (i <= j <= l)";
  return out + "; moments above order " + k + " read as those of the law whose cumulants above order " +
         k + " are zero\n";
}

std::string realisability_text(const FilterEquations& eq, PolynomialWriter& writer) {
  if (eq.realisability.empty()) return {};
  std::string out = "realisable while each is positive:";
  for (std::size_t k = 0; k < eq.realisability.size(); ++k)
    out += std::string(k ? "," : "") + " " + writer.print(eq.realisability[k]) + " (" + eq.realisability_meaning[k] + ")";
  return out + "\n";
}

std::string realisability_latex(const FilterEquations& eq, PolynomialWriter& writer) {
  if (eq.realisability.empty()) return {};
  // The states' names may not be LaTeX: the margins are said by kind, in state order.
  std::string out = "\\noindent Realisable while each is positive (each state's variance, $P$'s leading principal "
                    "minors, then each state's Pearson bound $\\mu_{4} P - P^{3} - \\mu_{3}^{2}$):";
  for (std::size_t k = 0; k < eq.realisability.size(); ++k)
    out += std::string(k ? "," : "") + " $" + writer.print(eq.realisability[k]) + "$";
  return out + ".\n";
}

void add_moments_json(const FilterEquations& eq, PolynomialWriter& writer, Json& out) {
  if (eq.higher_drift.empty()) return;
  const FilterVariables& vars = eq.variables;
  Json names = Json::array(), drift = Json::array(), gains = Json::array();
  for (std::size_t q = 0; q < eq.higher_drift.size(); ++q) {
    names.push(Json::string(vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q))));
    drift.push(Json::string(writer.print(eq.higher_drift[q])));
    Json row = Json::array();
    for (std::size_t r = 0; r < eq.p && !eq.higher_gain.empty(); ++r) row.push(Json::string(writer.print(eq.higher_gain[q][r])));
    gains.push(row);
  }
  out.add("moments", names);
  Json margins = Json::array();
  for (const Polynomial& margin : eq.realisability) margins.push(Json::string(writer.print(margin)));
  out.add("realisability", margins);
  out.add("moment_drift", drift);
  if (!eq.higher_gain.empty()) out.add("moment_gain", gains);
}

}  // namespace pfgen
