#include "pfgen/kinds/output_languages.hpp"

#include <stdexcept>

namespace pfgen {

// Each language's own reserved words, defined in its backend's folder and declared only here, so
// that a new language is its folder and one row below.
std::optional<std::string> cpp_reserved_name_problem(const std::string& name);   // backends/cpp/cpp_reserved_words.cpp
std::optional<std::string> c_reserved_name_problem(const std::string& name);     // backends/c/c_reserved_words.cpp
std::optional<std::string> rust_reserved_name_problem(const std::string& name);  // backends/rust/rust_reserved_words.cpp

const std::vector<OutputLanguageInfo>& output_languages() {
  static const std::vector<OutputLanguageInfo> languages = {
      {"cpp", "C++", &cpp_reserved_name_problem},
      {"c", "C", &c_reserved_name_problem},
      {"rust", "Rust", &rust_reserved_name_problem},
  };
  return languages;
}

const OutputLanguageInfo& output_language_info(const std::string& name) {
  for (const auto& info : output_languages())
    if (info.name == name) return info;
  throw std::logic_error("output language '" + name + "' missing from the registry");
}

}  // namespace pfgen
