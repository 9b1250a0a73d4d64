#include "pfgen/kinds/output_languages.hpp"

#include <stdexcept>

namespace pfgen {

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
