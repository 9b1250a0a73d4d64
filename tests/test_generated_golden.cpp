// generated/ is the checked-in output of `pfgen codegen` for every example, in every scalar mode
// with its Eigen wrappers (layout: generated/README.md): regenerating it must reproduce every file
// byte for byte, with nothing missing and nothing left over. The commands are those of the
// `regenerate` target of the top-level CMakeLists.txt; fix a failure with
//   cmake --build build --target regenerate
// (and delete the files reported as left over), then commit generated/.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "support/cli_helpers.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

// A scalar mode's place under generated/ and its options.
struct Mode {
  std::string directory;  // "" for generated/ itself
  std::vector<std::string> options;
};

const std::vector<Mode>& modes() {
  static const std::vector<Mode> list = {{"", {"--eigen"}},
                                         {"float", {"--eigen", "--scalar", "float"}},
                                         {"double", {"--eigen", "--scalar", "double"}},
                                         {"c/float", {"--language", "c", "--scalar", "float"}},
                                         {"c/double", {"--language", "c", "--scalar", "double"}}};
  return list;
}

// Every generated file (.hpp, .h, .c) under root, relative to it.
std::set<std::string> header_files(const fs::path& root) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file() &&
        (entry.path().extension() == ".hpp" || entry.path().extension() == ".h" || entry.path().extension() == ".c"))
      files.insert(fs::relative(entry.path(), root).generic_string());
  return files;
}

// "line N: `expected` / `actual`" for the first line where the two texts differ.
std::string first_difference(const std::string& expected, const std::string& actual) {
  std::istringstream a(expected), b(actual);
  std::string line_a, line_b;
  for (std::size_t line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, line_a));
    const bool more_b = static_cast<bool>(std::getline(b, line_b));
    if (!more_a && !more_b) return "they differ in line endings only";
    if (!more_a || !more_b || line_a != line_b)
      return "first difference in line " + std::to_string(line) + ": pfgen writes `" + (more_a ? line_a : "<end>") +
             "`, generated/ has `" + (more_b ? line_b : "<end>") + "`";
  }
}

const char* const kFix = "run `cmake --build build --target regenerate` and commit generated/";

}  // namespace

TEST_CASE("generated/ matches a fresh pfgen codegen of every example in every scalar mode, byte for byte",
          "[integration][codegen][golden]") {
  TempDir out;
  std::map<std::string, std::string> command_of;  // file under generated/ -> the command writing it
  for (const auto& entry : fs::directory_iterator(source_dir() + "/examples")) {
    if (entry.path().extension() != ".yaml") continue;
    for (const Mode& mode : modes()) {
      TempDir run;
      std::vector<std::string> arguments = {"codegen", entry.path().string(), "-o", run.path()};
      arguments.insert(arguments.end(), mode.options.begin(), mode.options.end());
      ProcessResult r = run_pfgen(arguments);
      INFO(entry.path() << ": " << r.err);
      REQUIRE(r.exit_code == 0);
      std::string command = "pfgen codegen examples/" + entry.path().filename().string();
      for (const auto& option : mode.options) command += " " + option;
      command += " -o generated" + (mode.directory.empty() ? "" : "/" + mode.directory);
      const fs::path target = fs::path(out.path()) / mode.directory;
      for (const auto& file : header_files(run.path())) {
        const fs::path relative = fs::path(mode.directory) / file;
        fs::create_directories((target / file).parent_path());
        fs::copy_file(fs::path(run.path()) / file, target / file);
        command_of[relative.generic_string()] = command;
      }
    }
  }
  const fs::path golden = source_dir() + "/generated";
  const std::set<std::string> expected = header_files(out.path());
  const std::set<std::string> present = header_files(golden);
  // Every mode and the Eigen wrappers are covered.
  for (const char* file : {"basin2006_quadratic/optimal.hpp", "basin2006_quadratic/optimal_eigen.hpp",
                           "float/basin2006_quadratic/optimal.hpp", "double/basin_skliar_partial/ekf_eigen.hpp",
                           "c/float/basin2006_quadratic/optimal.h", "c/double/delay_linear/delay_optimal.c"})
    CHECK(expected.count(file) == 1);
  for (const auto& file : expected) {
    if (!present.count(file)) {
      FAIL_CHECK("generated/" << file << " is missing (" << command_of[file] << " writes it): " << kFix);
      continue;
    }
    const std::string written = read_file((fs::path(out.path()) / file).string());
    const std::string checked_in = read_file((golden / file).string());
    if (written != checked_in)
      FAIL_CHECK("generated/" << file << " differs from what `" << command_of[file] << "` writes now; "
                              << first_difference(written, checked_in) << ". If the change is intended, " << kFix);
  }
  for (const auto& file : present)
    if (!expected.count(file))
      FAIL_CHECK("generated/" << file << " is left over: no example writes it any more; delete it and commit");
}

TEST_CASE("pfgen codegen output is identical across separate processes", "[integration][codegen][determinism]") {
  std::string model = example("basin_skliar_partial.yaml");
  std::vector<std::string> runs;
  for (const char* scalar : {"template", "float", "double", "template", "float", "double"}) {
    TempDir out;
    ProcessResult r = run_process(shell_quote(pfgen_executable()) + " codegen " + shell_quote(model) + " -o " +
                                  shell_quote(out.path()) + " --stats --scalar " + scalar);
    REQUIRE(r.exit_code == 0);
    runs.push_back(r.out + read_file(out.file("basin_skliar_partial/optimal.hpp")) +
                   read_file(out.file("basin_skliar_partial/ekf.hpp")));
  }
  CHECK(runs[0] == runs[3]);
  CHECK(runs[1] == runs[4]);
  CHECK(runs[2] == runs[5]);
  CHECK(runs[0] != runs[1]);  // the scalar mode does change the text
}
