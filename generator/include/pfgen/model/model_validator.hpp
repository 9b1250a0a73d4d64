#pragma once
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"

namespace pfgen {

// Checks every invariant documented in model.hpp; throws ModelError naming the
// field (and row/column) of the first violation.
void validate_model(const Model& model);

// pfgen's built-in filter kinds as the model room knows them: names a user filter may not
// take (nor their C++ identifiers), and which of them need the model's additive diffusion
// (simulation.filters may name only kinds the model supports). derivation/filter_kind is the
// authority on kinds; tests/test_user_filters.cpp keeps the two lists equal.
struct BuiltinFilterName {
  std::string name;
  bool needs_additive_diffusion = false;
};
const std::vector<BuiltinFilterName>& builtin_filter_names();

// True if `name` may be used for a state, parameter or time symbol.
bool is_valid_identifier(const std::string& name);

}  // namespace pfgen
