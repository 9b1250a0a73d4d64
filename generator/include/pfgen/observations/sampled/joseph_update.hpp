#pragma once
// The body of a generated sampled filter's update(state, t, y, params), which absorbs one sample, as
// statements for every language: K = P C^T S^-1 (the file's solve_gain), m += K (y - h), and P's
// Joseph form (Id - K C) P (Id - K C)^T + K R K^T, which keeps P symmetric and positive
// semi-definite under rounding. The sizes are the file's dimensions (n, p) and the functions the
// file's (innovation_terms, solve_gain, observation_matrices, predicted_observation, packed_at),
// each spelt by the backend's emitter.
//
// In four parts, which a language's template places: Rust may not borrow parts of CR (the views C
// and R) before observation_matrices() writes it, while C declares them first.
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

struct JosephUpdate {
  ir::Block arrays;  // the local arrays: u, CR, K, h, P, A, AP
  ir::Block views;   // C and R, the parts of CR, and the packed index k
  ir::Block solve;   // the functions' values into the arrays, and the gain (false when S is not positive definite)
  ir::Block update;  // P unpacked, m and P updated, true
};

JosephUpdate joseph_update_statements();

}  // namespace pfgen::codegen
