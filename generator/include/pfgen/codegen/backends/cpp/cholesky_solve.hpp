#pragma once
// The body of a generated sampled filter's detail::solve_gain(PCt, S, K): K = PCt S^-1 for an
// r x r symmetric S (packed upper triangle, row by row) by its Cholesky factor S = L L^T, every
// operation on S written out for the given r (no loops over r, no library), then for each of
// the n rows of PCt a forward and a back substitution, also written out. Returns false from the
// generated function when a pivot is not positive (S not positive definite in floating point).
// Uses only Scalar, std::sqrt and arithmetic, so the float code stays float-clean.
#include <cstddef>
#include <string>

namespace pfgen::codegen {

std::string cholesky_gain_body(std::size_t r);

}  // namespace pfgen::codegen
