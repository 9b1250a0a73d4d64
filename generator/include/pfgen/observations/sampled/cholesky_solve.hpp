#pragma once
// The body of a generated sampled filter's solve_gain(PCt, S, K), as statements for every
// language: K = PCt S^-1 for an r x r symmetric S (packed upper triangle, row by row) by its
// Cholesky factor S = L L^T, every operation on S written out for the given r (no loops over r, no
// library), then for each of the n rows of PCt a forward and a back substitution, also written out.
// Returns false from the generated function when a pivot is not positive (S not positive definite
// in floating point). Uses only the scalar type, its sqrt and arithmetic, so float code stays
// float-clean.
#include <cstddef>

#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// The solve for r outputs; the file's sizes n and p are its dimensions, spelt by the backend.
ir::Block cholesky_gain_statements(std::size_t r);

}  // namespace pfgen::codegen
