#pragma once
// The Ito form of a Stratonovich equation dx = f dt + g o dW: dx = (f + c) dt + g dW with
//   c_i = 1/2 sum_j sum_k g_jk d(g_ik)/d(x_j)
// (docs/theory.md §1.2). For polynomial g the correction is polynomial, of degree at most
// 2 deg g - 1, so every filter of pfgen applies to the converted model unchanged.
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

// c for the n x q diffusion g in the given states, each entry expanded.
ExVector stratonovich_correction(const ExMatrix& g, const std::vector<GiNaC::symbol>& states);

}  // namespace pfgen
