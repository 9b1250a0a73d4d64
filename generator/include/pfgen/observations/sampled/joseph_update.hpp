#pragma once
// The body of a generated sampled filter's update(state, t, y, params), which absorbs one sample, as
// statements for every language: K = P C^T S^-1 (the file's solve_gain), m += K (y - h), and P's
// Joseph form (Id - K C) P (Id - K C)^T + K R K^T, which keeps P symmetric and positive
// semi-definite under rounding. The sizes are the file's dimensions (n, p) and the functions the
// file's (innovation_terms, solve_gain, observation_matrices, predicted_observation), each spelt by
// the backend's emitter, as are R's packed entries (ir::packed_entry: C's and Rust's packed_at, C++'s
// lambda R_at, which R's view declares).
//
// In six parts, which a language's template places in its order: Rust may not borrow parts of CR
// (the views C and R) before observation_matrices() writes it, while C declares them first; C++
// declares P, A, AP and k after the views, C and Rust with the other arrays.
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

struct JosephUpdate {
  ir::Block arrays;    // the local arrays of the functions' values: u, CR, K, h
  ir::Block matrices;  // the local n x n arrays P, A, AP
  ir::Block views;     // C and R, the parts of CR (R packed)
  ir::Block counter;   // k, the index into the state's packed P
  ir::Block solve;     // the functions' values into the arrays, and the gain (false when S is not positive definite)
  ir::Block update;    // P unpacked, m and P updated, true
};

JosephUpdate joseph_update_statements();

// Its m += K (y - h) and A = Id - K C (n x n, row-major, into the local A), which the moment filters' update of a
// polynomial c shares (sampled_moment_update.hpp).
ir::Block mean_and_gain_complement_statements();

}  // namespace pfgen::codegen
