// The registry of output languages' backends: one row per folder codegen/backends/<language>/,
// whose factory (defined in that folder, a function-local static object) is declared here only, so
// that a new language is its folder and one line in each list below.
#include <stdexcept>

#include "pfgen/codegen/backend.hpp"

namespace pfgen::codegen {

const Backend& cpp_backend();  // backends/cpp/cpp_backend.cpp
const Backend& c_backend();    // backends/c/c_backend.cpp
const Backend& rust_backend();  // backends/rust/rust_backend.cpp

const std::vector<const Backend*>& backends() {
  static const std::vector<const Backend*> rows = {&cpp_backend(), &c_backend(), &rust_backend()};
  return rows;
}

const Backend& backend(const std::string& name) {
  for (const Backend* row : backends())
    if (row->name() == name) return *row;
  throw std::logic_error("no backend for the output language '" + name + "'");
}

const OutputLanguageInfo& Backend::facts() const { return output_language_info(name()); }

std::string Backend::file_role(std::size_t) const { return ""; }

std::optional<std::string> Backend::scalar_problem(ScalarMode) const { return std::nullopt; }

std::optional<std::string> Backend::eigen_problem() const { return std::nullopt; }

void Backend::check_model(const Model&, const std::string&) const {}

}  // namespace pfgen::codegen
