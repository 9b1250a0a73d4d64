#pragma once
// Renders one filter's equations for `pfgen derive`: text, a LaTeX fragment (the
// exactness diagnostic as a paragraph, then align* blocks) and JSON. What the report holds depends
// on how the states are observed, so each is its observation module's (printing/observation_report.hpp):
// continuous and delayed observations' reports are the rate form (rate_report.hpp), dm with the
// innovation gain, the gain entries and dP part by part, a delayed filter's with what
// observations/delayed/delayed_report.cpp adds (h, the meaning of m(t-h), Phi* and x*'s
// equations); a sampled filter's shows its prediction and its update apart
// (observations/sampled/sampled_report.cpp).
#include <iosfwd>
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

std::string equations_text(const Model& model, const FilterEquations& eq);
// The same bytes written to `out` equation by equation, never holding the whole report
// (a dense cubic n = 20 report is 63 MB).
void write_equations_text(std::ostream& out, const Model& model, const FilterEquations& eq);
std::string equations_latex(const Model& model, const FilterEquations& eq);
Json equations_json(const Model& model, const FilterEquations& eq);

}  // namespace pfgen
