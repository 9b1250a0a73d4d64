// expanded_counts (codegen/expanded_counts.hpp): derivatives()' expanded form counted from the
// polynomials, without its graph. Its count without sharing must be the graph's exactly (it is
// printed in every generated file), and its bound must never exceed the graph's count with
// sharing (else derivatives() could drop the form it would have kept). Both are checked against
// the graph GraphBuilder builds from the same outputs, on the dense cubic models and the
// examples, every kind whose equations generate code.
#include <catch2/catch.hpp>

#include "pfgen/codegen/expanded_counts.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/dense_cubic_model.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

namespace {

struct GraphCounts {
  OpCounts tree, shared;
};

// The expanded form as derivatives() builds it: definitions first, then each output's polynomial.
GraphCounts graph_counts(const Model& model, const FilterEquations& eq) {
  ExpressionGraph graph;
  GraphBuilder builder(graph, model, eq.variables, "state", "params");
  builder.define(eq.definitions, eq.variables.symbols());
  std::vector<std::size_t> roots;
  for_each_expanded_output(eq, [&](const Polynomial& p) { roots.push_back(builder.polynomial(p)); });
  return {graph.tree_counts(roots), graph.shared_counts(roots)};
}

void check_counts(const Model& model, FilterKind kind, bool numbers) {
  const FilterEquations eq = derive_filter(model, kind);
  const std::optional<ExpandedCounts> counted = expanded_counts(eq);
  INFO(model.name << ", " << filter_kind_name(kind));
  REQUIRE(counted.has_value() == numbers);
  if (!counted) return;
  const GraphCounts graph = graph_counts(model, eq);
  CHECK(counted->naive.adds == graph.tree.adds);
  CHECK(counted->naive.muls == graph.tree.muls);
  CHECK(counted->naive.divs == graph.tree.divs);
  CHECK(counted->naive.calls == graph.tree.calls);
  CHECK(counted->shared_lower_bound <= graph.shared.total());
  // The bound is the chains' additions, which dominate a dense model's expanded form.
  CHECK(counted->shared_lower_bound > 0);
}

}  // namespace

TEST_CASE("expanded_counts: the expanded form's counts without its graph, dense cubic", "[codegen][unit]") {
  for (std::size_t n : {2, 4, 6}) {
    const Model model = pfgen_test::dense_cubic_model(n);
    for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf})
      check_counts(model, kind, true);
    // At n = 6 the bound alone already exceeds what the moment form writes (3359 operations).
    if (n == 6) CHECK(expanded_counts(derive_filter(model, FilterKind::Optimal))->shared_lower_bound > 3359);
  }
}

TEST_CASE("expanded_counts: examples, and coefficients that are not numbers", "[codegen][unit]") {
  // Numbers only (Basin, Perez & Skliar 2006; Basin & Skliar), every kind they have.
  const Model quadratic = load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Additive, FilterKind::EkfAdditive})
    check_counts(quadratic, kind, true);
  const Model partial = load_model_file(pfgen_test::example("basin_skliar_partial.yaml"));
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf}) check_counts(partial, kind, true);
  // A parameter in a coefficient (the Van der Pol example's mu, s): only the graph counts it.
  const Model vdp = load_model_file(pfgen_test::example("van_der_pol.yaml"));
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Additive}) check_counts(vdp, kind, false);
}
