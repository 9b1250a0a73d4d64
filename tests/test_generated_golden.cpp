// generated/ is the checked-in output of `pfgen codegen` for every example:
// regenerating it must reproduce every file byte for byte, with nothing
// missing and nothing left over. Fix a failure with
//   cmake --build build --target regenerate
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>

#include "support/cli_helpers.hpp"

namespace fs = std::filesystem;
using namespace pfgen_test;

namespace {

std::set<std::string> header_files(const fs::path& root) {
  std::set<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file() && entry.path().extension() == ".hpp")
      files.insert(fs::relative(entry.path(), root).string());
  return files;
}

}  // namespace

TEST_CASE("generated/ matches a fresh pfgen codegen of every example byte for byte", "[codegen][golden][integration]") {
  TempDir out;
  for (const auto& entry : fs::directory_iterator(source_dir() + "/examples")) {
    if (entry.path().extension() != ".yaml") continue;
    ProcessResult r = run_process(shell_quote(pfgen_executable()) + " codegen " + shell_quote(entry.path().string()) +
                                  " -o " + shell_quote(out.path()));
    INFO(entry.path() << ": " << r.err);
    REQUIRE(r.exit_code == 0);
  }
  const fs::path golden = source_dir() + "/generated";
  std::set<std::string> expected = header_files(out.path());
  REQUIRE(!expected.empty());
  CHECK(header_files(golden) == expected);
  for (const auto& file : expected) {
    INFO(file << " differs: run `cmake --build build --target regenerate`");
    CHECK(read_file((golden / file).string()) == read_file(out.file(file)));
  }
}

TEST_CASE("pfgen codegen output is identical across separate processes", "[codegen][determinism][integration]") {
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
