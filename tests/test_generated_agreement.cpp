// The checked-in generated code (generated/, double) agrees with the
// generator's own exact evaluation (what `pfgen eval` prints) at 50 random
// points per example and filter kind, to 1e-12 relative to the largest entry
// of each output vector.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "generated/basin2006_quadratic/additive.hpp"
#include "generated/basin2006_quadratic/ekf.hpp"
#include "generated/basin2006_quadratic/ekf_additive.hpp"
#include "generated/basin2006_quadratic/optimal.hpp"
#include "generated/basin_skliar_partial/ekf.hpp"
#include "generated/basin_skliar_partial/optimal.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

// A random point with rational coordinates k/1000 (exact for the evaluator,
// rounded once for the generated code) and P = L L^T + I/10, positive definite.
EvaluationPoint random_point(std::size_t n, std::mt19937& rng) {
  std::uniform_int_distribution<int> k(-2000, 2000);
  auto r = [&] { return GiNaC::numeric(k(rng), 1000); };
  EvaluationPoint point;
  point.t = GiNaC::abs(r());
  for (std::size_t i = 0; i < n; ++i) point.m.push_back(r());
  std::vector<std::vector<GiNaC::numeric>> L(n, std::vector<GiNaC::numeric>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j) L[i][j] = r();
  point.P.assign(n, std::vector<GiNaC::numeric>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      GiNaC::numeric s = i == j ? GiNaC::numeric(1, 10) : 0;
      for (std::size_t k2 = 0; k2 < n; ++k2) s += L[i][k2] * L[j][k2];
      point.P[i][j] = s;
    }
  return point;
}

void check_close(const std::vector<double>& generated, const std::vector<double>& reference, const char* what) {
  REQUIRE(generated.size() == reference.size());
  double scale = 0;
  for (double v : reference) scale = std::max(scale, std::abs(v));
  for (std::size_t k = 0; k < reference.size(); ++k) {
    INFO(what << "[" << k << "]: generated " << generated[k] << ", reference " << reference[k]);
    CHECK(std::abs(generated[k] - reference[k]) <= 1e-12 * std::max(scale, 1e-300));
  }
}


#define PFGEN_CHECK_AGREEMENT(NS, MODEL_FILE, KIND)                                                         \
  SECTION(MODEL_FILE " " #KIND) {                                                                            \
    namespace gen = NS;                                                                                      \
    Model model = load_model_file(pfgen_test::example(MODEL_FILE));                                          \
    FilterEquations eq = derive_filter(model, FilterKind::KIND);                                             \
    std::mt19937 rng(12345);                                                                                 \
    for (int sample = 0; sample < 50; ++sample) {                                                            \
      EvaluationPoint point = random_point(gen::n, rng);                                                     \
      EvaluatedFilter reference = evaluate_at(model, eq, point);                                             \
      std::vector<double> state;                                                                             \
      for (const auto& v : point.m) state.push_back(v.to_double());                                          \
      for (std::size_t i = 0; i < gen::n; ++i)                                                               \
        for (std::size_t j = i; j < gen::n; ++j) state.push_back(point.P[i][j].to_double());                 \
      REQUIRE(state.size() == gen::state_size);                                                              \
      std::vector<double> out(gen::state_size), K(gen::n * gen::p);                                          \
      gen::derivatives<double>(point.t.to_double(), state.data(), gen::Params<double>{}, out.data());        \
      gen::gain<double>(point.t.to_double(), state.data(), gen::Params<double>{}, K.data());                 \
      std::vector<double> expected = reference.m_drift, expected_K;                                          \
      for (std::size_t i = 0; i < gen::n; ++i)                                                               \
        for (std::size_t j = i; j < gen::n; ++j) expected.push_back(reference.P_drift[i][j]);                \
      for (const auto& row : reference.gain) expected_K.insert(expected_K.end(), row.begin(), row.end());    \
      check_close(out, expected, "derivatives");                                                             \
      check_close(K, expected_K, "gain");                                                                    \
    }                                                                                                        \
  }

}  // namespace

TEST_CASE("generated derivatives and gain agree with pfgen's exact evaluation", "[codegen][agreement][unit]") {
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin2006_quadratic::optimal, "basin2006_quadratic.yaml", Optimal)
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin2006_quadratic::ekf, "basin2006_quadratic.yaml", Ekf)
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin2006_quadratic::additive, "basin2006_quadratic.yaml", Additive)
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin2006_quadratic::ekf_additive, "basin2006_quadratic.yaml", EkfAdditive)
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin_skliar_partial::optimal, "basin_skliar_partial.yaml", Optimal)
  PFGEN_CHECK_AGREEMENT(pfgen_models::basin_skliar_partial::ekf, "basin_skliar_partial.yaml", Ekf)
}
