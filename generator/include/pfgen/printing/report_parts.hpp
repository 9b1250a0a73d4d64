#pragma once
// Pieces every filter report shares, whatever its observation: a sum printed part by part, the
// exactness diagnostic as text, LaTeX and JSON, and the filter variables' LaTeX names.
#include <string>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/exactness.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/notation/polynomial_writer.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// One part of a sum: the polynomial, or its negative (the correction of dP), unbuilt.
using ReportPart = SignedPolynomial;

// "a + b - c" from parts printed separately, so like terms of different parts (0.03*P11^2 from
// E[gg^T] and -P11^2 from the correction) stay visible; "0" when every part is zero.
std::string join_parts(PolynomialWriter& writer, const std::vector<ReportPart>& parts);
// The same, appended to `out` (a report of a large model is tens of megabytes: no copies).
void append_parts(std::string& out, PolynomialWriter& writer, const std::vector<ReportPart>& parts);

// What the first of dP's terms is, as the "dP terms:" lines say it: E[(x-m)f^T] + E[f(x-m)^T] for
// the Gaussian closure, J P + P J^T with J the Jacobian of f at m for the extended filters.
std::string moment_terms_text(const FilterEquations& eq);

// The explanation, then one "\n  failed: ..." line per failed condition.
std::string exactness_text(const ExactnessReport& report);
// "\noindent\textbf{Exactness:} ...", then the failed conditions as an itemize list.
std::string exactness_latex(const ExactnessReport& report);
// {exact, condition, explanation, failed}.
Json exactness_json(const ExactnessReport& report);

// The LaTeX name of a filter variable as the printers must use it: a variable after m and P (a
// delayed filter's \Phi^*_{1}, x^*_{1}, m_{1}(t-h)) in braces, so that a power of one, phi1^2 in
// the correction or xs1^2 in the x* drift, is {\Phi^*_{1}}^{2} and not a double superscript.
std::string latex_variable_name(const FilterVariables& vars, std::uint32_t variable);

}  // namespace pfgen
