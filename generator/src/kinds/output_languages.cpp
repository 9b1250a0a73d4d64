#include "pfgen/kinds/output_languages.hpp"

#include <stdexcept>

namespace pfgen {

const std::vector<OutputLanguageInfo>& output_languages() {
  static const std::vector<OutputLanguageInfo> languages = {
      {OutputLanguage::Cpp, "cpp", "C++", &cpp_reserved_name_problem},
      {OutputLanguage::C, "c", "C", &c_reserved_name_problem},
      {OutputLanguage::Rust, "rust", "Rust", &rust_reserved_name_problem},
  };
  return languages;
}

const OutputLanguageInfo& output_language_info(OutputLanguage language) {
  for (const auto& info : output_languages())
    if (info.language == language) return info;
  throw std::logic_error("output language missing from the registry");
}

}  // namespace pfgen
