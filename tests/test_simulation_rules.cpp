// `pfgen simulate`'s settings obey one set of rules (model/simulation_rules.hpp): a value broken
// in the model file's `simulation:` section and the same value given on the command line are
// refused with the same words, and only the place in front differs (the field's file:line:col,
// or the option).
#include <catch2/catch.hpp>

#include <regex>

#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen;
using namespace pfgen_test;

namespace {

Model example_model() { return load_model_file(example("basin2006_quadratic.yaml")); }

}  // namespace

TEST_CASE("simulation rules: each rule names its field and entry, and applies once its inputs are known",
          "[unit][simulation]") {
  const Model model = example_model();
  auto breach_of = [&model](const SimulationSection& s) { return check_simulation_settings(model, s); };

  SimulationSection s;
  CHECK(!breach_of(s));  // nothing given, nothing to break
  s.dt = 0.3;
  CHECK(!breach_of(s));  // no T yet: "a whole number of steps" cannot apply
  s.T = 1;
  auto whole = breach_of(s);
  REQUIRE(whole);
  CHECK(whole->field == "dt");
  CHECK(whole->message == "T = 1 is not a whole number of steps of 0.3 (T / dt = 3.3333333333333335); choose a dt "
                          "that divides T");
  s.dt = 0.25;
  CHECK(!breach_of(s));

  s.windows = {{0, 0.5}, {0.5, 2}};
  auto window = breach_of(s);
  REQUIRE(window);
  CHECK(window->field == "windows");
  CHECK(window->entry == std::optional<std::size_t>(1));
  CHECK(window->message == "window [0.5, 2] ends after the horizon T = 1");
  s.windows = {{0.5, 0.6}};  // both ends snap to the grid point 0.5
  window = breach_of(s);
  REQUIRE(window);
  CHECK(window->message == "window [0.5, 0.6] is shorter than a step dt = 0.25");
  s.windows.clear();

  s.filters = std::vector<std::string>{"optimal", "kalman"};
  auto filter = breach_of(s);
  REQUIRE(filter);
  CHECK(filter->field == "filters");
  CHECK(filter->entry == std::optional<std::size_t>(1));
  CHECK(filter->message == "unknown filter 'kalman' (known: optimal, ekf, additive, ekf-additive, ukf, closure3, closure4, ekf-printed)");
  s.filters = std::vector<std::string>{"ekf", "ekf"};
  REQUIRE(breach_of(s));
  CHECK(breach_of(s)->message == "filter 'ekf' is listed twice");
  s.filters.reset();

  s.scheme = "rk4";  // paper 000's diffusion is not zero
  REQUIRE(breach_of(s));
  CHECK(breach_of(s)->message == "rk4 is for deterministic truths only, and this model's diffusion is not zero");
  s.scheme = "adaptive-euler";
  s.runs = 3;
  s.shown_run = 3;
  REQUIRE(breach_of(s));
  CHECK(breach_of(s)->field == "shown_run");
  s.shown_run = 2;
  CHECK(!breach_of(s));
}

TEST_CASE("simulation rules: the model file and the command line refuse a value with the same words",
          "[integration][simulation]") {
  TempDir dir;
  const std::string original = read_file(example("basin2006_quadratic.yaml"));
  struct Case {
    std::string field_line;  // replaces the field's line in the example's simulation: section
    std::vector<std::string> option;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"  T: -1", {"--T", "-1"}, "the horizon T (the simulation starts at t = 0) must be a number greater than 0, found -1"},
      {"  dt: 0.3", {"--dt", "0.3"}, "T = 9.2 is not a whole number of steps of 0.3"},
      {"  runs: 0", {"--runs", "0"}, "at least 1 run is required"},
      {"  scheme: rk4", {"--scheme", "rk4"}, "rk4 is for deterministic truths only"},
      {"  scheme: heun", {"--scheme", "heun"}, "unknown scheme 'heun' (known: auto, euler-maruyama,"},
      {"  filters: [optimal, kalman]", {"--filters", "optimal,kalman"}, "unknown filter 'kalman' (known: optimal,"},
      {"  filters: [ekf, ekf]", {"--filters", "ekf,ekf"}, "filter 'ekf' is listed twice"},
      {"  report_times: [2, 10]", {"--report-times", "2,10"}, "report time 10 is after the horizon T = 9.2"},
      {"  windows: [[0, 4], [4, 10]]", {"--windows", "0:4,4:10"}, "window [4, 10] ends after the horizon T = 9.2"},
  };
  for (const Case& c : cases) {
    INFO(c.field_line);
    const std::string key = c.field_line.substr(0, c.field_line.find(':') + 1);
    const std::string text = std::regex_replace(original, std::regex("\n" + key + "[^\n]*"), "\n" + c.field_line);
    REQUIRE(text != original);
    write_file(dir.file("m.yaml"), text);
    ProcessResult from_file = run_pfgen({"derive", dir.file("m.yaml")});
    INFO("file: " << from_file.err);
    CHECK(from_file.exit_code != 0);
    CHECK(std::regex_search(from_file.err, std::regex("m\\.yaml:[0-9]+:[0-9]+: error: field 'simulation\\.")));
    CHECK(from_file.err.find(c.message) != std::string::npos);

    std::vector<std::string> args{"simulate", example("basin2006_quadratic.yaml"), "--cache-dir", dir.file("cache")};
    args.insert(args.end(), c.option.begin(), c.option.end());
    ProcessResult from_command_line = run_pfgen(args);
    INFO("command line: " << from_command_line.err);
    CHECK(from_command_line.exit_code != 0);
    CHECK(from_command_line.err.find("pfgen: error: " + c.option[0] + ": ") == 0);
    CHECK(from_command_line.err.find(c.message) != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("cache")));  // refused before anything is compiled
}

TEST_CASE("simulation rules: one budget of 1e9 steps per run, the truth's and each sampled filter's sub-steps",
          "[unit][simulation]") {
  const Model model = load_model_file(example("paper003/example1_gamma0.yaml"));  // period 1, substeps 10
  auto breach_of = [&model](const SimulationSection& s) { return check_simulation_settings(model, s); };
  SimulationSection s;
  s.T = 2000;
  s.dt = 0.01;
  s.filters = std::vector<std::string>{"cd-optimal", "cd-euler@100000"};  // 2e8 sub-steps: within
  CHECK(!breach_of(s));
  s.filters = std::vector<std::string>{"cd-optimal", "cd-euler@1000000"};  // 2e9: beyond, like 2e9 truth steps
  auto filters = breach_of(s);
  REQUIRE(filters);
  CHECK(filters->field == "filters");
  CHECK(filters->entry == std::optional<std::size_t>(1));
  CHECK(filters->message.find("filter 'cd-euler@1000000' would take 2e+09 prediction sub-steps per run") == 0);
  CHECK(filters->message.find("the budget of one run is 1e9 steps") != std::string::npos);
  // The model's own substeps with no filters given: the horizon is what breaks the budget.
  s.filters.reset();
  s.T = 2e8;
  s.dt = 1;
  auto horizon = breach_of(s);
  REQUIRE(horizon);
  CHECK(horizon->field == "T");
  s.dt = 0.1;  // 2e9 truth steps: the same budget
  auto truth = breach_of(s);
  REQUIRE(truth);
  CHECK(truth->field == "dt");
  CHECK(truth->message.find("more than 1e9 steps") == 0);
}

TEST_CASE("simulation rules: a job's dt must divide a sampled model's period, a model file's alone need not",
          "[unit][simulation]") {
  const Model model = load_model_file(example("paper003/example1_gamma0.yaml"));  // period 1
  SimulationSection s;
  s.T = 3;
  s.dt = 0.3;
  // At load the file's dt is a default the command line may replace: no rule holds it to the period.
  CHECK(!check_simulation_settings(model, s));
  auto period = check_simulation_job(model, s);
  REQUIRE(period);
  CHECK(period->field == "dt");
  CHECK(period->model_field == "observation.sampled.period");  // named at the model's period
  CHECK(period->message == "the sampling period 1 is not a whole number of steps dt = 0.29999999999999999 "
                           "(T/dt = 3.3333333333333335); choose --dt = T/N");
  s.dt = 1.5;  // a whole number of steps of T, but more than the period
  REQUIRE(check_simulation_job(model, s));
  CHECK(check_simulation_job(model, s)->message.find("(T/dt = 0.66666666666666663)") != std::string::npos);
  s.dt = 0.25;
  CHECK(!check_simulation_job(model, s));
  // The rules the file shares come first: a runs of 0 is named before the period.
  s.dt = 0.3;
  s.runs = 0;
  REQUIRE(check_simulation_job(model, s));
  CHECK(check_simulation_job(model, s)->field == "runs");
  CHECK(check_simulation_job(model, s)->model_field.empty());
}

TEST_CASE("simulation rules: the truth scheme auto stands for follows the model's drift and diffusion",
          "[unit][simulation]") {
  auto scheme_of = [](const std::string& drift, const std::string& diffusion) {
    return choose_truth_scheme(load_model_text("name: s\nstates: [x]\ndrift: [\"" + drift + "\"]\ndiffusion: [[\"" +
                                                   diffusion + "\"]]\nobservation: {A: [[\"1\"]], B: [[\"1\"]]}\n",
                                               "s.yaml"));
  };
  CHECK(scheme_of("-x", "0") == "rk4");                          // no noise
  CHECK(scheme_of("-x", "0.3") == "euler-maruyama");             // additive noise
  CHECK(scheme_of("-x", "0.3*x") == "milstein");                 // g linear in x
  CHECK(scheme_of("-x^3", "0.3") == "adaptive-euler");           // superlinear drift
  CHECK(scheme_of("-x", "0.1*x^2") == "adaptive-euler");         // superlinear diffusion
  CHECK(choose_truth_scheme(example_model()) == "adaptive-euler");  // 0.1 x^2 dt + 0.1 x^2 dW
}
