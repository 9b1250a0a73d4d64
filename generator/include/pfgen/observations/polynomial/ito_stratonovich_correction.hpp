#pragma once
// The drift correction between the Ito and the Stratonovich reading of a filter driven by the
// observation, for filters whose noise coefficient depends on the filter's own state
// (docs/theory.md, "Polynomial observations"). With s the filter variables (m, then P's upper
// triangle: FilterVariables' numbering) and
//   ds = F(s) dt + sigma(s) dnu,     dnu = dy - yhat(s) dt,   d<y_r, y_q> = R_rq dt,
// the Stratonovich equation with the same solution is ds = (F - c) dt + sigma o dnu, where
//   c_v = 1/2 sum_{r,q} R_rq sum_u (d sigma_vr / d s_u) sigma_uq.
// A scheme that treats the increment of y as given across a step (Heun's, as the generated step
// takes it) converges to the Stratonovich solution: stepping F - c instead of F makes it converge
// to the Ito filter. For a linear observation c = 0 (sigma reads P only, and P has no dnu term:
// docs/theory.md §7.1).
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

// `noise`: one row per filter variable u in 0..vars.count()-1, p entries each (sigma_u,r);
// `B`: p x q, R = B B^T. Returns c, one polynomial per filter variable.
std::vector<Polynomial> ito_stratonovich_correction(const std::vector<std::vector<Polynomial>>& noise,
                                                    const ExMatrix& B, const FilterVariables& vars);

}  // namespace pfgen
