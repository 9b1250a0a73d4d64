// The generated filters for delayed observations (generator/src/codegen/backends/cpp/templates/delayed_filter.hpp.tmpl), run:
// the ring history hands out exactly the m (and x*) a direct record of the run holds h ago; Phi*
// of dx = a x dt is exp(-a h) once t >= h and 0 before; with h = 0 every delay kind's equations
// are its undelayed counterpart's (md -> m, Phi* -> I), and its generated code steps the same.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "generated/delay_linear/delay_ekf.hpp"
#include "generated/delay_linear/delay_optimal.hpp"
#include "generated/delay_linear/delay_uncorrected.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/process.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

namespace {

using DelayedInputs = void (*)(const double*, const double*, const double*, std::size_t, std::size_t, double*);

// Steps a generated delayed filter on random increments and checks, before every step k, that
// the inputs it reads at grid indices k - D (predictor) and k + 1 - D (corrector) are the m and x*
// a plain record of every state holds there (the pre-history m0, x*(0) = m0 before 0).
template <class Filter>
void check_history_against_record(DelayedInputs inputs, std::size_t D, std::size_t n, bool x_star, std::size_t steps) {
  Filter filter;
  std::vector<std::vector<double>> record;  // record[j] = state at grid index j
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.1);
  const std::size_t x_star_at = filter.state.size() - n;
  for (std::size_t k = 0; k < steps; ++k) {
    record.emplace_back(filter.state.begin(), filter.state.end());
    for (std::size_t offset : {std::size_t(0), std::size_t(1)}) {
      // The state "now": the start state for the predictor; for the corrector any state stands in
      // for the predicted one (it supplies x*(t), Phi*'s denominator).
      std::vector<double> now(filter.state.begin(), filter.state.end());
      if (offset == 1)
        for (auto& v : now) v *= 1.5;
      std::vector<double> delayed(x_star ? 2 * n : n);
      inputs(filter.history.data(), filter.state.data(), now.data(), k, offset, delayed.data());
      const long j = static_cast<long>(k + offset) - static_cast<long>(D);
      const std::vector<double>& past = record.at(j < 0 ? 0 : static_cast<std::size_t>(j));
      for (std::size_t i = 0; i < n; ++i) {
        INFO("k = " << k << ", offset " << offset << ", i = " << i);
        REQUIRE(delayed[i] == past[i]);
        // Phi* is 0 over every step that starts before h, its corrector included (k < D).
        if (x_star) REQUIRE(delayed[n + i] == (k < D ? 0.0 : past[x_star_at + i] / now[x_star_at + i]));
      }
    }
    const double dy[1] = {noise(rng)};
    filter.step(dy);
  }
}

namespace optimal = pfgen_models::delay_linear::delay_optimal;
namespace uncorrected = pfgen_models::delay_linear::delay_uncorrected;

// A one-state model dx = a x dt + sigma dW1 observed through dy = x(t - h) dt + B dW2, with h = 0
// (C++ API only: the model file's delay: 0 is the undelayed model) or the same model undelayed.
Model linear_model(bool delayed, double a = -0.5) {
  ModelBuilder b(delayed ? "linear_h0" : "linear_undelayed");
  const GiNaC::symbol x = b.state("x");
  b.drift({GiNaC::numeric(a) * x + GiNaC::numeric(1, 10) * x * x});
  b.diffusion({{GiNaC::numeric(3, 10) + GiNaC::numeric(1, 10) * x}});
  if (delayed)
    b.delayed_observation(0, {0}, {{1}}, {{GiNaC::numeric(1, 5)}});
  else
    b.observation({0}, {{1}}, {{GiNaC::numeric(1, 5)}});
  InitialConditions initial;
  initial.x0 = {1};
  initial.m0 = {GiNaC::numeric(1, 2)};
  initial.P0 = {{GiNaC::numeric(1, 4)}};
  b.initial(initial);
  return b.build();
}

}  // namespace

TEST_CASE("the generated history hands out the m and x* of h ago, as a direct record holds them",
          "[codegen][delayed][unit]") {
  static_assert(optimal::delay_steps == 50 && optimal::uses_x_star);
  static_assert(!uncorrected::uses_x_star && uncorrected::history_size == uncorrected::delay_steps);
  check_history_against_record<optimal::Filter<double>>(&optimal::detail::delayed_inputs<double>, 50, 1, true, 400);
  check_history_against_record<uncorrected::Filter<double>>(&uncorrected::detail::delayed_inputs<double>, 50, 1,
                                                            false, 400);
}

TEST_CASE("Phi* of dx = a x dt is exp(-a h) from t = h on and 0 before", "[codegen][delayed][unit]") {
  // delay_linear: a = -0.5, h = 0.5, dt = 0.01, so Phi* = exp(0.25) for t >= 0.5.
  optimal::Filter<double> filter;
  const double a = filter.params.a, h = optimal::delay<double>();
  double worst = 0;
  std::size_t checked_before = 0, checked_after = 0;
  for (std::size_t k = 0; k < 400; ++k) {
    double delayed[2];
    optimal::detail::delayed_inputs<double>(filter.history.data(), filter.state.data(), filter.state.data(), k, 0,
                                            delayed);
    if (k < optimal::delay_steps) {
      REQUIRE(delayed[1] == 0.0);
      ++checked_before;
    } else {
      worst = std::max(worst, std::abs(delayed[1] / std::exp(-a * h) - 1));
      ++checked_after;
    }
    const double dy[1] = {0.01 * std::sin(0.1 * static_cast<double>(k))};
    filter.step(dy);
  }
  CHECK(checked_before == 50);
  CHECK(checked_after == 350);
  // x* is Heun's solution of dx*/dt = a x*: its ratio over h is exp(-a h) to O(dt^2) relative.
  CHECK(worst < 1e-5);
}

TEST_CASE("with h = 0 every delay kind's equations are its undelayed counterpart's", "[delayed][derivation][unit]") {
  const Model delayed = linear_model(true);
  const Model undelayed = linear_model(false);
  const std::vector<std::pair<FilterKind, FilterKind>> pairs = {{FilterKind::DelayOptimal, FilterKind::Optimal},
                                                                {FilterKind::DelayUncorrected, FilterKind::Optimal},
                                                                {FilterKind::DelayEkf, FilterKind::Ekf}};
  for (const auto& [kind, counterpart] : pairs) {
    INFO(filter_kind_name(kind));
    const FilterEquations d = derive_filter(delayed, kind);
    const FilterEquations u = derive_filter(undelayed, counterpart);
    const FilterVariables& v = d.variables;
    REQUIRE(v.delayed());
    // md_i -> m_i, phi_i -> 1: substitute through GiNaC, in the filter variables' symbols.
    GiNaC::exmap h0;
    for (std::size_t i = 0; i < d.n(); ++i) {
      h0[v.symbols()[v.m_delayed(i)]] = v.symbols()[v.m(i)];
      h0[v.symbols()[v.phi(i)]] = 1;
    }
    auto at_h0 = [&](const Polynomial& p) { return p.to_ex(v.symbols()).subs(h0).expand(); };
    auto as_ex = [&](const Polynomial& p) { return p.to_ex(u.variables.symbols()).expand(); };
    // The undelayed variables' symbols are other objects with the same names: compare as text.
    auto same = [&](const Polynomial& a, const Polynomial& b) {
      std::ostringstream x, y;
      x << at_h0(a);
      y << as_ex(b);
      GiNaC::parser reader;
      return (reader(x.str()) - reader(y.str())).expand().is_zero();
    };
    for (std::size_t i = 0; i < d.n(); ++i) {
      CHECK(same(d.m_drift[i], u.m_drift[i]));
      CHECK(same(d.predicted_observation[i], u.predicted_observation[i]));
      for (std::size_t r = 0; r < d.p; ++r) CHECK(same(d.gain[i][r], u.gain[i][r]));
      for (std::size_t j = i; j < d.n(); ++j) CHECK(same(d.P_drift(i, j), u.P_drift(i, j)));
    }
    CHECK(d.uses_x_star() == (kind == FilterKind::DelayOptimal));
    // With h = 0 the exactness diagnostic is the counterpart's.
    CHECK(d.exactness.condition == u.exactness.condition);
  }
}

TEST_CASE("with h = 0 the generated delay filters step as the undelayed ones", "[codegen][delayed][compiler]") {
  const Model delayed = linear_model(true);
  const Model undelayed = linear_model(false);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pfgen-test-delayed-h0";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  codegen::CodegenOptions options;
  options.scalar = codegen::ScalarMode::Double;
  options.grid_step = 0.01;
  auto write = [&](const codegen::GeneratedFilter& file) {
    std::filesystem::create_directories((dir / file.files.at(0).relative_path).parent_path());
    std::ofstream(dir / file.files.at(0).relative_path) << file.files.at(0).contents;
  };
  const std::vector<std::pair<FilterKind, FilterKind>> pairs = {{FilterKind::DelayOptimal, FilterKind::Optimal},
                                                                {FilterKind::DelayUncorrected, FilterKind::Optimal},
                                                                {FilterKind::DelayEkf, FilterKind::Ekf}};
  std::string program = "#include <cmath>\n#include <cstdio>\n#include <random>\n";
  std::string calls;
  for (const auto& [kind, counterpart] : pairs) {
    write(codegen::generate_filter_code(delayed, derive_filter(delayed, kind), options));
    if (kind != FilterKind::DelayUncorrected)  // its counterpart is optimal, written with delay-optimal's
      write(codegen::generate_filter_code(undelayed, derive_filter(undelayed, counterpart), options));
    const std::string d = filter_identifier(filter_kind_name(kind)), u = filter_identifier(filter_kind_name(counterpart));
    program += "#include \"linear_h0/" + d + ".hpp\"\n";
    if (kind != FilterKind::DelayUncorrected) program += "#include \"linear_undelayed/" + u + ".hpp\"\n";
    // The same increments into both; the largest difference of m and P, relative to 1 + |entry|.
    calls += "  {\n    namespace D = pfgen_models::linear_h0::" + d + ";\n    namespace U = pfgen_models::linear_undelayed::" +
             u + ";\n    D::Filter delayed;\n    double state[U::state_size];\n    U::initial_state(state);\n" +
             "    std::mt19937 rng(3);\n    std::normal_distribution<double> noise(0.0, 0.02);\n    double worst = 0;\n" +
             "    for (int k = 0; k < 2000; ++k) {\n      const double dy[1] = {noise(rng)};\n      delayed.step(dy);\n" +
             "      U::step(state, k * 0.01, 0.01, dy, U::Params<double>{});\n" +
             "      for (std::size_t i = 0; i < U::state_size; ++i)\n" +
             "        worst = std::fmax(worst, std::fabs(delayed.state[i] - state[i]) / (1 + std::fabs(state[i])));\n" +
             "    }\n    std::printf(\"" + d + " %.3g %.6f\\n\", worst, state[0]);\n  }\n";
  }
  program += "int main() {\n" + calls + "  return 0;\n}\n";
  std::ofstream(dir / "main.cpp") << program;
  const std::string binary = (dir / "compare").string();
  const std::string command = "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " +
                              pfgen_test::shell_quote(dir.string()) + " " +
                              pfgen_test::shell_quote((dir / "main.cpp").string()) + " -o " +
                              pfgen_test::shell_quote(binary);
  const auto compiled = pfgen_test::run_process(command);
  INFO(command << "\n" << compiled.err.substr(0, 4000));
  REQUIRE(compiled.exit_code == 0);
  const auto ran = pfgen_test::run_process(pfgen_test::shell_quote(binary));
  INFO(ran.out);
  REQUIRE(ran.exit_code == 0);
  std::istringstream lines(ran.out);
  std::string name;
  double worst = 1, m = 0;
  std::size_t count = 0;
  while (lines >> name >> worst >> m) {
    INFO(name << ": largest relative difference " << worst << ", final m " << m);
    CHECK(worst <= 1e-12);
    CHECK(std::isfinite(m));
    ++count;
  }
  CHECK(count == 3);
  std::filesystem::remove_all(dir);
}
