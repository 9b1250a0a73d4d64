// Observation modules describe their filters' files in no language (DESIGN.md, "Code generation"):
// a module builds its functions, statements and words (codegen/filter_file.hpp), and each backend
// (codegen/backends/<language>/) writes them. This reads the sources of every module and names
// each place that writes or picks a language: a backend's emitter or writer, a template of a
// language, a header of a backend, or a writer file per language. (The plugin part, C++ by design,
// is not read: the truth's observation is composed from the axes in backends/cpp/truth_codegen.)
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/kinds/observation_kinds.hpp"
#include "support/cli_helpers.hpp"
#include "support/test_paths.hpp"

namespace fs = std::filesystem;

namespace {

// What names a language in a module's file: `pattern` and why it does.
struct LanguageMark {
  std::regex pattern;
  std::string what;
};

const std::vector<LanguageMark>& language_marks() {
  static const std::vector<LanguageMark> marks = {
      {std::regex(R"(\b(CppEmitter|CEmitter|RustEmitter|CFamilyEmitter|CFilterWriter|RustFilterWriter)\b)"),
       "a backend's emitter or writer"},
      {std::regex(R"(\b(write_cpp_filter|write_c_filter|write_rust_filter|c_symbol_prefix|rust_indent)\b)"),
       "a backend's own part"},
      {std::regex(R"("(cpp|c|rust)/)"), "a language's template"},
      {std::regex(R"(\.(hpp|h|c|rs)\.tmpl)"), "a language's template"},
      {std::regex(R"(#include "pfgen/codegen/backends/)"), "a backend's header"},
      {std::regex(R"(Scalar\(|\bSTATES\b|\bOBSERVATIONS\b)"), "a language's spelling"},
  };
  return marks;
}

// The module's files serving code generation's filter files: every source and header of its
// folders but its plugin part (<kind>_plugin.cpp writes the simulation plugin, which is C++).
std::vector<fs::path> module_files(const std::string& kind) {
  std::vector<fs::path> files;
  const fs::path source(pfgen_test::source_dir());
  for (const fs::path& folder : {source / "generator/src/observations" / kind,
                                 source / "generator/include/pfgen/observations" / kind})
    for (const auto& entry : fs::directory_iterator(folder)) {
      const std::string name = entry.path().filename().string();
      if (!entry.is_regular_file() || name == kind + "_plugin.cpp") continue;
      files.push_back(entry.path());
    }
  return files;
}

}  // namespace

TEST_CASE("observation modules describe their filter files in no language", "[unit][codegen]") {
  for (const auto& info : pfgen::observation_kinds()) {
    CHECK_FALSE(pfgen::codegen::observation_code(info.kind).layouts().empty());
    for (const fs::path& file : module_files(info.name)) {
      const std::string name = file.filename().string();
      INFO(file.string());
      for (const char* language : {"_cpp_filter", "_c_filter", "_rust_filter"})
        CHECK(name.find(language) == std::string::npos);
      const std::string text = pfgen_test::read_file(file.string());
      for (const LanguageMark& mark : language_marks()) {
        std::smatch found;
        const bool marked = std::regex_search(text, found, mark.pattern);
        INFO(mark.what + ": " + (marked ? found.str() : std::string()));
        CHECK_FALSE(marked);
      }
    }
  }
}
