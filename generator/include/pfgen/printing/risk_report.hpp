#pragma once
// What a report of the risk-sensitive kind (docs/theory.md §2.7) says in place of the
// mean-square kinds' header: the criterion J with its epsilon and weight M, that m is the
// risk-sensitive estimate (the centre of the information state) and not E[x], and which terms make
// up dP. equation_report.cpp calls these only for that kind, so other reports are unchanged.
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

bool is_risk_sensitive_report(const FilterEquations& eq);
// Text: the "criterion:", "variables:" and "dP terms:" lines, each ending in "\n", the last in "\n\n".
std::string risk_header_text(const Model& model, const FilterEquations& eq);
// LaTeX: a paragraph with the criterion and the meaning of m and P.
std::string risk_paragraph_latex(const FilterEquations& eq);
// JSON: adds "criterion": {"J", "epsilon", "weight"}.
void add_risk_json(const FilterEquations& eq, Json& out);

}  // namespace pfgen
