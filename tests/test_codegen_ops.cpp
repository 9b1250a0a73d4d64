// Common-subexpression elimination pays on dense models, and integer powers
// are products, never pow().
#include <catch2/catch.hpp>

#include "pfgen/codegen/filter_codegen.hpp"
#include "support/dense_cubic_model.hpp"

using namespace pfgen;

TEST_CASE("CSE op count is at most 60% of the naive count on dense cubic models", "[codegen][cse][unit]") {
  for (std::size_t n : {4, 6}) {
    Model model = pfgen_test::dense_cubic_model(n);  // bench_derive's models
    codegen::GeneratedFilter code =
        codegen::generate_filter_code(model, derive_filter(model, FilterKind::Optimal), codegen::CodegenOptions{});
    const double ratio = double(code.cse_total().total()) / double(code.naive_total().total());
    INFO("n = " << n << ": naive " << code.naive_total().total() << ", cse " << code.cse_total().total());
    CHECK(ratio <= 0.60);
    CHECK(code.files.at(0).contents.find("pow(") == std::string::npos);
    // The banner reports both counts.
    CHECK(code.files.at(0).contents.find("// Ops before CSE: " + std::to_string(code.naive_total().total())) != std::string::npos);
    CHECK(code.files.at(0).contents.find("// Ops after CSE:  " + std::to_string(code.cse_total().total())) != std::string::npos);
  }
}
