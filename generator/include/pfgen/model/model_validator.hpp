#pragma once
#include <optional>
#include <string>
#include <vector>

#include "pfgen/model/model.hpp"

namespace pfgen {

// Checks every invariant documented in model.hpp; throws ModelError naming the
// field (and row/column) of the first violation.
void validate_model(const Model& model);

// True if `name` may be used for a state, parameter or time symbol.
bool is_valid_identifier(const std::string& name);
// Why `name` is not an identifier ("'α' is not an identifier: ..."), or nullopt. The loader asks
// as it reads each name, before any expression uses it; validate_model asks again for the C++ API.
std::optional<std::string> identifier_problem(const std::string& name);

}  // namespace pfgen
