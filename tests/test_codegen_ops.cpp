// Common-subexpression elimination pays on dense models, and integer powers
// are products, never pow().
#include <catch2/catch.hpp>

#include <random>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/model/model_builder.hpp"

using namespace pfgen;

namespace {

// Every monomial up to degree 3 in each drift component, linear multiplicative
// diffusion g = diag(c0 + sum_k c_k x_k), one observation per state.
Model dense_cubic(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> k(-9, 9);
  auto c = [&] { int v = k(rng); return GiNaC::numeric(v == 0 ? 1 : v, 10); };
  ModelBuilder b("dense_cubic");
  std::vector<GiNaC::symbol> x;
  for (std::size_t i = 0; i < n; ++i) x.push_back(b.state("x" + std::to_string(i + 1)));
  std::vector<GiNaC::ex> monomials{1};
  for (std::size_t i = 0; i < n; ++i) {
    monomials.push_back(x[i]);
    for (std::size_t j = i; j < n; ++j) {
      monomials.push_back(x[i] * x[j]);
      for (std::size_t l = j; l < n; ++l) monomials.push_back(x[i] * x[j] * x[l]);
    }
  }
  ExVector f;
  ExMatrix g(n, ExVector(n, 0)), I(n, ExVector(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    GiNaC::ex fi = 0;
    for (const auto& m : monomials) fi += c() * m;
    f.push_back(fi);
    GiNaC::ex gi = c();
    for (std::size_t l = 0; l < n; ++l) gi += c() * x[l];
    g[i][i] = gi;
    I[i][i] = 1;
  }
  b.drift(f).diffusion(g).observation(ExVector(n, 0), I, I);
  return b.build();
}

}  // namespace

TEST_CASE("CSE op count is at most 60% of the naive count on dense cubic models", "[codegen][cse][unit]") {
  for (std::size_t n : {4, 6}) {
    Model model = dense_cubic(n, 7);
    codegen::GeneratedFilter code =
        codegen::generate_filter_code(model, derive_filter(model, FilterKind::Optimal), codegen::CodegenOptions{});
    const double ratio = double(code.cse_total().total()) / double(code.naive_total().total());
    INFO("n = " << n << ": naive " << code.naive_total().total() << ", cse " << code.cse_total().total());
    CHECK(ratio <= 0.60);
    CHECK(code.contents.find("pow(") == std::string::npos);
    // The banner reports both counts.
    CHECK(code.contents.find("// Ops before CSE: " + std::to_string(code.naive_total().total())) != std::string::npos);
    CHECK(code.contents.find("// Ops after CSE:  " + std::to_string(code.cse_total().total())) != std::string::npos);
  }
}
