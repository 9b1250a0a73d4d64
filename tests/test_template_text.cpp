// fill_template and embedded_template (codegen/template_text.hpp): every `{{key}}` is replaced
// by its value; a placeholder without a value, a value without a placeholder and an unterminated
// placeholder are errors, never half-filled code; the templates compiled into pfgen are the
// files of templates/, of each backend's templates/ (named after its language) and of each
// observation module's templates/.
#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

#include "pfgen/codegen/template_text.hpp"
#include "support/cli_helpers.hpp"

using pfgen::codegen::embedded_template;
using pfgen::codegen::fill_template;

namespace {

// The message of the std::logic_error that `fill` throws, or "" when it throws none.
template <class F>
std::string logic_error_of(F fill) {
  try {
    fill();
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("template filler: every placeholder gets its value, as often as it appears", "[unit][codegen]") {
  CHECK(fill_template("t", "inline void {{name}}(Scalar {{t}}) { {{body}}}\n// {{name}}",
                      {{"name", "gain"}, {"t", "tau"}, {"body", "x = 1; "}}) ==
        "inline void gain(Scalar tau) { x = 1; }\n// gain");
  CHECK(fill_template("t", "no placeholders", {}) == "no placeholders");
  CHECK(fill_template("t", "{{a}}{{b}}", {{"a", "{{b}}"}, {"b", ""}}) == "{{b}}");  // values are not re-read
  CHECK(fill_template("t", "{{empty}}", {{"empty", ""}}).empty());
}

TEST_CASE("template filler: a placeholder without value, a value without placeholder, an open brace are errors",
          "[unit][codegen]") {
  const std::string unknown = logic_error_of([] { fill_template("cpp/x.tmpl", "a {{what}} b", {{"other", "1"}}); });
  CHECK(unknown.find("cpp/x.tmpl") != std::string::npos);
  CHECK(unknown.find("no value for placeholder {{what}}") != std::string::npos);

  const std::string unused =
      logic_error_of([] { fill_template("cpp/x.tmpl", "a {{k}} b", {{"k", "1"}, {"spare", "2"}}); });
  CHECK(unused.find("value for {{spare}} has no placeholder") != std::string::npos);

  const std::string open = logic_error_of([] { fill_template("cpp/x.tmpl", "a {{k b", {{"k", "1"}}); });
  CHECK(open.find("unterminated placeholder") != std::string::npos);
}

TEST_CASE("embedded templates are the files of templates/, of the backends' and of the observation modules' templates/",
          "[unit][codegen]") {
  namespace fs = std::filesystem;
  const fs::path source(pfgen_test::source_dir());
  // Each root with the prefix its files are embedded under.
  std::vector<std::pair<fs::path, std::string>> roots = {{source / "templates", ""}};
  std::size_t backends = 0;
  for (const auto& language : fs::directory_iterator(source / "generator/src/codegen/backends"))
    if (fs::is_directory(language.path() / "templates")) {
      roots.emplace_back(language.path() / "templates", language.path().filename().string() + "/");
      ++backends;
    }
  CHECK(backends == 3);  // cpp, c, rust
  for (const auto& module : fs::directory_iterator(source / "generator/src/observations"))
    if (fs::is_directory(module.path() / "templates")) roots.emplace_back(module.path() / "templates", "");
  std::size_t files = 0;
  for (const auto& [root, prefix] : roots)
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (entry.path().extension() != ".tmpl") continue;
      const std::string name = prefix + entry.path().lexically_relative(root).generic_string();
      INFO(name);
      CHECK(embedded_template(name) == pfgen_test::read_file(entry.path().string()));
      ++files;
    }
  CHECK(files >= 24);
  CHECK(embedded_template("pfgen_runtime/plugin_abi.h") ==
        pfgen_test::read_file(pfgen_test::source_dir() + "/runtime/include/pfgen_runtime/plugin_abi.h"));
  CHECK_THROWS_AS(embedded_template("cpp/missing.tmpl"), std::logic_error);
}

TEST_CASE("template filler: an include line becomes the partial, whose placeholders are filled too", "[unit][codegen]") {
  const std::string& head = embedded_template("cpp/partials/eigen_layer_head.hpp.tmpl");
  REQUIRE(!head.empty());
  REQUIRE(head.back() == '\n');
  // A line holding only the include becomes the partial's lines, with no blank line added.
  const std::map<std::string, std::string> values = {
      {"banner", "// b"}, {"kind_header", "k.hpp"}, {"namespace", "ns"}, {"template_prefix", ""}};
  const std::string filled = fill_template("t", "{{> cpp/partials/eigen_layer_head.hpp.tmpl}}\nrest {{namespace}}\n", values);
  CHECK(filled == fill_template("t", head + "rest {{namespace}}\n", values));
  CHECK(filled.find("{{") == std::string::npos);
  // Both Eigen layers share it; each template still reads as its own file once expanded.
  for (const char* file : {"cpp/filter_eigen.hpp.tmpl", "cpp/sampled_filter_eigen.hpp.tmpl"})
    CHECK(embedded_template(file).rfind("{{> cpp/partials/eigen_layer_head.hpp.tmpl}}\n", 0) == 0);
  const std::string missing = logic_error_of([] { fill_template("t", "{{> cpp/partials/none.tmpl}}", {}); });
  CHECK(missing.find("no template cpp/partials/none.tmpl") != std::string::npos);
  const std::string open = logic_error_of([] { fill_template("t", "{{> cpp/partials/eigen", {}); });
  CHECK(open.find("unterminated include") != std::string::npos);
}
