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

}  // namespace pfgen::codegen
