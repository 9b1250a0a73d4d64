#pragma once
// The body of a generated sampled filter's solve_gain(PCt, S, K) in C or C++: K = PCt S^-1 for an
// r x r symmetric S (packed upper triangle, row by row) by its Cholesky factor S = L L^T, every
// operation on S written out for the given r (no loops over r, no library), then for each of
// the n rows of PCt a forward and a back substitution, also written out. Returns false (C: 0)
// from the generated function when a pivot is not positive (S not positive definite in floating
// point). Uses only the scalar type, its sqrt and arithmetic, so float code stays float-clean.
#include <cstddef>
#include <string>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

// What the language calls what the solve's loop and its result need.
struct CholeskySpelling {
  std::string size_type;  // "std::size_t", "size_t"
  std::string n, p;       // the filter's dimension constants
  std::string zero;       // the pivot's bound: "Scalar(0)", "0.0f"
  std::string failure, success;  // "false", "true" (C: "0", "1")
};

std::string cholesky_gain_body(std::size_t r, const CFamilyEmitter& emitter, const CholeskySpelling& spelling);

}  // namespace pfgen::codegen
