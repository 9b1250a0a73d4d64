#pragma once
// The languages pfgen writes filters in, as plain facts: each one's name on the command line, its
// title in messages, and the names its generated code cannot declare. A model file is valid for
// every language, so the model room refuses a name that any of them reserves, at its line and
// column, when the file is read (model/reserved_names.hpp). The model room stands below code
// generation, so these facts are a table of their own here rather than the backends' (codegen/
// backend.hpp, one folder codegen/backends/<language>/ each, which write the code and name their
// row here): a new language is its backend's folder, which holds its reserved words (defined there,
// declared beside the rows), and one row in output_languages.cpp.
#include <optional>
#include <string>
#include <vector>

namespace pfgen {

struct OutputLanguageInfo {
  std::string name;   // as `pfgen codegen --language` takes it: "cpp"
  std::string title;  // as messages name it: "C++"
  // Why the language's generated code cannot declare `name` as a local (a keyword, a macro of the
  // headers it includes, a type or function it uses), or nothing.
  std::optional<std::string> (*name_problem)(const std::string& name);
};

// Every output language, in a fixed order (C++ first: its words were checked first historically,
// and the first problem found is the one reported).
const std::vector<OutputLanguageInfo>& output_languages();
// The row of that name; std::logic_error for another.
const OutputLanguageInfo& output_language_info(const std::string& name);

}  // namespace pfgen
