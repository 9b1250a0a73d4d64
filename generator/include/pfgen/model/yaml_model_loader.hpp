#pragma once
// Reads a model file (YAML). See docs/guide/model-file.md.
#include <cstddef>
#include <string>

#include "pfgen/model/model.hpp"

namespace pfgen {

// The most a model file may hold; the loader stops reading there.
inline constexpr std::size_t kMaxModelFileBytes = std::size_t{64} << 20;

// Loads and validates; throws ModelError (with file, line and column) on any problem.
Model load_model_file(const std::string& path);

// Same, from text already in memory; `path` only names the source in errors.
Model load_model_text(const std::string& text, const std::string& path);

}  // namespace pfgen
