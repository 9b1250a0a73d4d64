// Each room's part of the observation is composed from the axes in one place per room (as the
// derivation's, observation_derivation): printing's filter reports and code generation take a
// linear h's part from its affine case (its filters are A0 + A x's), while the document, the
// coefficient form and eval repeat the rate as the model wrote it; the simulation plugin's truth
// observation is composed per axis value (the rate fills the matrices or writes observation_rate,
// the timing names them and the noise).
#include <catch2/catch.hpp>

#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/observation_report.hpp"

using namespace pfgen;

namespace {

Model with_observation(const std::string& observation) {
  return load_model_text("name: m\nstates: [x, y]\nparameters: {a: 0.5}\ndrift: [\"-x\", \"x - y\"]\n"
                         "diffusion: [[\"0.3\", \"0\"], [\"0\", \"0.3\"]]\nobservation:\n" + observation +
                             "\ninitial: {x0: prior, m0: [1, 0.5], P0: [[0.2, 0], [0, 0.2]]}\n",
                         "m.yaml");
}

const std::string kNoise = "\n  B: [[\"1\", \"0\"], [\"0\", \"1\"]]";

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("observation parts: A0 + A x as written takes the continuous parts everywhere", "[observation][axes][unit]") {
  const Model model = with_observation("  A: [[\"a\", \"2\"], [\"0\", \"1\"]]\n  A0: [\"3\", \"0\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &continuous_observation_report());
  CHECK(&observation_statement(model.observation) == &continuous_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &continuous_observation_evaluation());
  CHECK(&codegen::observation_code(model.observation) == &codegen::continuous_observation_code());
}

TEST_CASE("observation parts: a linear h's filters are A0 + A x's, its statement and eval its rows",
          "[observation][axes][unit]") {
  const Model model = with_observation("  h: [\"a*x + 2*y + 3\", \"y\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &continuous_observation_report());
  CHECK(&codegen::observation_code(model.observation) == &codegen::continuous_observation_code());
  CHECK(&observation_statement(model.observation) == &polynomial_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &polynomial_observation_evaluation());
}

TEST_CASE("observation parts: a nonlinear h takes the polynomial parts", "[observation][axes][unit]") {
  const Model model = with_observation("  h: [\"x^2 + y\", \"y\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &polynomial_observation_report());
  CHECK(&observation_statement(model.observation) == &polynomial_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &polynomial_observation_evaluation());
  CHECK(&codegen::observation_code(model.observation) == &codegen::polynomial_observation_code());
}

TEST_CASE("observation parts: the timing and the delay choose before the rate", "[observation][axes][unit]") {
  for (const std::string& samples : {std::string("  sampled: {period: 0.5, C: [[\"1\", \"0\"]], Uv: [[\"0.5\"]]}"),
                                     std::string("  sampled: {period: 0.5, c: [\"x^2\"], Uv: [[\"0.5\"]]}")}) {
    const Model model = with_observation(samples);
    CHECK(&observation_report(model.observation) == &sampled_observation_report());
    CHECK(&observation_statement(model.observation) == &sampled_observation_statement());
    CHECK(&observation_evaluation(model.observation) == &sampled_observation_evaluation());
    CHECK(&codegen::observation_code(model.observation) == &codegen::sampled_observation_code());
  }
  const Model delayed = with_observation("  A: [[\"1\", \"0\"], [\"0\", \"1\"]]\n  delay: 0.25" + kNoise);
  CHECK(&observation_report(delayed.observation) == &delayed_observation_report());
  CHECK(&observation_statement(delayed.observation) == &delayed_observation_statement());
  CHECK(&observation_evaluation(delayed.observation) == &delayed_observation_evaluation());
  CHECK(&codegen::observation_code(delayed.observation) == &codegen::delayed_observation_code());
}

TEST_CASE("observation parts: the truth's observation, the rate's matrices or rows named by the timing",
          "[observation][axes][plugin][unit]") {
  SECTION("increments of A0 + A x: observation and observation_noise, no rate function") {
    const codegen::TruthCode truth = codegen::generate_truth_code(with_observation("  A: [[\"1\", \"0\"]]\n  B: [[\"a\"]]"));
    CHECK_FALSE(truth.observation_is_sampled);
    CHECK_FALSE(truth.has_observation_rate);
    CHECK(has(truth.definitions, "inline void observation("));
    CHECK(has(truth.definitions, "inline void observation_noise("));
    CHECK_FALSE(has(truth.definitions, "observation_rate("));
  }
  SECTION("increments of a nonlinear h: zero matrices, then observation_rate") {
    const codegen::TruthCode truth = codegen::generate_truth_code(with_observation("  h: [\"x^2\"]\n  B: [[\"a\"]]"));
    CHECK_FALSE(truth.observation_is_sampled);
    CHECK(truth.has_observation_rate);
    CHECK(has(truth.definitions, "inline void observation_rate("));
    CHECK(has(truth.definitions, "inline void observation_noise("));
  }
  SECTION("samples through c: sampled_observation and observation_rate, no observation_noise") {
    const codegen::TruthCode truth =
        codegen::generate_truth_code(with_observation("  sampled: {period: 0.5, c: [\"x^2\"], Uv: [[\"0.5\"]]}"));
    CHECK(truth.observation_is_sampled);
    CHECK(truth.has_observation_rate);
    CHECK(has(truth.definitions, "inline void sampled_observation("));
    CHECK(has(truth.definitions, "inline void observation_rate("));
    CHECK_FALSE(has(truth.definitions, "observation_noise("));
    CHECK(truth.r == 1);
  }
}
