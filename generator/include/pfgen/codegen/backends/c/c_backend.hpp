#pragma once
// The C99 backend's config (Backend, codegen/backend.hpp): a .h/.c pair per filter (this folder's
// templates/, one pair per layout), every external name prefixed <prefix>_ = <namespace, `::` written
// `_`>_<model>_<filter identifier>_. No heap, no variable-length arrays; float or double; <math.h>
// only for sqrt (sampled filters' update) and the functions the model's own equations call.
// Parameters are a record the caller owns; a delayed filter's history is an array the caller owns
// (or the <prefix>_filter record). c_filter_writer.hpp writes any observation module's
// description of the file into the pair of its layout.
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

// "<model>/<identifier>.h", "<model>/<identifier>.c".
std::vector<std::string> c_filter_paths(const std::string& model_name, const std::string& filter_name);

// The prefix of the filter's C names: "pfgen_models_van_der_pol_optimal".
std::string c_symbol_prefix(const std::string& name_space, const std::string& model_name, const std::string& filter_name);

}  // namespace pfgen::codegen
