#pragma once
// Vectors and matrices of GiNaC expressions, as the model room stores coefficients.
#include <ginac/ginac.h>

#include <vector>

namespace pfgen {

using ExVector = std::vector<GiNaC::ex>;
using ExMatrix = std::vector<std::vector<GiNaC::ex>>;  // row-major, rows of equal length

}  // namespace pfgen
