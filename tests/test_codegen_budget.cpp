// Code generation's budget (codegen::kMaxCodegenTerms, CodegenOptions::max_equation_terms): a
// filter whose equations have more terms than code generation can hold in memory is refused before
// any of it is built, in one message naming the filter, its terms and the memory it would need.
// The dense cubic n = 20 optimal filter (3.6 million terms, about 0.7 GB) is within the budget;
// lowered below it, the budget refuses it. Smaller filters are untouched. A moment filter's higher
// moments count kMomentTermWeight terms each.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "support/cli_helpers.hpp"
#include "support/dense_cubic_model.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

TEST_CASE("codegen refuses a filter beyond its budget of equation terms, before building any code",
          "[codegen][unit]") {
  const Model big = pfgen_test::dense_cubic_model(20);
  const FilterEquations optimal = derive_filter(big, FilterKind::Optimal);
  CHECK(codegen::codegen_terms(optimal) == 3604699);
  CHECK(codegen::codegen_terms(optimal) < codegen::kMaxCodegenTerms);
  codegen::CodegenOptions lowered;
  lowered.max_equation_terms = 1000000;
  try {
    (void)codegen::generate_filter_code(big, optimal, lowered);
    FAIL("the 20-state dense cubic optimal filter was generated beyond the budget");
  } catch (const codegen::CodegenError& e) {
    const std::string message = e.what();
    CHECK(message.find("<api>: filter 'optimal' of model dense_cubic_20 has 3604699 terms in its equations; code "
                       "generation holds at most 1000000") == 0);
    CHECK(message.find("would need about 0.7 GB") != std::string::npos);
  }
  // Within the budget: the 4-state model generates as before.
  const Model small = pfgen_test::dense_cubic_model(4);
  const FilterEquations within = derive_filter(small, FilterKind::Optimal);
  CHECK(codegen::codegen_terms(within) < codegen::kMaxCodegenTerms);
  CHECK_NOTHROW(codegen::generate_filter_code(small, within, codegen::CodegenOptions{}));
}

TEST_CASE("codegen counts a moment filter's higher moments, each as kMomentTermWeight terms of its budget",
          "[codegen][unit]") {
  // The 3-state dense cubic closure4: its higher moments' terms are most of its equations'. With the budget set
  // between its plain term count and its load, it is refused in the message's moment form; optimal is not.
  const Model model = pfgen_test::dense_cubic_model(3);
  const FilterEquations closure4 = derive_filter(model, FilterKind::Closure4);
  const FilterEquations optimal = derive_filter(model, FilterKind::Optimal);
  const double terms = codegen::codegen_terms(closure4), moments = codegen::moment_terms(closure4);
  CHECK(moments > 0.8 * terms);
  CHECK(codegen::moment_terms(optimal) == 0);
  CHECK(codegen::codegen_load(optimal) == codegen::codegen_terms(optimal));
  CHECK(codegen::codegen_load(closure4) == terms + (codegen::kMomentTermWeight - 1) * moments);
  codegen::CodegenOptions lowered;
  lowered.max_equation_terms = terms + moments;  // above its terms, below its load
  CHECK_NOTHROW(codegen::generate_filter_code(model, optimal, lowered));
  try {
    (void)codegen::generate_filter_code(model, closure4, lowered);
    FAIL("closure4 was generated beyond its budget");
  } catch (const codegen::CodegenError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("<api>: filter 'closure4' of model dense_cubic_3 has " + std::to_string(std::lround(terms)) +
                       " terms in its equations, " + std::to_string(std::lround(moments)) +
                       " of them its higher moments', which count 3.5 each (" +
                       std::to_string(std::lround(codegen::codegen_load(closure4))) +
                       " in all); code generation holds at most ") == 0);
    CHECK(message.find("a lower order generates") != std::string::npos);
  }
}

TEST_CASE("codegen and simulate refuse a sampled observation of more outputs than the unrolled update takes",
          "[codegen][integration]") {
  using namespace pfgen_test;
  TempDir dir;
  const std::string model = test_data_dir() + "/sampled_65_outputs.yaml";
  // The message names the model's file, not only its name.
  const std::string message = model + ": filter 'cd-optimal' of model sampled_65_outputs samples 65 outputs";
  for (const auto& args : {std::vector<std::string>{"codegen", model, "-o", dir.file("out")},
                           std::vector<std::string>{"simulate", model, "--cache-dir", dir.file("cache"), "-q"}}) {
    const auto r = run_pfgen(args);
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find(message) != std::string::npos);
    CHECK(r.err.find("code generation takes at most 64 outputs") != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("out")));
  CHECK_FALSE(std::filesystem::exists(dir.file("cache")));
  CHECK(run_pfgen({"derive", model}).exit_code == 0);  // derive and eval take any number of outputs
}
