#pragma once
// The languages pfgen writes filters in, as plain facts: each one's name on the command line and
// the names its generated code cannot declare. A model file is valid for every language, so the
// model room refuses a name that any of them reserves, at its line and column, when the file is
// read (model/reserved_names.hpp); the backends (codegen/backends/<language>/) write the code.
// A new language is one row here, its reserved words in their own file, and its backend.
#include <optional>
#include <string>
#include <vector>

namespace pfgen {

enum class OutputLanguage { Cpp, C, Rust };

struct OutputLanguageInfo {
  OutputLanguage language;
  std::string name;   // as `pfgen codegen --language` takes it: "cpp"
  std::string title;  // as messages name it: "C++"
  // Why the language's generated code cannot declare `name` as a local (a keyword, a macro of the
  // headers it includes, a type or function it uses), or nothing.
  std::optional<std::string> (*name_problem)(const std::string& name);
};

// Every output language, in a fixed order (C++ first: its words were checked first historically,
// and the first problem found is the one reported).
const std::vector<OutputLanguageInfo>& output_languages();
const OutputLanguageInfo& output_language_info(OutputLanguage language);

// Each language's own reserved words (kinds/cpp_reserved_words.cpp, kinds/c_reserved_words.cpp,
// kinds/rust_reserved_words.cpp).
std::optional<std::string> cpp_reserved_name_problem(const std::string& name);
std::optional<std::string> c_reserved_name_problem(const std::string& name);
std::optional<std::string> rust_reserved_name_problem(const std::string& name);

}  // namespace pfgen
