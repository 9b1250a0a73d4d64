#pragma once
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"

namespace pfgen {

// Checks every invariant documented in model.hpp; throws ModelError naming the
// field (and row/column) of the first violation.
void validate_model(const Model& model);

// True if `name` may be used for a state, parameter or time symbol.
bool is_valid_identifier(const std::string& name);

}  // namespace pfgen
