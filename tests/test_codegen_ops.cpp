// Common-subexpression elimination pays on dense models, and integer powers
// are products, never pow().
#include <catch2/catch.hpp>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
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

namespace {

// The Lorenz system with state-multiplicative noise, fully observed: a sparse model whose E[J] has
// entries that are numbers or parameters (-sigma, -1, -beta), negated states (-m1) and sums
// (rho - m3). `drift` spells the coefficients, as numbers or as the parameters'.
Model lorenz(const std::string& drift, const std::string& diffusion) {
  return load_model_text(
      "name: lorenz\n"
      "states: [x, y, z]\n"
      "parameters: {sigma: 10, rho: 28, beta: 2.6667, s: 0.1}\n"
      "drift: " + drift + "\n"
      "diffusion: " + diffusion + "\n"
      "observation:\n"
      "  A0: ['0', '0', '0']\n"
      "  A: [['1', '0', '0'], ['0', '1', '0'], ['0', '0', '1']]\n"
      "  B: [['0.5', '0', '0'], ['0', '0.5', '0'], ['0', '0', '0.5']]\n"
      "initial: {m0: [0, 0, 18], P0: [[4, 0, 0], [0, 4, 0], [0, 0, 4]]}\n",
      "lorenz.yaml");
}

std::size_t derivatives_ops(const Model& model, FilterKind kind) {
  const codegen::GeneratedFilter code =
      codegen::generate_filter_code(model, derive_filter(model, kind), codegen::CodegenOptions{});
  for (const auto& f : code.functions)
    if (f.function == "derivatives") return f.cse.total();
  FAIL("no derivatives() in the generated filter");
  return 0;
}

}  // namespace

// P's drift in Stein's structure, P E[J]^T + E[J] P + E[g g^T] - K (A P), as a SymPy user writes
// it (benchmarks/bench_sympy_peer.py's sympy-structured: 106 operations with the coefficients as
// numbers, 121 as parameters, 115 with the additive part): pfgen's derivatives() must need no more.
// Two things made it need more: an E[J] entry that is a negated value (-m1, -10, -1) was negated
// or multiplied as it is (P12 * -1), where the product of its positive can be subtracted; and
// products of P with E[J]'s constant entries were summed apart from E[g g^T]'s terms in the same
// P entries (-20 P11 and 0.01 P11), which the peer's expression merges (-19.99 P11).
TEST_CASE("derivatives(): a sparse model's E[J] signs and constant entries cost no operations of their own",
          "[codegen][cse][unit]") {
  const std::string numbers = "['10*(y - x)', 'x*(28 - z) - y', 'x*y - 8/3*z']";
  const std::string parameters = "['sigma*(y - x)', 'x*(rho - z) - y', 'x*y - beta*z']";
  const std::string multiplicative = "[['0.1*x', '0', '0'], ['0', '0.1*y', '0'], ['0', '0', '0.1*z']]";
  const std::string parameter_noise = "[['s*x', '0', '0'], ['0', 's*y', '0'], ['0', '0', 's*z']]";
  const std::string additive = "[['1 + 0.1*x', '0', '0'], ['0', '1 + 0.1*y', '0'], ['0', '0', '1 + 0.1*z']]";
  CHECK(derivatives_ops(lorenz(numbers, multiplicative), FilterKind::Optimal) <= 106);
  CHECK(derivatives_ops(lorenz(parameters, parameter_noise), FilterKind::Optimal) <= 121);
  CHECK(derivatives_ops(lorenz(numbers, additive), FilterKind::Optimal) <= 115);
}
