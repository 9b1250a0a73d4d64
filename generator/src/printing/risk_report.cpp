#include "pfgen/printing/risk_report.hpp"

#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/text_printer.hpp"

namespace pfgen {
namespace {

const char* const kCriterionText = "J = eps log E[exp(eps^-1 int_0^T L dt)], L = (x-m)^T M (x-m)";

std::string weight_text(const ExpressionPrinter& printer, const ExMatrix& M) {
  std::string out = "[";
  for (std::size_t i = 0; i < M.size(); ++i) {
    out += i ? ", [" : "[";
    for (std::size_t j = 0; j < M[i].size(); ++j) out += (j ? ", " : "") + printer.print(M[i][j]);
    out += "]";
  }
  return out + "]";
}

}  // namespace

bool is_risk_sensitive_report(const FilterEquations& eq) { return eq.kind && is_risk_sensitive(*eq.kind); }

std::string risk_header_text(const Model& model, const FilterEquations& eq) {
  const TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  std::string out = "criterion: " + std::string(kCriterionText) + ", eps = " + printer.print(eq.risk->epsilon) +
                    ", M = " + weight_text(printer, eq.risk->weight) + "\n";
  out += "variables: ";
  for (std::size_t i = 0; i < eq.n(); ++i)
    out += (i ? ", " : "") + vars.text_name(vars.m(i)) + " = risk-sensitive estimate of " + model.state_names[i];
  out += " (the centre of the information state, not E[x]); P = its spread (the information state is "
         "exp(-1/2 (x-m)^T P^-1 (x-m)) to second order)\n";
  out += "dP terms: [J P + P J^T, J = df/dx at m] + [diffusion] - [P (A^T (B B^T)^-1 A + Hess(div f)(m) - (2/eps) M) P]\n\n";
  return out;
}

std::string risk_paragraph_latex(const FilterEquations& eq) {
  const LatexPrinter printer;
  return "\\noindent Risk-sensitive filter for the criterion "
         "$J = \\varepsilon \\log E\\left[\\exp\\left(\\varepsilon^{-1}\\int_0^T (x-m)^T M (x-m)\\,dt\\right)\\right]$ "
         "with $\\varepsilon = " + printer.print(eq.risk->epsilon) +
         "$: $m$ is the centre of the information state, not $E[x]$, and the covariance equation is "
         "$J P + P J^T + G - P\\left(A^T (B B^T)^{-1} A + \\nabla^2(\\operatorname{div} f)(m) - "
         "\\tfrac{2}{\\varepsilon} M\\right) P$ with $J = \\partial f / \\partial x$ at $m$.\n\n";
}

void add_risk_json(const FilterEquations& eq, Json& out) {
  const TextPrinter printer;
  Json criterion = Json::object();
  criterion.add("J", Json::string(kCriterionText));
  criterion.add("epsilon", Json::string(printer.print(eq.risk->epsilon)));
  Json weight = Json::array();
  for (const auto& row : eq.risk->weight) {
    Json entries = Json::array();
    for (const auto& e : row) entries.push(Json::string(printer.print(e)));
    weight.push(entries);
  }
  criterion.add("weight", weight);
  out.add("criterion", criterion);
}

}  // namespace pfgen
