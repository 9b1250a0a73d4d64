// The same input gives the same bytes in every run. GiNaC orders the terms of its sums by hashes
// that change from run to run (docs/theory.md §9.1), and a sum inside a product comes out either as
// it is or negated with the sign outside; the printers and the code generator choose one of the two
// themselves (ExpressionPrinter::to_term, GraphBuilder::product). A single process cannot show the
// difference, so pfgen is run several times, each with its own address layout.
#include <catch2/catch.hpp>

#include <set>

#include "support/cli_helpers.hpp"
#include "support/test_paths.hpp"

using namespace pfgen_test;

TEST_CASE("run to run: sums in products print and generate the same in every run", "[determinism][integration]") {
  const std::string model = test_data_dir() + "/sums_in_products.yaml";
  constexpr int kRuns = 6;
  for (const std::string& filter : {std::string("mine"), std::string("ukf")}) {
    for (const std::string& format : {std::string("text"), std::string("latex"), std::string("json")}) {
      std::set<std::string> outputs;
      for (int run = 0; run < kRuns; ++run) {
        ProcessResult r = run_pfgen({"derive", model, "--filter", filter, "--format", format});
        REQUIRE(r.exit_code == 0);
        outputs.insert(r.out);
      }
      INFO(filter << " " << format);
      CHECK(outputs.size() == 1);
    }
  }
  std::set<std::string> headers;
  for (int run = 0; run < kRuns; ++run) {
    TempDir dir;
    ProcessResult r = run_pfgen({"codegen", model, "--filter", "mine,ukf", "-o", dir.file("out")});
    REQUIRE(r.exit_code == 0);
    headers.insert(read_file(dir.file("out/sums_in_products/mine.hpp")) +
                   read_file(dir.file("out/sums_in_products/ukf.hpp")));
  }
  CHECK(headers.size() == 1);
}
