#pragma once
// The Rust backend's filters (its config is rust_backend.cpp, a Backend of codegen/backend.hpp): a
// filter as one `#![no_std]` module, "<model>/<identifier>.rs", for f32 or f64 (CodegenOptions::scalar
// Float or Double): its parameters a `Params` struct the caller owns, the C backend's functions
// under their own names (derivatives, gain, predicted_observation, initial_state, step; a sampled
// filter's predict, update, advance; a delayed filter's step and its `Filter` record), fixed-size
// arrays, no allocation. rustc 1.63 (Debian 12's) compiles it, edition 2021, with warnings denied.
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

std::vector<std::string> rust_filter_paths(const std::string& model_name, const std::string& filter_name);

// The filter's module, by its observation (rust_rate_filters.cpp: continuous and polynomial;
// rust_sampled_filter.cpp; rust_delayed_filter.cpp), each filling its templates/rust/ template
// with the functions its observation module builds (observations/<kind>/<kind>_code.hpp).
GeneratedFilter rust_continuous_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options);
GeneratedFilter rust_polynomial_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options);
GeneratedFilter rust_sampled_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options);
GeneratedFilter rust_delayed_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options);

}  // namespace pfgen::codegen
