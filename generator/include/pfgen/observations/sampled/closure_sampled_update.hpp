#pragma once
// A moment filter's update at a sample through a polynomial c (cd-closure3, cd-closure4; docs/theory.md §2.10):
// the moments of the law of x+ = x + K (y - c(x) - v) under the filter's closed law, v ~ N(0, R) independent of x,
// K the gain that moment matching gives (K = Cov(x, c) S^-1, S = Cov(c) + R). Write e = x - m, C = E[J_c] and
// d = c(x) - E[c] - C e, the part of the sample that C e does not explain (0 for C0 + C x). Then
//   x+ - m+ = A e - K d - K v = Abar z - K v,   A = I - K C,   Abar = [A, -K],   z = (e, d),
// and every central moment of x+ is a contraction of z's joint central moments with Abar, plus v's terms: the linear
// update's formulas (sampled_moment_update.hpp) with A replaced by Abar and the moments of e by those of z,
// P+ = Abar Z2 Abar^T + K R K^T included. cd-optimal's Joseph form (C = E[J_c], R_c) does not give P+ here: under
// a non-Gaussian law Cov(x, c) = P C^T + Cov(e, d), and Cov(e, d) is not zero (a Joseph form with the slope
// Cov(c, x) P^-1 would, but the higher moments need z's anyway).
//
// The derivation returns z's joint moments that are not the filter's own (an index of d among the indices), each a
// polynomial in the filter variables (ClosedExpectation); the gain's parts, the predicted sample E[c], C and R.
#include <string>
#include <vector>

#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/derivation/sampled_update_parts.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// `kind` names the filter in the budget's message (check_closure_samples_budget), checked before any expectation.
SampledUpdate closure_sampled_update(const Model& model, const FilterVariables& vars, const std::string& kind,
                                     std::vector<Polynomial>& predicted);

// z's joint moments of orders 2 .. vars.order() with at least one index of d (>= n), indices ascending over the
// n + r entries of z, by order then lexicographically: SampledUpdate::joint's order.
std::vector<std::vector<std::size_t>> joint_moment_indices(std::size_t n, std::size_t r, std::size_t order);

}  // namespace pfgen
