#pragma once
// What every report of a moment filter (closure3, closure4 and their sampled forms cd-closure3, cd-closure4)
// says about the moments it carries beyond m and P, whatever its observation: the header line naming them,
// the realisability margins as text, LaTeX and JSON, and the JSON keys of the moments' equations.
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/notation/polynomial_writer.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// "central moments: M3_ijl = ..." on the line after the variables; empty without higher moments.
std::string higher_moments_header_text(const FilterEquations& eq);

// "realisable while each is positive: ..." and its LaTeX sentence; empty without margins.
std::string realisability_text(const FilterEquations& eq, PolynomialWriter& writer);
std::string realisability_latex(const FilterEquations& eq, PolynomialWriter& writer);

// The keys "moments", "realisability", "moment_drift" and (with an observation rate) "moment_gain".
void add_moments_json(const FilterEquations& eq, PolynomialWriter& writer, Json& out);

}  // namespace pfgen
