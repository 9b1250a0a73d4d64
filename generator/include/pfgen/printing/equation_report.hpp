#pragma once
// Renders one filter's equations for `pfgen derive`: text, a LaTeX fragment (the
// exactness diagnostic as a paragraph, then an align* block) and
// JSON. All three list the same things in the same order: the exactness
// diagnostic, dm (drift and innovation gain), the gain entries, and dP for the
// upper triangle of P. In text and LaTeX each dP is written as its three parts
// in turn, E[(x-m)f^T] + E[f(x-m)^T], then E[g g^T], then - P A^T R^-1 A P, so
// it reads like the published equations; JSON gives each entry combined.
// A filter for delayed observations adds what delayed_report.hpp lists (h, the meaning of m(t-h),
// Phi* and x*'s equations); sampled filters are handed to sampled_report.hpp.
#include <iosfwd>
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

std::string equations_text(const Model& model, const FilterEquations& eq);
// The same bytes written to `out` equation by equation, never holding the whole report
// (a dense cubic n = 20 report is 63 MB).
void write_equations_text(std::ostream& out, const Model& model, const FilterEquations& eq);
std::string equations_latex(const FilterEquations& eq);
Json equations_json(const Model& model, const FilterEquations& eq);

}  // namespace pfgen
