// Simulation plugins (pfgen simulate's compiled model): the generated source compiled by the
// system compiler through the cache, loaded with dlopen, and checked against the model itself.
// The truth's f, g and dg/dx against GiNaC at random points (and dg/dx against central
// differences), the observation and x0 against the model, each filter's step against a Heun
// step built by hand from pfgen's exact evaluation (and against the checked-in headers of
// generated/), then the cache and the errors. One cache directory serves the whole file, and
// each plugin is compiled once.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include "generated/basin2006_quadratic/additive.hpp"
#include "generated/basin2006_quadratic/ekf.hpp"
#include "generated/basin2006_quadratic/ekf_additive.hpp"
#include "generated/basin2006_quadratic/optimal.hpp"
#include "generated/basin_skliar_partial/ekf.hpp"
#include "generated/basin_skliar_partial/optimal.hpp"
#include "pfgen/codegen/backends/cpp/simulation_plugin.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/toolchain/plugin_compiler.hpp"
#include "pfgen_runtime/simulation_plugin.hpp"
#include "support/random_polynomial_system.hpp"
#include "support/exact_rational.hpp"
#include "support/test_paths.hpp"

namespace fs = std::filesystem;
using pfgen_runtime::SimulationPlugin;
using pfgen_test::exact;

namespace {

// A temporary directory for the whole run: the plugin cache, and a compiler wrapper that
// counts how often the compiler is run (to show that a cache hit runs none).
struct Workspace {
  fs::path root;
  Workspace() {
    char name[] = "/tmp/pfgen-plugin-test-XXXXXX";
    if (!::mkdtemp(name)) throw std::runtime_error("mkdtemp failed");
    root = name;
    std::ofstream script(compiler());
    script << "#!/bin/sh\necho run >> '" << runs_file().string() << "'\nexec " << pfgen::toolchain::default_compiler()
           << " \"$@\"\n";
    script.close();
    fs::permissions(compiler(), fs::perms::owner_all);
  }
  ~Workspace() {
    std::error_code ignored;
    fs::remove_all(root, ignored);
  }
  fs::path cache() const { return root / "cache"; }
  fs::path compiler() const { return root / "counting-c++"; }
  fs::path runs_file() const { return root / "compiler-runs"; }
  std::size_t compiler_runs() const {
    std::ifstream in(runs_file());
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    return lines;
  }
  pfgen::toolchain::PluginBuildOptions options() const {
    pfgen::toolchain::PluginBuildOptions options;
    options.compiler = compiler().string();
    options.cache_dir = cache().string();
    return options;
  }
};

Workspace& workspace() {
  static Workspace w;
  return w;
}

// Every filter the model offers: the built-in kinds it supports, then its user filters. Not the moment filters
// (closure3, closure4), whose state goes on past m and P and whose step is not the hand-written Heun step these
// cases check: their generated functions and step are checked in test_generated_polynomial.cpp, their plugin
// in test_record_data.cpp ("simulate stops a moment filter's run ...").
std::vector<pfgen::FilterEquations> all_filters(const pfgen::Model& model) {
  std::vector<pfgen::FilterEquations> filters;
  for (const std::string& name : pfgen::available_filter_names(model)) {
    if (const auto kind = pfgen::parse_filter_kind(name); kind && pfgen::uses_cumulant_closure(*kind)) continue;
    filters.push_back(pfgen::derive_named_filter(model, name));
  }
  return filters;
}

struct Built {
  std::string source;
  pfgen::toolchain::PluginBuild build;
};

// Each plugin compiled once per run, whichever test asks first.
const Built& built(const std::string& label, const pfgen::Model& model, const std::vector<pfgen::FilterEquations>& filters) {
  static std::map<std::string, Built> done;
  auto it = done.find(label);
  if (it != done.end()) return it->second;
  Built b;
  b.source = pfgen::codegen::generate_simulation_plugin(model, filters);
  b.build = pfgen::toolchain::build_plugin(b.source, workspace().options());
  WARN(label << ": compiled in " << b.build.compile_seconds << " s (" << b.source.size() << " bytes of source)");
  return done.emplace(label, std::move(b)).first->second;
}

// The model's expression e at (t, x) and the parameters' defaults, in GiNaC, rounded once.
double evaluate(const pfgen::Model& model, const GiNaC::ex& e, double t, const std::vector<double>& x) {
  GiNaC::exmap values;
  for (std::size_t i = 0; i < model.n(); ++i) values[model.states[i]] = exact(x[i]);
  for (const auto& p : model.parameters) values[p.symbol] = p.default_value;
  values[model.time] = exact(t);
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(values).evalf()).to_double();
}

void check_close(const std::vector<double>& got, const std::vector<double>& expected, double tolerance,
                 const std::string& what) {
  REQUIRE(got.size() == expected.size());
  double scale = 0;
  for (double v : expected) scale = std::max(scale, std::abs(v));
  for (std::size_t k = 0; k < got.size(); ++k) {
    INFO(what << "[" << k << "]: plugin " << got[k] << ", reference " << expected[k]);
    CHECK(std::abs(got[k] - expected[k]) <= tolerance * scale);
  }
}

std::vector<double> random_vector(std::mt19937& rng, std::size_t size, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(size);
  for (double& value : v) value = u(rng);
  return v;
}

// f, g, dg/dx (GiNaC and central differences), G when only G is given.
// Each batched function of the table gives, lane by lane, the bits of its one-state function
// (or is absent exactly when that is), for batches of 1, 5 and 32 random states.
void check_batches(const SimulationPlugin& plugin) {
  const pfgen_plugin& table = plugin.table();
  CHECK((table.diffusion_batch != nullptr) == (table.diffusion != nullptr));
  CHECK((table.observation_rate_batch != nullptr) == (table.observation_rate != nullptr));
  REQUIRE(table.drift_batch != nullptr);
  using One = void (*)(double, const double*, double*);
  using Many = void (*)(double, std::size_t, const double*, double*);
  const std::size_t n = table.n;
  auto check = [&](const char* what, One one, Many many, std::size_t outputs) {
    std::mt19937 rng(99);
    for (const std::size_t count : {1, 5, 32}) {
      const double t = random_vector(rng, 1, 0, 3)[0];
      const std::vector<double> x = random_vector(rng, n * count, -3, 3);
      std::vector<double> batch(outputs * count, 0.0), lane(n), value(outputs);
      many(t, count, x.data(), batch.data());
      for (std::size_t k = 0; k < count; ++k) {
        for (std::size_t i = 0; i < n; ++i) lane[i] = x[i * count + k];
        one(t, lane.data(), value.data());
        for (std::size_t e = 0; e < outputs; ++e) {
          INFO(what << ": lane " << k << " of " << count << ", entry " << e);
          CHECK(std::memcmp(&batch[e * count + k], &value[e], sizeof(double)) == 0);
        }
      }
    }
  };
  check("drift", table.drift, table.drift_batch, n);
  if (table.diffusion) check("diffusion", table.diffusion, table.diffusion_batch, n * table.q);
  if (table.observation_rate) check("observation rate", table.observation_rate, table.observation_rate_batch, table.p);
}

void check_truth(const pfgen::Model& model, const SimulationPlugin& plugin) {
  check_batches(plugin);
  const std::size_t n = model.n();
  const pfgen_runtime::SdeSystem system = plugin.system();
  REQUIRE(system.n == n);
  std::mt19937 rng(2024);
  for (int sample = 0; sample < 20; ++sample) {
    const std::vector<double> x = random_vector(rng, n, -2, 2);
    const double t = random_vector(rng, 1, 0, 3)[0];
    std::vector<double> f(n), f_expected;
    system.drift(t, x.data(), f.data());
    for (const auto& e : model.drift) f_expected.push_back(evaluate(model, e, t, x));
    check_close(f, f_expected, 1e-12, "f");
    if (plugin.diffusion_is_zero()) continue;

    const std::size_t q = system.q;
    std::vector<double> g(n * q);
    system.diffusion(t, x.data(), g.data());
    if (!model.diffusion.g) {  // g = sqrt(G): check g g^T = G
      std::vector<double> ggT(n * n, 0), G;
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
          for (std::size_t k = 0; k < q; ++k) ggT[i * n + j] += g[i * q + k] * g[j * q + k];
          G.push_back(evaluate(model, model.diffusion.G[i][j], t, x));
        }
      check_close(ggT, G, 1e-12, "g g^T");
      continue;
    }
    std::vector<double> g_expected, dg(n * q * n), dg_expected, dg_numeric;
    system.diffusion_jacobian(t, x.data(), dg.data());
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < q; ++j) {
        const GiNaC::ex& gij = (*model.diffusion.g)[i][j];
        g_expected.push_back(evaluate(model, gij, t, x));
        for (std::size_t l = 0; l < n; ++l) {
          dg_expected.push_back(evaluate(model, gij.diff(model.states[l]), t, x));
          const double h = 1e-5 * (1 + std::abs(x[l]));
          std::vector<double> up = x, down = x, g_up(n * q), g_down(n * q);
          up[l] += h;
          down[l] -= h;
          system.diffusion(t, up.data(), g_up.data());
          system.diffusion(t, down.data(), g_down.data());
          dg_numeric.push_back((g_up[i * q + j] - g_down[i * q + j]) / (up[l] - down[l]));
        }
      }
    check_close(g, g_expected, 1e-12, "g");
    check_close(dg, dg_expected, 1e-12, "dg/dx");
    check_close(dg, dg_numeric, 1e-7, "dg/dx against central differences");
  }
}

void check_observation(const pfgen::Model& model, const SimulationPlugin& plugin) {
  const std::size_t n = model.n(), p = model.p(), r = model.observation.rate().noise().front().size();
  REQUIRE(plugin.p() == p);
  REQUIRE(plugin.r() == r);
  pfgen_runtime::Observation observation = plugin.observation();
  for (double t : {0.0, 0.7, 2.5}) {
    // The rate A0 + A x at unit vectors x = e_j gives A0 and each column of A.
    const std::vector<double> none(n, 0.0);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    std::vector<double> A0(p), A0_expected;
    Eigen::VectorXd h0(static_cast<Eigen::Index>(p));
    observation.rate().value(t, x.data(), h0.data());
    for (std::size_t i = 0; i < p; ++i) {
      A0[i] = h0[static_cast<Eigen::Index>(i)];
      A0_expected.push_back(evaluate(model, model.observation.rate().affine()->A0[i], t, none));
    }
    check_close(A0, A0_expected, 1e-14, "A0");
    for (std::size_t j = 0; j < n; ++j) {
      x.setZero();
      x[static_cast<Eigen::Index>(j)] = 1;
      Eigen::VectorXd h(static_cast<Eigen::Index>(p));
      observation.rate().value(t, x.data(), h.data());
      std::vector<double> column, expected;
      for (std::size_t i = 0; i < p; ++i) {
        column.push_back(h[static_cast<Eigen::Index>(i)] - h0[static_cast<Eigen::Index>(i)]);
        expected.push_back(evaluate(model, model.observation.rate().affine()->A[i][j], t, none));
      }
      check_close(column, expected, 1e-14, "A column");
    }
    // B through the raw table (Observation does not expose it).
    std::vector<double> raw_A0(p), raw_A(p * n), B(p * r), B_expected;
    plugin.table().observation(t, raw_A0.data(), raw_A.data(), B.data());
    for (std::size_t i = 0; i < p; ++i)
      for (std::size_t k = 0; k < r; ++k) B_expected.push_back(evaluate(model, model.observation.rate().noise()[i][k], t, none));
    check_close(B, B_expected, 1e-14, "B");
  }
}

void check_initial_states(const pfgen::Model& model, const SimulationPlugin& plugin) {
  const bool has_x0 = model.initial && !model.initial->x0.empty();
  REQUIRE(plugin.has_truth_initial_state() == has_x0);
  if (!has_x0) {
    CHECK_THROWS_AS(plugin.truth_initial_state(), pfgen_runtime::PluginLoadError);
    return;
  }
  const Eigen::VectorXd x0 = plugin.truth_initial_state();
  for (std::size_t i = 0; i < model.n(); ++i) CHECK(x0[static_cast<Eigen::Index>(i)] == model.initial->x0[i].to_double());
}

// The change of the filter state over [t, t+dt] to first order, from pfgen's exact
// evaluation: [m_drift - K (A0 + A m)] dt + K dy; P_drift dt.
std::vector<double> increment(const pfgen::Model& model, const pfgen::FilterEquations& eq, double t,
                              const std::vector<double>& state, double dt, const std::vector<double>& dy) {
  const std::size_t n = model.n(), p = model.p();
  pfgen::EvaluationPoint point;
  point.t = exact(t);
  point.P.assign(n, std::vector<GiNaC::numeric>(n));
  std::size_t k = n;
  for (std::size_t i = 0; i < n; ++i) point.m.push_back(exact(state[i]));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) point.P[i][j] = point.P[j][i] = exact(state[k++]);
  const pfgen::EvaluatedFilter value = pfgen::evaluate_at(model, eq, point);
  std::vector<double> m(state.begin(), state.begin() + static_cast<long>(n)), delta;
  for (std::size_t i = 0; i < n; ++i) {
    double d = value.m_drift[i] * dt;
    for (std::size_t r = 0; r < p; ++r) {
      double h = evaluate(model, model.observation.rate().affine()->A0[r], t, m);
      for (std::size_t j = 0; j < n; ++j) h += evaluate(model, model.observation.rate().affine()->A[r][j], t, m) * m[j];
      d += value.gain[i][r] * (dy[r] - h * dt);
    }
    delta.push_back(d);
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) delta.push_back(value.P_drift[i][j] * dt);
  return delta;
}

std::vector<double> heun_step(const pfgen::Model& model, const pfgen::FilterEquations& eq, double t,
                              const std::vector<double>& state, double dt, const std::vector<double>& dy) {
  const std::vector<double> first = increment(model, eq, t, state, dt, dy);
  std::vector<double> predicted = state, out = state;
  for (std::size_t i = 0; i < state.size(); ++i) predicted[i] += first[i];
  const std::vector<double> second = increment(model, eq, t + dt, predicted, dt, dy);
  for (std::size_t i = 0; i < state.size(); ++i) out[i] += (first[i] + second[i]) / 2;
  return out;
}

// A random state with P = L L^T + I/10 (positive definite).
std::vector<double> random_state(std::mt19937& rng, std::size_t n) {
  std::vector<double> state = random_vector(rng, n, -1.5, 1.5);
  const std::vector<double> L = random_vector(rng, n * n, -1, 1);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      double s = i == j ? 0.1 : 0;
      for (std::size_t k = 0; k <= std::min(i, j); ++k) s += L[i * n + k] * L[j * n + k];
      state.push_back(s);
    }
  return state;
}

using ReferenceStep = std::function<void(double* state, double t, double dt, const double* dy)>;

// Initial state from m0, P0; then steps at random states against Heun by hand (and against
// the checked-in generated header when there is one).
void check_filters(const pfgen::Model& model, const std::vector<pfgen::FilterEquations>& equations,
                   const SimulationPlugin& plugin, const std::map<std::string, ReferenceStep>& headers = {}) {
  const std::vector<pfgen_runtime::FilterModel> filters = plugin.filters();
  REQUIRE(filters.size() == equations.size());
  std::mt19937 rng(99);
  for (std::size_t k = 0; k < filters.size(); ++k) {
    const pfgen_runtime::FilterModel& filter = filters[k];
    INFO("filter " << filter.name);
    CHECK(filter.name == equations[k].name);
    REQUIRE(filter.n == model.n());
    REQUIRE(filter.p == model.p());
    std::vector<double> initial(filter.state_size()), expected_initial;
    filter.initial_state(initial.data());
    for (std::size_t i = 0; i < model.n(); ++i) expected_initial.push_back(model.initial ? model.initial->m0[i].to_double() : 0);
    for (std::size_t i = 0; i < model.n(); ++i)
      for (std::size_t j = i; j < model.n(); ++j)
        expected_initial.push_back(model.initial ? model.initial->P0[i][j].to_double() : 0);
    CHECK(initial == expected_initial);
    // A continuous model's filters step on the grid (GridSteps).
    const auto& grid_steps = dynamic_cast<const pfgen_runtime::GridSteps&>(*filter.timing);

    for (int sample = 0; sample < 5; ++sample) {
      const std::vector<double> state = random_state(rng, model.n());
      const double t = random_vector(rng, 1, 0, 2)[0], dt = 0.01;
      const std::vector<double> dy = random_vector(rng, model.p(), -0.1, 0.1);
      std::vector<double> stepped = state;
      grid_steps.step()(stepped.data(), t, dt, dy.data());
      check_close(stepped, heun_step(model, equations[k], t, state, dt, dy), 1e-12, "step against Heun by hand");
      auto header = headers.find(filter.name);
      if (header != headers.end()) {
        std::vector<double> reference = state;
        header->second(reference.data(), t, dt, dy.data());
        check_close(stepped, reference, 1e-14, "step against generated/");
      }
    }
    // step_lanes: each lane bit for bit step() on its own state and increment (the generated step
    // on the plugin's lane type). A filter whose code calls a function (the ukf's square roots, a
    // sin(t) of the model) has none.
    if (!grid_steps.lanes()) continue;
    const std::size_t width = grid_steps.width(), size = filter.state_size(), p = model.p();
    CHECK(width >= 2);
    const double t = random_vector(rng, 1, 0, 2)[0], dt = 0.01;
    std::vector<double> states(size * width), increments(p * width);
    std::vector<std::vector<double>> alone(width);
    for (std::size_t lane = 0; lane < width; ++lane) {
      alone[lane] = random_state(rng, model.n());
      const std::vector<double> dy = random_vector(rng, p, -0.1, 0.1);
      for (std::size_t i = 0; i < size; ++i) states[i * width + lane] = alone[lane][i];
      for (std::size_t r = 0; r < p; ++r) increments[r * width + lane] = dy[r];
      grid_steps.step()(alone[lane].data(), t, dt, dy.data());
    }
    grid_steps.step_lanes()(states.data(), t, dt, increments.data());
    for (std::size_t lane = 0; lane < width; ++lane)
      for (std::size_t i = 0; i < size; ++i) {
        INFO("step_lanes: lane " << lane << ", entry " << i);
        CHECK(std::memcmp(&states[i * width + lane], &alone[lane][i], sizeof(double)) == 0);
      }
  }
}

// Two states whose diffusion is given as G = g g^T only, with a parameter.
pfgen::Model covariance_model() {
  pfgen::ModelBuilder builder("covariance_only");
  const GiNaC::symbol x = builder.state("x"), y = builder.state("y");
  const GiNaC::symbol b = builder.parameter("b", GiNaC::numeric(1, 2));
  builder.drift({-x + y * y, -b * y});
  builder.diffusion_covariance({{1 + x * x, x * y / 2}, {x * y / 2, 1 + y * y}});
  builder.observation({0}, {{1, 1}}, {{1}});
  return builder.build();
}

template <class Params>
ReferenceStep header_step(void (*step)(double*, double, double, const double*, const Params&)) {
  return [step](double* state, double t, double dt, const double* dy) { step(state, t, dt, dy, Params{}); };
}

}  // namespace

TEST_CASE("plugin: paper 000's model compiles, loads and agrees with the model and generated/", "[plugin][compiler]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  const auto filters = all_filters(model);
  const Built& b = built("paper 000", model, filters);
  const SimulationPlugin plugin(b.build.path);
  CHECK(plugin.model_name() == "basin2006_quadratic");
  CHECK(plugin.pfgen_version() == PFGEN_VERSION);
  CHECK(plugin.n() == 1);
  CHECK(plugin.q() == 1);
  CHECK_FALSE(plugin.diffusion_is_zero());
  CHECK(plugin.has_diffusion_jacobian());
  CHECK(plugin.observation_is_constant());
  check_truth(model, plugin);
  check_observation(model, plugin);
  check_initial_states(model, plugin);
  for (const pfgen_runtime::FilterModel& filter : plugin.filters()) {
    INFO(filter.name);
    // Arithmetic alone, each steps runs side by side; but the ukf, which takes square roots.
    const pfgen_runtime::GridSteps* lanes = filter.timing->lanes();
    CHECK((lanes != nullptr) == (filter.name != "ukf"));
    CHECK((lanes ? lanes->width() : 0u) == (filter.name != "ukf" ? 8u : 0u));
  }
  namespace gen = pfgen_models::basin2006_quadratic;
  check_filters(model, filters, plugin,
                {{"optimal", header_step(&gen::optimal::step<double>)},
                 {"ekf", header_step(&gen::ekf::step<double>)},
                 {"additive", header_step(&gen::additive::step<double>)},
                 {"ekf-additive", header_step(&gen::ekf_additive::step<double>)}});
}

TEST_CASE("plugin: paper 001's noise-free truth has q = 0 and no diffusion", "[plugin][compiler]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("basin_skliar_partial.yaml"));
  const auto filters = all_filters(model);
  const SimulationPlugin plugin(built("paper 001", model, filters).build.path);
  CHECK(plugin.diffusion_is_zero());
  CHECK(plugin.q() == 0);
  const pfgen_runtime::SdeSystem system = plugin.system();
  CHECK(system.q == 0);
  CHECK_FALSE(system.diffusion);
  CHECK_FALSE(system.diffusion_jacobian);
  check_truth(model, plugin);
  check_observation(model, plugin);
  check_initial_states(model, plugin);
  namespace gen = pfgen_models::basin_skliar_partial;
  check_filters(model, filters, plugin,
                {{"optimal", header_step(&gen::optimal::step<double>)}, {"ekf", header_step(&gen::ekf::step<double>)}});
}

TEST_CASE("plugin: a random cubic system with multiplicative noise and a time-varying observation", "[plugin][compiler]") {
  std::mt19937 rng(7);
  pfgen_test::RandomSystemOptions options;
  options.n = 3;
  options.q = 2;
  options.identity_observation = false;
  pfgen_test::RandomSystem s = pfgen_test::make_random_system(rng, options, "random_cubic");
  // A time- and parameter-dependent observation, to exercise the time-varying path.
  pfgen::AffineRate observation = *s.model.observation.rate().affine();
  observation.A0[0] = observation.A0[0] + GiNaC::sin(s.t) / 2;
  observation.A[0][0] = observation.A[0][0] * (1 + s.a) + s.t;
  s.model.observation = pfgen::ObservationModel(
      pfgen::ObservationRate::of_affine(observation.A0, observation.A, observation.B), std::nullopt, std::nullopt);
  const auto filters = all_filters(s.model);
  const SimulationPlugin plugin(built("random", s.model, filters).build.path);
  CHECK(plugin.q() == 2);
  CHECK_FALSE(plugin.observation_is_constant());
  check_truth(s.model, plugin);
  check_observation(s.model, plugin);
  check_initial_states(s.model, plugin);
  check_filters(s.model, filters, plugin);
}

TEST_CASE("plugin: a diffusion given only as G, and a plugin without filters", "[plugin][compiler]") {
  const pfgen::Model model = covariance_model();
  const SimulationPlugin plugin(built("covariance", model, {}).build.path);
  CHECK(plugin.table().diffusion_is_covariance);
  CHECK(plugin.q() == 2);
  CHECK_FALSE(plugin.has_diffusion_jacobian());
  CHECK(plugin.filters().empty());
  check_truth(model, plugin);
  check_observation(model, plugin);
  check_initial_states(model, plugin);
}

TEST_CASE("plugin: a polynomial observation's truth observes h(x), with B from observation()", "[plugin][compiler]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("polynomial/range_squared.yaml"));
  const SimulationPlugin plugin(built("range squared", model, {pfgen::derive_filter(model, pfgen::FilterKind::Optimal)})
                                    .build.path);
  REQUIRE(plugin.table().observation_rate != nullptr);
  check_batches(plugin);
  CHECK(plugin.observation_is_constant());
  pfgen_runtime::Observation observation = plugin.observation();
  CHECK_FALSE(observation.rate().affine());
  CHECK_FALSE(observation.sampled());
  Eigen::VectorXd x(2), h(1);
  x << 1.25, -0.5;
  observation.rate().value(0.0, x.data(), h.data());
  CHECK(h[0] == 1.25 * 1.25 + 0.25);
  Eigen::VectorXd dy(1), dW2(1);
  CHECK(observation.noise(0.0)(0, 0) == 0.5);  // r
  dW2 << 0.125;
  observation.increment(0.0, 0.1, x, x, dW2, dy);
  CHECK(dy[0] == Approx(1.8125 * 0.1 + 0.5 * 0.125).epsilon(1e-15));
  CHECK(plugin.filters().size() == 1);
}

TEST_CASE("plugin: samples through a polynomial c are c(x) + Uv v", "[plugin][compiler]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("polynomial/range_squared_sampled.yaml"));
  const SimulationPlugin plugin(
      built("range squared sampled", model, {pfgen::derive_filter(model, pfgen::FilterKind::CdOptimal)}).build.path);
  REQUIRE(plugin.table().observation_rate != nullptr);
  check_batches(plugin);
  pfgen_runtime::Observation measurement = plugin.observation();
  REQUIRE(measurement.sampled());
  CHECK_FALSE(measurement.rate().affine());
  const double x[2] = {1.25, -0.5}, v[1] = {0.5};
  double clean[1], noisy[1];
  measurement.sample(0.1, x, v, clean, noisy);
  CHECK(clean[0] == 1.25 * 1.25 + 0.25);
  CHECK(noisy[0] == Approx(1.8125 + 0.2 * 0.5).epsilon(1e-15));
  CHECK(plugin.filters().size() == 1);
}

TEST_CASE("plugin: what the runtime gets outlives the SimulationPlugin and simulates", "[plugin][compiler]") {
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  std::vector<pfgen_runtime::FilterModel> filters;
  pfgen_runtime::SdeSystem system;
  {
    SimulationPlugin plugin(built("paper 000", model, all_filters(model)).build.path);
    SimulationPlugin moved = std::move(plugin);
    filters = moved.filters();
    system = moved.system();
  }
  std::vector<double> state(filters.at(0).state_size());
  filters[0].initial_state(state.data());
  const double dy = 0.01;
  dynamic_cast<const pfgen_runtime::GridSteps&>(*filters[0].timing).step()(state.data(), 0, 0.01, &dy);
  CHECK(std::isfinite(state[0]));
  double f = 0;
  const double x = 2;
  system.drift(0, &x, &f);
  CHECK(f == Approx(0.4).epsilon(1e-15));
}

TEST_CASE("plugin: the cache", "[plugin][compiler]") {
  Workspace& w = workspace();
  const pfgen::Model model = pfgen::load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  const Built& first = built("paper 000", model, all_filters(model));

  SECTION("the source is byte-identical across derivations and calls") {
    const pfgen::Model again = pfgen::load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
    CHECK(pfgen::codegen::generate_simulation_plugin(again, all_filters(again)) == first.source);
  }

  SECTION("a second build is a hit: the same path, no compiler run") {
    const std::size_t runs = w.compiler_runs();
    const auto second = pfgen::toolchain::build_plugin(first.source, w.options());
    CHECK(second.cache_hit);
    CHECK(second.compile_seconds == 0);
    CHECK(second.path == first.build.path);
    CHECK(second.key == first.build.key);
    CHECK(w.compiler_runs() == runs);
    CHECK(fs::path(second.path).parent_path().filename() == second.key);
    CHECK(fs::exists(fs::path(second.path).parent_path() / "plugin.cpp"));
    CHECK(fs::exists(second.log_path));
  }

  SECTION("a changed model, compiler or flags give another key") {
    std::ifstream in(pfgen_test::example("basin2006_quadratic.yaml"));
    std::stringstream text;
    text << in.rdbuf();
    std::string changed = text.str();
    changed.replace(changed.find("0.1*x^2\"]"), 7, "0.2*x^2");
    const pfgen::Model other = pfgen::load_model_text(changed, "changed.yaml");
    const std::string other_source = pfgen::codegen::generate_simulation_plugin(other, all_filters(other));
    CHECK(other_source != first.source);
    CHECK(pfgen::toolchain::plugin_cache_key(other_source, w.options()) != first.build.key);
    CHECK(pfgen::toolchain::plugin_cache_key(first.source, w.options()) == first.build.key);
    auto flags = w.options();
    flags.flags = pfgen::toolchain::default_plugin_flags();
    flags.flags.push_back("-g");
    CHECK(pfgen::toolchain::plugin_cache_key(first.source, flags) != first.build.key);
    auto compiler = w.options();
    compiler.compiler = pfgen::toolchain::default_compiler();
    CHECK(pfgen::toolchain::plugin_cache_key(first.source, compiler) != first.build.key);
  }

  SECTION("two builds at once (as two pfgen processes would) both get the one complete plugin") {
    auto options = w.options();
    options.cache_dir = (w.root / "concurrent-cache").string();
    const std::string source = pfgen::codegen::generate_simulation_plugin(covariance_model(), {});
    pfgen::toolchain::PluginBuild a, b;
    std::thread other([&] { a = pfgen::toolchain::build_plugin(source, options); });
    b = pfgen::toolchain::build_plugin(source, options);
    other.join();
    CHECK(a.path == b.path);
    CHECK(SimulationPlugin(a.path).model_name() == "covariance_only");
    for (const auto& entry : fs::directory_iterator(fs::path(a.path).parent_path()))
      CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
  }

  SECTION("the default cache directory: $PFGEN_CACHE_DIR, $XDG_CACHE_HOME/pfgen, $HOME/.cache/pfgen") {
    const char* names[] = {"PFGEN_CACHE_DIR", "XDG_CACHE_HOME", "HOME"};
    std::map<std::string, std::optional<std::string>> saved;
    for (const char* name : names) {
      const char* value = std::getenv(name);
      saved[name] = value ? std::optional<std::string>(value) : std::nullopt;
    }
    ::setenv("PFGEN_CACHE_DIR", "/a", 1);
    ::setenv("XDG_CACHE_HOME", "/b", 1);
    ::setenv("HOME", "/c", 1);
    CHECK(pfgen::toolchain::default_cache_dir() == "/a");
    ::unsetenv("PFGEN_CACHE_DIR");
    CHECK(pfgen::toolchain::default_cache_dir() == "/b/pfgen");
    ::unsetenv("XDG_CACHE_HOME");
    CHECK(pfgen::toolchain::default_cache_dir() == "/c/.cache/pfgen");
    for (const auto& [name, value] : saved)
      if (value) ::setenv(name.c_str(), value->c_str(), 1); else ::unsetenv(name.c_str());
  }

  SECTION("a compiler that cannot run is a clear error and leaves nothing in the cache") {
    auto options = w.options();
    options.cache_dir = (w.root / "broken-cache").string();
    options.compiler = "/bin/false";
    CHECK_THROWS_WITH(pfgen::toolchain::build_plugin(first.source, options),
                      Catch::Contains("/bin/false") && Catch::Contains("failed on --version") &&
                          Catch::Contains("set CXX"));
    options.compiler = "pfgen-no-such-compiler";
    CHECK_THROWS_WITH(pfgen::toolchain::build_plugin(first.source, options),
                      Catch::Contains("cannot run the C++ compiler `pfgen-no-such-compiler`"));
    // $CXX is the default compiler.
    const char* saved = std::getenv("CXX");
    const std::string saved_value = saved ? saved : "";
    ::setenv("CXX", "/bin/false", 1);
    options.compiler.clear();
    CHECK_THROWS_AS(pfgen::toolchain::build_plugin(first.source, options), pfgen::toolchain::ToolchainError);
    if (saved) ::setenv("CXX", saved_value.c_str(), 1); else ::unsetenv("CXX");
    CHECK_FALSE(fs::exists(options.cache_dir));
  }

  SECTION("a failed compile quotes the error, keeps the log and leaves no shared object") {
    const std::string broken = "#error this plugin is deliberately broken\n";
    try {
      pfgen::toolchain::build_plugin(broken, w.options());
      FAIL("no error");
    } catch (const pfgen::toolchain::PluginCompileError& e) {
      const std::string message = e.what();
      CHECK_THAT(message, Catch::Contains("deliberately broken") && Catch::Contains(e.log_path()));
      CHECK(fs::exists(e.log_path()));
      const fs::path dir = fs::path(e.log_path()).parent_path();
      CHECK_FALSE(fs::exists(dir / "plugin.so"));
      for (const auto& entry : fs::directory_iterator(dir))
        CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
    }
  }

  SECTION("the loader rejects what is no plugin, or one of another ABI version") {
    CHECK_THROWS_WITH(SimulationPlugin((w.root / "missing.so").string()), Catch::Contains("cannot load"));
    const std::string other_abi = pfgen::codegen::plugin_abi_header() +
                                  "static pfgen_plugin table{};\n"
                                  "extern \"C\" __attribute__((visibility(\"default\"))) const pfgen_plugin* "
                                  "pfgen_plugin_entry(void) { table.abi_version = 999; return &table; }\n";
    const auto build = pfgen::toolchain::build_plugin(other_abi, w.options());
    CHECK_THROWS_WITH(SimulationPlugin(build.path), Catch::Contains("ABI version 999") &&
                                                        Catch::Contains("reads version " +
                                                                        std::to_string(PFGEN_PLUGIN_ABI_VERSION)));
  }

  SECTION("the loader rejects a table whose drift has no batched form") {
    // Consistent in every other field: a deterministic scalar truth dx = -x dt observed as dy = x dt + dW.
    const std::string unbatched = pfgen::codegen::plugin_abi_header() +
                                  "static void drift(double, const double* x, double* f) { f[0] = -x[0]; }\n"
                                  "static void observation(double, double* A0, double* A, double* B) "
                                  "{ A0[0] = 0; A[0] = 1; B[0] = 1; }\n"
                                  "static pfgen_plugin table{};\n"
                                  "extern \"C\" __attribute__((visibility(\"default\"))) const pfgen_plugin* "
                                  "pfgen_plugin_entry(void) {\n"
                                  "  table.abi_version = PFGEN_PLUGIN_ABI_VERSION; table.model_name = \"m\";\n"
                                  "  table.pfgen_version = \"v\"; table.n = 1; table.p = 1; table.r = 1;\n"
                                  "  table.diffusion_is_zero = 1; table.observation_is_constant = 1;\n"
                                  "  table.drift = &drift; table.observation = &observation; return &table;\n"
                                  "}\n";
    const auto build = pfgen::toolchain::build_plugin(unbatched, w.options());
    CHECK_THROWS_WITH(SimulationPlugin(build.path),
                      Catch::Contains("is inconsistent") && Catch::Contains("a batched function is missing"));
  }
  SECTION("the loader rejects a filter whose step_lanes and lanes disagree") {
    // The same truth, batched, with one filter; `lanes` set by the case.
    auto source = [](const std::string& lanes_fields) {
      return pfgen::codegen::plugin_abi_header() +
             "static void drift(double, const double* x, double* f) { f[0] = -x[0]; }\n"
             "static void drift_batch(double, size_t count, const double* x, double* f) "
             "{ for (size_t k = 0; k < count; ++k) f[k] = -x[k]; }\n"
             "static void observation(double, double* A0, double* A, double* B) { A0[0] = 0; A[0] = 1; B[0] = 1; }\n"
             "static void init(double* s) { s[0] = 0; s[1] = 1; }\n"
             "static void step(double*, double, double, const double*) {}\n"
             "static pfgen_plugin table{};\nstatic pfgen_plugin_filter filter{};\n"
             "extern \"C\" __attribute__((visibility(\"default\"))) const pfgen_plugin* pfgen_plugin_entry(void) {\n"
             "  filter.name = \"f\"; filter.n = 1; filter.p = 1; filter.state_size = 2;\n"
             "  filter.initial_state = &init; filter.step = &step;\n" +
             lanes_fields +
             "  table.abi_version = PFGEN_PLUGIN_ABI_VERSION; table.model_name = \"m\";\n"
             "  table.pfgen_version = \"v\"; table.n = 1; table.p = 1; table.r = 1;\n"
             "  table.diffusion_is_zero = 1; table.observation_is_constant = 1; table.drift = &drift;\n"
             "  table.drift_batch = &drift_batch; table.observation = &observation;\n"
             "  table.filter_count = 1; table.filters = &filter; return &table;\n}\n";
    };
    for (const std::string& fields : {std::string("  filter.step_lanes = &step; filter.lanes = 0;\n"),
                                      std::string("  filter.step_lanes = nullptr; filter.lanes = 8;\n"),
                                      std::string("  filter.step_lanes = &step; filter.lanes = 65;\n")}) {
      INFO(fields);
      const auto build = pfgen::toolchain::build_plugin(source(fields), w.options());
      CHECK_THROWS_WITH(SimulationPlugin(build.path),
                        Catch::Contains("is inconsistent") && Catch::Contains("filter f has step_lanes without 1 to 64 lanes"));
    }
    const auto fine = pfgen::toolchain::build_plugin(source("  filter.step_lanes = &step; filter.lanes = 8;\n"), w.options());
    const pfgen_runtime::GridSteps* lanes = SimulationPlugin(fine.path).filters().at(0).timing->lanes();
    REQUIRE(lanes != nullptr);
    CHECK(lanes->width() == 8);
  }
}

TEST_CASE("plugin: a filter steps runs in lanes when its code is arithmetic alone and small", "[plugin][unit]") {
  using pfgen::codegen::FunctionStats;
  using pfgen::codegen::GeneratedFilter;
  using pfgen::codegen::kMaxLaneOps;
  auto function = [](std::size_t adds, std::size_t calls, bool in_totals = true) {
    FunctionStats stats;
    stats.cse.adds = adds;
    stats.cse.calls = calls;
    stats.in_totals = in_totals;
    return stats;
  };
  GeneratedFilter filter;
  filter.functions = {function(kMaxLaneOps - 100, 0), function(100, 0)};
  CHECK(pfgen::codegen::steps_in_lanes(filter));
  // rates() repeats what the others compute: not counted.
  filter.functions.push_back(function(kMaxLaneOps, 0, false));
  CHECK(pfgen::codegen::steps_in_lanes(filter));
  filter.functions.push_back(function(1, 0));
  CHECK_FALSE(pfgen::codegen::steps_in_lanes(filter));  // one operation too many
  filter.functions = {function(3, 1)};
  CHECK_FALSE(pfgen::codegen::steps_in_lanes(filter));  // a sqrt is not defined on the lanes
}
