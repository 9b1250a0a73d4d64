#pragma once
// The history ring of a generated delayed filter, as statements for every language: the body of
// initial_history(state, history), of delayed_inputs(history, start, now, k, offset, delayed) and
// the step's store of its start state, each built for the delay's case (no history when the delay
// is 0 steps; the end's read from the start state when it is 1; a ring otherwise), with and without
// x*, so that no generated branch is always true or always false and nothing indexes an empty
// history (which C's -Wextra and rustc report). The sizes are the file's dimensions (n,
// state_size, delay_steps, history_width), spelt by the backend's emitter.
//
// The same parts also in one form for every case, chosen by the file's constants delay_steps and
// uses_x_star (tests of sizes, and a compile-time conditional on x*): a language that folds its
// constants when it compiles, as C++'s constexpr ones, places this form (its template has these
// keys), the others the case's.
#include <cstddef>
#include <map>
#include <string>

#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// The blocks under their templates' keys: initial_history_body, delayed_inputs_body, history_store.
std::map<std::string, ir::Block> history_statements(std::size_t delay_steps, bool x_star);

// The ring for any delay, under the keys any_delay_initial_history_body, any_delay_delayed_inputs_body
// and any_delay_history_store.
std::map<std::string, ir::Block> any_delay_history_statements();

}  // namespace pfgen::codegen
