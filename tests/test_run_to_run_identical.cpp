// The same input gives the same bytes in every run. GiNaC orders the terms of its sums by hashes
// that change from run to run (docs/theory.md §9.1), and a sum inside a product comes out either as
// it is or negated with the sign outside; the printers and the code generator choose one of the two
// themselves (ExpressionPrinter::to_term, GraphBuilder::product). A single process cannot show the
// difference, so pfgen is run several times, each with its own address layout.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

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

// eval sums floating-point values (a ukf's Cholesky entries, a user filter's definitions); GiNaC's
// subs() then evalf() added them in its hash order, and the last digit changed in about one run in
// a dozen (pfgen/algebra/numeric_value.hpp). Every kind of five models (continuous, sampled,
// delayed, risk-sensitive), at points where the Cholesky entries and definitions are irrational,
// with parameters set on the command line.
TEST_CASE("run to run: eval prints the same digits in every run, for every kind", "[determinism][integration]") {
  constexpr int kRuns = 6;
  const std::string m3 = "--m=0.37,-1.21,2.9", P3 = "1.3,0.21,-0.17;0.21,2.7,0.33;-0.17,0.33,1.9";
  const std::string m2 = "--m=0.37,-1.21", P2 = "1.3,0.21;0.21,2.7";
  // Continuous (with the ukf and a user filter's definitions), sampled, delayed and risk-sensitive.
  const struct {
    std::string model, assignment, m, P;
  } models[] = {{test_data_dir() + "/lorenz_multiplicative.yaml", "q=0.37", m3, P3},
                {test_data_dir() + "/sums_in_products.yaml", "a=0.3", m3, P3},
                {example("paper003/example2_gamma05.yaml"), "", m2, P2},
                {example("delay_linear.yaml"), "a=-0.37", "--m=0.37", "1.3"},
                {example("paper002/reactor.yaml"), "", m2, P2}};
  for (const auto& m : models) {
    const std::string& model = m.model;
    // Every filter the model offers, from the message that lists them: "... (known: a, b, c)".
    const std::string refused = run_pfgen({"derive", model, "--filter", "nonexistent"}).err;
    const auto open = refused.find("(known: ");
    REQUIRE(open != std::string::npos);
    std::vector<std::string> filters;
    std::string list = refused.substr(open + 8, refused.find(')', open) - open - 8) + ",";
    for (std::size_t start = 0, comma; (comma = list.find(',', start)) != std::string::npos; start = comma + 2)
      filters.push_back(list.substr(start, comma - start));
    CHECK(filters.size() >= 3);
    for (const std::string& filter : filters) {
      std::set<std::string> outputs;
      for (int run = 0; run < kRuns; ++run) {
        std::vector<std::string> args{"eval", model, "--filter", filter, m.m, "--P", m.P};
        if (!m.assignment.empty()) args.insert(args.end(), {"--set", m.assignment});
        ProcessResult r = run_pfgen(args);
        INFO(m.model << " " << filter << ": " << r.err);
        REQUIRE(r.exit_code == 0);
        outputs.insert(r.out);
      }
      INFO(m.model << " " << filter);
      CHECK(outputs.size() == 1);
    }
  }
}
