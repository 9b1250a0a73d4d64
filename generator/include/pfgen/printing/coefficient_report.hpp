#pragma once
// Renders a model's coefficient form (derivation/drift_coefficients.hpp) for
// `pfgen derive --coefficients` and `pfgen latex --coefficients`: text, a LaTeX fragment and JSON.
// Each starts with the convention, then lists A and A1 whole, the nonzero entries of A2 and A3
// (every order of the lower indices, indices from 1, in lexicographic order), then the
// observation's E and E1 (or a sampled observation's C0 and C, under those names).
#include <string>

#include "pfgen/derivation/drift_coefficients.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

std::string coefficients_text(const Model& model, const DriftCoefficients& drift,
                              const ObservationCoefficients& observation);
// A paragraph stating the convention, then an align* block.
std::string coefficients_latex(const Model& model, const DriftCoefficients& drift,
                               const ObservationCoefficients& observation);
// Dense A, A1, E, E1 (arrays of expression texts); A2 and A3 as lists of
// {"index": [i, j, k], "value": "..."} with 1-based indices.
Json coefficients_json(const Model& model, const DriftCoefficients& drift, const ObservationCoefficients& observation);

}  // namespace pfgen
