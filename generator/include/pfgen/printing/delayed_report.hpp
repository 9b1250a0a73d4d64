#pragma once
// What a report of a filter for delayed observations (docs/theory.md §2.6) adds to the continuous
// report: the delay h and the observation dy = (A0 + A x(t-h)) dt + B dW2; what the delayed
// inputs md_i = m_i(t-h) mean (m0 for t < h); for the kinds with the Phi* gain the definition of
// phi_i = Phi*_ii and the auxiliary ODE dxs = f(xs, t) dt, xs(0) = m0. equation_report.cpp calls
// these only when FilterEquations::is_delayed(), so undelayed reports are unchanged.
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// The LaTeX name of a filter variable as the printers must use it: the delayed variables'
// names (\Phi^*_{1}, x^*_{1}, m_{1}(t-h)) in braces, so that a power of one, phi1^2 in the
// correction or xs1^2 in the x* drift, is {\Phi^*_{1}}^{2} and not a double superscript.
std::string latex_variable_name(const FilterVariables& vars, std::uint32_t variable);

// Text: the header lines (observation and delayed inputs, each ending in "\n"), and the
// auxiliary ODE's equations "dxs1 = (...) dt\n" (empty without x*).
std::string delayed_header_text(const FilterEquations& eq);
std::string x_star_equations_text(const FilterEquations& eq);
// LaTeX: a paragraph with the same definitions, and the align* lines of the auxiliary ODE.
std::string delayed_paragraph_latex(const FilterEquations& eq);
std::vector<std::string> x_star_lines_latex(const FilterEquations& eq);
// JSON: adds "delay", "delayed_variables" ({name: definition}) and, with x*, "x_star_drift".
void add_delayed_json(const FilterEquations& eq, Json& out);

// The correction term's words: "P A^T (B B^T)^-1 A P", or with the Phi* gain
// "P Phi* A^T (B B^T)^-1 A Phi* P" (Phi* = diag(phi) is diagonal, so Phi*^T = Phi*).
std::string correction_words_text(const FilterEquations& eq);

}  // namespace pfgen
