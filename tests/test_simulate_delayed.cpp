// `pfgen simulate` of models with delayed observations, dy = (A0 + A x(t - h)) dt + B dW2: the
// rules refuse an h that is not a whole number of steps dt (model file and command line alike,
// and a huge h / dt before anything is allocated); the plugin of an h = 0 model steps its delay
// filters exactly as the undelayed kinds' plugin does; end to end, every delay kind and a user
// filter run on the same delayed observations, with output identical for 1 and 2 threads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

// Paper 004's example shape with state noise, small enough to simulate in a moment; h = 0.2.
// The user filter is paper 004's uncorrected filter written out (gain P, delayed innovation).
const char* const kDelayedModel = R"(name: delayed_growth
states: [x]
drift: ["0.09*x^2"]
diffusion: [["0.1"]]
observation: {delay: 0.2, A: [["1"]], B: [["1"]]}
initial: {x0: [1.1], m0: [0.1], P0: [[1]]}
filters:
  printed:
    m_drift: ["0.09*m1^2 + 0.09*P11"]
    P_drift: [["0.36*m1*P11 + 0.01 - P11^2"]]
    gain: [["P11"]]
)";

std::string with_simulation(const std::string& settings) { return std::string(kDelayedModel) + settings; }

std::size_t lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE("simulate delayed: the rules refuse an h that is not a whole number of steps dt", "[simulate][delayed][unit]") {
  const pfgen::Model model = pfgen::load_model_text(kDelayedModel, "delayed.yaml");
  pfgen::SimulationSection s;
  s.dt = 0.05;  // h = 4 dt
  CHECK(!pfgen::check_simulation_settings(model, s));
  s.dt = 0.1;  // 0.2 / 0.1 = 2 exactly in decimal, 2.0000000000000004 in doubles: within 1e-9
  CHECK(!pfgen::check_simulation_settings(model, s));
  s.dt = 0.03;
  auto breach = pfgen::check_simulation_settings(model, s);
  REQUIRE(breach);
  CHECK(breach->field == "dt");
  CHECK(breach->message.find("observation.delay") == 0);
  CHECK(breach->message.find("h = 0.2") != std::string::npos);
  CHECK(breach->message.find("dt = 0.03") != std::string::npos);
  s.dt = 1e-9;  // 2e8 steps of history: refused before anything is allocated
  breach = pfgen::check_simulation_settings(model, s);
  REQUIRE(breach);
  CHECK(breach->message.find("10000000") != std::string::npos);
  // A model without a delay has no such rule.
  const pfgen::Model undelayed =
      pfgen::load_model_text(std::regex_replace(kDelayedModel, std::regex("delay: 0.2, "), ""), "undelayed.yaml");
  s.dt = 0.03;
  CHECK(!pfgen::check_simulation_settings(undelayed, s));
}

TEST_CASE("simulate delayed: h not a whole number of steps is a one-line error, from --dt or the model file",
          "[simulate][delayed][bad_input][integration]") {
  TempDir dir;
  write_file(dir.file("d.yaml"), kDelayedModel);
  const auto from_option =
      run_pfgen({"simulate", dir.file("d.yaml"), "--cache-dir", dir.file("cache"), "--T", "0.9", "--dt", "0.03"});
  CHECK(from_option.exit_code != 0);
  CHECK(lines(from_option.err) == 1);
  CHECK(from_option.err.find("--dt: observation.delay") != std::string::npos);
  CHECK(from_option.err.find("h = 0.2") != std::string::npos);
  CHECK(from_option.out.empty());

  write_file(dir.file("file.yaml"), with_simulation("simulation: {T: 0.9, dt: 0.03}\n"));
  const auto from_file = run_pfgen({"simulate", dir.file("file.yaml"), "--cache-dir", dir.file("cache")});
  CHECK(from_file.exit_code != 0);
  CHECK(lines(from_file.err) == 1);
  CHECK(from_file.err.find("simulation.dt") != std::string::npos);
  CHECK(from_file.err.find("observation.delay") != std::string::npos);
  CHECK(from_file.err.find("dt = 0.03") != std::string::npos);

  const auto huge = run_pfgen({"simulate", dir.file("d.yaml"), "--cache-dir", dir.file("cache"), "--T", "0.001",
                               "--dt", "1e-8"});
  CHECK(huge.exit_code != 0);
  CHECK(lines(huge.err) == 1);
  CHECK(huge.err.find("10000000") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("cache")));  // refused before any build
}

TEST_CASE("simulate delayed: every filter on the same delayed observations, the same output on 1 and 2 threads",
          "[simulate][delayed][compiler]") {
  TempDir dir;
  write_file(dir.file("d.yaml"), kDelayedModel);
  auto run = [&](const std::string& threads, const std::string& csv) {
    return run_pfgen({"simulate", dir.file("d.yaml"), "--cache-dir", dir.file("cache"), "--runs", "6", "--T", "2",
                      "--dt", "0.01", "--report-times", "0.1,1,2", "--threads", threads, "-o", dir.file(csv), "-q"});
  };
  const auto one = run("1", "one.csv"), two = run("2", "two.csv");
  INFO(one.out << one.err);
  REQUIRE(one.exit_code == 0);
  REQUIRE(two.exit_code == 0);
  auto without_csv_line = [](std::string text) { return std::regex_replace(text, std::regex("csv: .*\n"), ""); };
  CHECK(without_csv_line(one.out) == without_csv_line(two.out));
  CHECK(read_file(dir.file("one.csv")) == read_file(dir.file("two.csv")));
  CHECK(one.out.find("observation delay h = 0.2 = 20 steps of dt = 0.01") != std::string::npos);
  for (const char* filter : {"delay-optimal", "delay-uncorrected", "delay-ekf", "printed"}) {
    INFO(filter);
    CHECK(one.out.find(std::string("\n") + filter + " ") != std::string::npos);
    CHECK(read_file(dir.file("one.csv")).find(std::string(filter) + "_m_x") != std::string::npos);
  }
  CHECK(one.out.find("nan") == std::string::npos);
}

TEST_CASE("simulate delayed: with h = 0 the plugin's delay filters step as the undelayed kinds' plugin does",
          "[simulate][delayed][plugin][compiler]") {
  // One model twice: dy = (A x(t - 0)) dt + B dW2 through the delayed filters, and the ordinary
  // observation through optimal and ekf. Multiplicative noise and a quadratic drift, so the
  // Gaussian-closure terms are all present.
  auto build = [](bool delayed) {
    pfgen::ModelBuilder b(delayed ? "h0_delayed" : "h0_plain");
    const GiNaC::symbol x = b.state("x");
    b.drift({-GiNaC::numeric(1, 2) * x + GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)});
    b.diffusion({{GiNaC::numeric(1, 5) + GiNaC::numeric(1, 10) * x}});
    if (delayed) b.delayed_observation(0, {GiNaC::numeric(1, 4)}, {{2}}, {{GiNaC::numeric(1, 2)}});
    else b.observation({GiNaC::numeric(1, 4)}, {{2}}, {{GiNaC::numeric(1, 2)}});
    pfgen::InitialConditions initial;
    initial.x0 = {GiNaC::numeric(1)};
    initial.m0 = {GiNaC::numeric(1, 2)};
    initial.P0 = {{GiNaC::numeric(1, 3)}};
    b.initial(initial);
    return b.build();
  };
  const double dt = 0.01;
  TempDir dir;
  pfgen::toolchain::PluginBuildOptions options;
  options.cache_dir = dir.file("cache");
  auto load = [&](const pfgen::Model& model, const std::vector<std::string>& names) {
    std::vector<pfgen::FilterEquations> filters;
    for (const std::string& name : names) filters.push_back(pfgen::derive_named_filter(model, name));
    const std::string source = pfgen::codegen::generate_simulation_plugin(model, filters, dt);
    return pfgen_runtime::SimulationPlugin(pfgen::toolchain::build_plugin(source, options).path);
  };
  const pfgen_runtime::SimulationPlugin delayed = load(build(true), {"delay-optimal", "delay-uncorrected", "delay-ekf"});
  const pfgen_runtime::SimulationPlugin plain = load(build(false), {"optimal", "ekf"});
  CHECK(delayed.observation().delay() == 0.0);
  delayed.check_grid_step(dt);
  CHECK_THROWS_WITH(delayed.check_grid_step(0.02), Catch::Contains("generated for the grid step dt = 0.01"));

  const auto delayed_filters = delayed.filters(), plain_filters = plain.filters();
  REQUIRE(delayed_filters.size() == 3);
  CHECK(dynamic_cast<const pfgen_runtime::FixedSteps&>(*delayed_filters[0].timing).fixed_dt() == dt);
  auto scheme = pfgen_runtime::make_scheme(pfgen_runtime::SchemeKind::euler_maruyama, plain.system());
  pfgen_runtime::Observation observation = plain.observation();
  const pfgen_runtime::TimeGrid grid = pfgen_runtime::TimeGrid::to_horizon(0.0, 3.0, dt);
  const pfgen_runtime::TruthRun truth =
      pfgen_runtime::simulate_truth(*scheme, observation, plain.truth_initial_state(), grid, 5, 0);
  REQUIRE(truth.completed_steps == grid.steps);

  pfgen_runtime::FilterGuardOptions fixed;
  fixed.stepping.adaptive = false;  // the undelayed filters too: one step() per grid step
  // delay-optimal and delay-uncorrected are optimal at h = 0 (Phi* = I), delay-ekf is ekf.
  const std::pair<std::size_t, std::size_t> pairs[] = {{0, 0}, {1, 0}, {2, 1}};
  for (const auto& [d, u] : pairs) {
    INFO(delayed_filters[d].name << " against " << plain_filters[u].name);
    const pfgen_runtime::FilterRun a = pfgen_runtime::run_filter(delayed_filters[d], truth, fixed);
    const pfgen_runtime::FilterRun b = pfgen_runtime::run_filter(plain_filters[u], truth, fixed);
    REQUIRE(a.completed_steps == grid.steps);
    REQUIRE(b.completed_steps == grid.steps);
    REQUIRE(a.state.rows() == b.state.rows());
    double largest = 0;
    for (Eigen::Index c = 0; c < a.state.cols(); ++c)
      for (Eigen::Index i = 0; i < a.state.rows(); ++i)
        largest = std::max(largest, std::abs(a.state(i, c) - b.state(i, c)) / (1 + std::abs(b.state(i, c))));
    CHECK(largest < 1e-12);
  }
}
