// The observation as three axes (model/observation_model.hpp): the rate (rows h(x, t) or A0 + A x,
// with its noise), the timing (continuous, or samples every T) and the delay. Every observation
// has a rate, which never throws; A0 + A x of rows of degree <= 1 is found once, when the model is
// built, against every declared state; the kind is a name derived from the axes.
//
// Each room's part of the observation is composed from the axes in one place per room (as the
// derivation's, observation_derivation): printing's filter reports and code generation take a
// linear h's part from its affine case (its filters are A0 + A x's), while the document, the
// coefficient form and eval repeat the rate as the model wrote it; the simulation plugin's truth
// observation is composed per axis value (the rate fills the matrices or writes observation_rate,
// the timing names them and the noise).
#include <catch2/catch.hpp>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/backends/cpp/truth_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/evaluation/observation_evaluation.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/observation_report.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

Model with_observation(const std::string& observation) {
  return load_model_text("name: m\nstates: [x, y]\nparameters: {a: 0.5}\ndrift: [\"-x\", \"x - y\"]\n"
                         "diffusion: [[\"0.3\", \"0\"], [\"0\", \"0.3\"]]\nobservation:\n" + observation +
                             "\ninitial: {x0: prior, m0: [1, 0.5], P0: [[0.2, 0], [0, 0.2]]}\n",
                         "m.yaml");
}

bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return (a - b).expand().is_zero(); }

const std::string kNoise = "\n  B: [[\"1\", \"0\"], [\"0\", \"1\"]]";

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("observation axes: rows of degree <= 1 carry their A0 + A x, found once", "[observation][axes][unit]") {
  const Model model = with_observation("  h: [\"a*x + 2*y + 3\", \"y\"]\n  B: [[\"1\", \"0\"], [\"0\", \"1\"]]");
  const ObservationRate& rate = model.observation.rate();
  CHECK(model.observation.kind() == ObservationKind::Polynomial);
  CHECK_FALSE(rate.written_affine());
  CHECK_FALSE(model.observation.samples());
  CHECK_FALSE(model.observation.delay_h());
  REQUIRE(rate.affine());
  const GiNaC::symbol a = model.parameters.front().symbol;
  CHECK(same(rate.affine()->A0[0], 3));
  CHECK(same(rate.affine()->A0[1], 0));
  CHECK(same(rate.affine()->A[0][0], a));
  CHECK(same(rate.affine()->A[0][1], 2));
  CHECK(same(rate.affine()->A[1][1], 1));
  CHECK(rate.affine()->B == rate.noise());
  CHECK(rate.degree(model.states) == 1);
}

TEST_CASE("observation axes: a nonlinear rate has rows and no affine case", "[observation][axes][unit]") {
  const Model model = load_model_file(pfgen_test::example("polynomial/cubic_sensor.yaml"));
  CHECK(model.observation.kind() == ObservationKind::Polynomial);
  CHECK_FALSE(model.observation.rate().affine());
  CHECK(model.observation.rate().degree(model.states) == 3);
  CHECK(model.observation.rate().polynomials(model.states).size() == model.p());
}

TEST_CASE("observation axes: samples have a rate too, and the timing holds the period", "[observation][axes][unit]") {
  const Model model = with_observation(
      "  sampled: {period: 0.5, substeps: 4, C: [[\"2\", \"a\"]], C0: [\"1\"], Uv: [[\"0.5\"]]}");
  CHECK(model.observation.kind() == ObservationKind::Sampled);
  REQUIRE(model.observation.samples());
  CHECK(model.observation.samples()->period == GiNaC::numeric(1, 2));
  CHECK(model.observation.samples()->substeps == std::optional<std::size_t>(4));
  // Before the axes, rate() threw for samples; now every observation has one.
  const ObservationRate& rate = model.observation.rate();
  CHECK(rate.p() == 1);
  CHECK(same(rate.noise()[0][0], GiNaC::numeric(1, 2)));
  REQUIRE(rate.affine());
  CHECK(same(rate.affine()->A[0][0], 2));
  // As polynomials in the states, whichever way written: 1 + 2 x + a y.
  const std::vector<Polynomial> rows = rate.polynomials(model.states);
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].degree() == 1);
  CHECK(rows[0].terms().size() == 3);
}

TEST_CASE("observation axes: samples through c of degree 2 keep their rows", "[observation][axes][unit]") {
  const Model model = with_observation("  sampled: {period: 0.5, c: [\"x^2 + y\"], Uv: [[\"0.5\"]]}");
  CHECK(model.observation.kind() == ObservationKind::Sampled);
  CHECK_FALSE(model.observation.rate().affine());
  CHECK(model.observation.rate().rows().size() == 1);
  CHECK(model.observation.rate().degree(model.states) == 2);
}

TEST_CASE("observation axes: the delay is its own axis", "[observation][axes][unit]") {
  const Model model = load_model_file(pfgen_test::example("delay_linear.yaml"));
  CHECK(model.observation.kind() == ObservationKind::Delayed);
  REQUIRE(model.observation.delay_h());
  CHECK(*model.observation.delay_h() == GiNaC::numeric(1, 2));
  CHECK_FALSE(model.observation.samples());
  REQUIRE(model.observation.rate().affine());
  CHECK(model.observation.rate().written_affine());
}

TEST_CASE("observation axes: rows are read against every state declared before build()", "[observation][axes][unit]") {
  // h names x only, and y is declared after it: the affine case has a column for y too.
  ModelBuilder builder("late_state");
  const GiNaC::symbol x = builder.state("x");
  builder.polynomial_observation({2 * x + 1}, {{1}});
  const GiNaC::symbol y = builder.state("y");
  builder.drift({-x, -y});
  builder.diffusion({{1, 0}, {0, 1}});
  InitialConditions initial;
  initial.m0 = {0, 0};
  initial.P0 = {{1, 0}, {0, 1}};
  builder.initial(initial);
  const Model model = builder.build();
  REQUIRE(model.observation.rate().affine());
  REQUIRE(model.observation.rate().affine()->A.size() == 1);
  CHECK(model.observation.rate().affine()->A[0].size() == 2);
  CHECK(same(model.observation.rate().affine()->A[0][0], 2));
  CHECK(same(model.observation.rate().affine()->A0[0], 1));
}

TEST_CASE("observation axes: the parts, A0 + A x as written takes the continuous parts everywhere", "[observation][axes][unit]") {
  const Model model = with_observation("  A: [[\"a\", \"2\"], [\"0\", \"1\"]]\n  A0: [\"3\", \"0\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &continuous_observation_report());
  CHECK(&observation_statement(model.observation) == &continuous_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &continuous_observation_evaluation());
  CHECK(&codegen::observation_code(model.observation) == &codegen::continuous_observation_code());
}

TEST_CASE("observation axes: the parts, a linear h's filters are A0 + A x's, its statement and eval its rows",
          "[observation][axes][unit]") {
  const Model model = with_observation("  h: [\"a*x + 2*y + 3\", \"y\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &continuous_observation_report());
  CHECK(&codegen::observation_code(model.observation) == &codegen::continuous_observation_code());
  CHECK(&observation_statement(model.observation) == &polynomial_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &polynomial_observation_evaluation());
}

TEST_CASE("observation axes: the parts, a nonlinear h takes the polynomial parts", "[observation][axes][unit]") {
  const Model model = with_observation("  h: [\"x^2 + y\", \"y\"]" + kNoise);
  CHECK(&observation_report(model.observation) == &polynomial_observation_report());
  CHECK(&observation_statement(model.observation) == &polynomial_observation_statement());
  CHECK(&observation_evaluation(model.observation) == &polynomial_observation_evaluation());
  CHECK(&codegen::observation_code(model.observation) == &codegen::polynomial_observation_code());
}

TEST_CASE("observation axes: the parts, the timing and the delay choose before the rate", "[observation][axes][unit]") {
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

TEST_CASE("observation axes: the parts, the truth's observation, the rate's matrices or rows named by the timing",
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
