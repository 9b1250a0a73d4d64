// The generated filters for polynomial observations (generator/src/codegen/backends/*/templates/polynomial_filter.*),
// compiled with g++ and run:
//  (a) derivatives(), gain(), covariance_gain() and predicted_observation() against the evaluator
//      (what `pfgen eval` prints: m_drift, P_drift, gain, P_gain, predicted_observation), for the
//      cubic sensor, the range-squared and the Van der Pol energy examples, kinds optimal, ekf, ukf,
//      C++ and C, at random points;
//  (b) stratonovich_correction() against its definition c_v = 1/2 sum R_rq sum_u (d sigma_vr/d s_u)
//      sigma_uq with the derivative taken here by central differences of the generated sigma =
//      [gain; covariance_gain] (independent of the symbolic derivative the generator takes);
//  (c) the generated step() on one Brownian path of the cubic sensor converges at first order to
//      the Ito filter: within a fraction of the distance of the uncorrected Heun limit from
//      Euler-Maruyama of the Ito equations, which the test integrates from the evaluator's closed form;
//  (d) a linear h: every file codegen writes, C++ and C, equals the A0 + A x model's byte for byte;
//  (e) the moment filters (closure3, closure4), which step in this layout for a linear h too: (a) and (b) with their
//      higher moments, and (c) against Euler-Maruyama of their Ito equations from the generated functions.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/exact_rational.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using namespace pfgen_test;

namespace {

// The generated functions' values at one packed state s = [m, P's upper triangle].
struct Values {
  std::vector<double> drift, K, L, yhat, c;
};

// Writes the filter's files for `language` under dir; returns the header's path below dir.
std::string write_filter(const TempDir& dir, const Model& model, const FilterEquations& eq,
                         codegen::Language language) {
  codegen::CodegenOptions options;
  options.scalar = codegen::ScalarMode::Double;
  options.language = language;
  // A short namespace, which the programs below name (pm_ in C, pm:: in C++).
  options.name_space = "pm";
  const codegen::GeneratedFilter filter = codegen::generate_filter_code(model, eq, options);
  for (const auto& file : filter.files) {
    std::filesystem::create_directories(std::filesystem::path(dir.file(file.relative_path)).parent_path());
    write_file(dir.file(file.relative_path), file.contents);
  }
  return filter.files.at(0).relative_path;
}

// A driver that prints, for every state of `states`, the five functions' outputs in %.17g.
std::vector<Values> run_functions(const Model& model, const FilterEquations& eq, codegen::Language language,
                                  const std::vector<std::vector<double>>& states) {
  TempDir dir;
  const std::string header = write_filter(dir, model, eq, language);
  const std::size_t n = eq.n(), p = eq.p, size = eq.variables.count();
  const bool c = language == "c";
  const std::string id = filter_identifier(eq.name);
  const std::string prefix = "pm_" + model.name + "_" + id + "_";
  std::ostringstream program;
  program << (c ? "#include <stdio.h>\n" : "#include <cstdio>\n") << "#include \"" << header << "\"\n";
  if (!c) program << "namespace F = pm::" << model.name << "::" << id << ";\n";
  program << "static const double states[][" << size << "] = {\n";
  for (const auto& s : states) {
    program << "  {";
    for (double v : s) program << std::setprecision(17) << v << ", ";
    program << "},\n";
  }
  program << "};\nstatic void print(const double* v, int count) {\n"
             "  for (int i = 0; i < count; ++i) printf(\"%.17g \", v[i]);\n  printf(\"\\n\");\n}\n"
          << "int main(void) {\n  double out[" << size << "], K[" << n * p << "], L[" << (size - n) * p << "], h[" << p
          << "], c[" << size << "];\n";
  if (c)
    program << "  " << prefix << "params params;\n  " << prefix << "default_params(&params);\n";
  else
    program << "  const F::Params<double> params{};\n";
  program << "  for (unsigned k = 0; k < sizeof states / sizeof states[0]; ++k) {\n";
  for (const char* function : {"derivatives", "gain", "covariance_gain", "predicted_observation", "stratonovich_correction"}) {
    const std::string target = std::string(function) == "derivatives" ? "out" : std::string(function) == "gain" ? "K"
                               : std::string(function) == "covariance_gain"      ? "L"
                               : std::string(function) == "predicted_observation" ? "h"
                                                                                   : "c";
    program << "    " << (c ? prefix : "F::") << function << "(0.25, states[k], " << (c ? "&params" : "params") << ", "
            << target << ");\n    print(" << target << ", (int)(sizeof " << target << " / sizeof(double)));\n";
  }
  program << "  }\n  return 0;\n}\n";
  const std::string source = dir.file(c ? "main.c" : "main.cpp");
  write_file(source, program.str());
  std::string command = c ? "gcc -std=c99 -O2 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " " +
                                shell_quote(source) + " " + shell_quote(dir.file(model.name + "/" + id + ".c")) + " -lm"
                          : "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " " +
                                shell_quote(source);
  command += " -o " + shell_quote(dir.file("driver"));
  const ProcessResult compiled = run_process(command);
  INFO(command << "\n" << compiled.err.substr(0, 4000));
  REQUIRE(compiled.exit_code == 0);
  const ProcessResult ran = run_program({dir.file("driver")});
  REQUIRE(ran.exit_code == 0);
  std::istringstream lines(ran.out);
  std::vector<Values> values(states.size());
  auto read = [&](std::size_t count) {
    std::vector<double> v(count);
    for (double& x : v) lines >> x;
    return v;
  };
  for (Values& v : values) {
    v.drift = read(size);
    v.K = read(n * p);
    v.L = read((size - n) * p);
    v.yhat = read(p);
    v.c = read(size);
  }
  REQUIRE(lines);
  return values;
}

EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const std::vector<double>& s) {
  const std::size_t n = eq.n();
  EvaluationPoint point;
  point.t = exact(0.25);
  for (std::size_t i = 0; i < n; ++i) point.m.push_back(exact(s[i]));
  point.P.assign(n, std::vector<GiNaC::numeric>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) point.P[i][j] = point.P[j][i] = exact(s[eq.variables.P(i, j)]);
  for (std::uint32_t v = eq.variables.first_higher_moment(); v < eq.variables.count(); ++v)
    point.moments[eq.variables.text_name(v)] = exact(s[v]);
  return evaluate_at(model, eq, point);
}

// A random state with P positive definite (P = A A^T + 0.1 I, A's entries in [-0.6, 0.6]).
// A moment filter's state also holds its higher moments: each drawn in [-0.3, 0.3] (order 3), or its Gaussian value
// plus up to 0.2 (order 4).
std::vector<double> random_state(std::mt19937& rng, const FilterVariables& vars);

std::vector<double> random_state(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<double> u(-0.6, 0.6), mean(-1.5, 1.5);
  std::vector<double> s;
  for (std::size_t i = 0; i < n; ++i) s.push_back(mean(rng));
  std::vector<std::vector<double>> A(n, std::vector<double>(n));
  for (auto& row : A)
    for (double& a : row) a = u(rng);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      double P = i == j ? 0.1 : 0.0;
      for (std::size_t k = 0; k < n; ++k) P += A[i][k] * A[j][k];
      s.push_back(P);
    }
  return s;
}

void check_close(const std::vector<double>& generated, const std::vector<double>& expected, double tolerance,
                 const std::string& what) {
  REQUIRE(generated.size() == expected.size());
  double scale = 1;
  for (double e : expected) scale = std::max(scale, std::abs(e));
  for (std::size_t k = 0; k < expected.size(); ++k) {
    INFO(what << "[" << k << "]: generated " << generated[k] << ", expected " << expected[k]);
    CHECK(std::abs(generated[k] - expected[k]) <= tolerance * scale);
  }
}

// R = B B^T of the model's observation at its parameter defaults (constant B in these examples).
std::vector<std::vector<double>> noise_covariance(const Model& model) {
  GiNaC::exmap defaults;
  for (const auto& parameter : model.parameters) defaults[parameter.symbol] = parameter.default_value;
  const ExMatrix& B = model.observation.rate().noise();
  std::vector<std::vector<double>> R(B.size(), std::vector<double>(B.size()));
  for (std::size_t r = 0; r < B.size(); ++r)
    for (std::size_t q = 0; q < B.size(); ++q)
      for (std::size_t k = 0; k < B[r].size(); ++k)
        R[r][q] += GiNaC::ex_to<GiNaC::numeric>((B[r][k] * B[q][k]).subs(defaults).evalf()).to_double();
  return R;
}

std::vector<double> random_state(std::mt19937& rng, const FilterVariables& vars) {
  std::vector<double> s = random_state(rng, vars.n());
  std::uniform_real_distribution<double> third(-0.3, 0.3), fourth(0.0, 0.2);
  for (const std::vector<std::size_t>& i : vars.higher_moments()) {
    if (i.size() == 3) {
      s.push_back(third(rng));
      continue;
    }
    auto P = [&](std::size_t a, std::size_t b) { return s[vars.P(i[a], i[b])]; };
    s.push_back(P(0, 1) * P(2, 3) + P(0, 2) * P(1, 3) + P(0, 3) * P(1, 2) + fourth(rng));
  }
  return s;
}

// The start of main() in the step-convergence drivers: one path of the cubic sensor's x (a = 1, sigma = rho = 0.5,
// x0 = 0.8) and its dy on 2^16 steps of [0, 1], and the model's parameters (F the filter's namespace).
const char* const kCubicSensorPath = R"(  const std::size_t finest = std::size_t{1} << 16;
  std::mt19937_64 rng(29);
  std::normal_distribution<double> normal;
  const double dt = 1.0 / finest;
  double x = 0.8;
  std::vector<double> dy(finest);
  for (std::size_t k = 0; k < finest; ++k) {
    dy[k] = x * x * x * dt + 0.5 * std::sqrt(dt) * normal(rng);
    x += -x * dt + 0.5 * std::sqrt(dt) * normal(rng);
  }
  const F::Params<double> params{};
)";

// What a C++ driver beside the filter's header in dir prints: compiled warning-free and run, each required to succeed.
std::string compiled_output(const TempDir& dir, const std::string& program) {
  write_file(dir.file("main.cpp"), program);
  const std::string command = "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + shell_quote(dir.path()) + " " +
                              shell_quote(dir.file("main.cpp")) + " -o " + shell_quote(dir.file("steps"));
  const ProcessResult compiled = run_process(command);
  INFO(compiled.err.substr(0, 4000));
  REQUIRE(compiled.exit_code == 0);
  const ProcessResult ran = run_program({dir.file("steps")});
  REQUIRE(ran.exit_code == 0);
  return ran.out;
}

}  // namespace

TEST_CASE("generated polynomial-observation filters: functions against the evaluator, the correction against its "
          "definition by finite differences",
          "[codegen][polynomial][compiler]") {
  std::mt19937 rng(31);
  for (const char* file : {"polynomial/cubic_sensor.yaml", "polynomial/range_squared.yaml",
                           "polynomial/van_der_pol_energy.yaml", "reference/double_well.yaml"}) {
    const Model model = load_model_file(example(file));
    const std::vector<std::vector<double>> R = noise_covariance(model);
    // A linear h's filters step in this layout only when they are moment filters.
    const bool linear = model.observation.rate().affine().has_value();
    for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Ukf, FilterKind::Closure3,
                            FilterKind::Closure4}) {
      if (linear && !uses_cumulant_closure(kind)) continue;
      const FilterEquations eq = derive_filter(model, kind);
      const std::size_t n = eq.n(), p = eq.p, size = eq.variables.count();
      // Three base states, each followed by s +- eps e_u for every u (central differences).
      constexpr double eps = 1e-5;
      std::vector<std::vector<double>> states;
      for (int point = 0; point < 3; ++point) {
        const std::vector<double> base = random_state(rng, eq.variables);
        states.push_back(base);
        for (std::size_t u = 0; u < size; ++u)
          for (double sign : {1.0, -1.0}) {
            std::vector<double> moved = base;
            moved[u] += sign * eps;
            states.push_back(moved);
          }
      }
      for (const codegen::Language language : {"cpp", "c"}) {
        INFO(file << " " << eq.name << (language == "c" ? " (C)" : " (C++)"));
        const std::vector<Values> values = run_functions(model, eq, language, states);
        const std::size_t stride = 1 + 2 * size;
        for (std::size_t b = 0; b < states.size(); b += stride) {
          const Values& v = values[b];
          const EvaluatedFilter e = evaluate(model, eq, states[b]);
          std::vector<double> drift = e.m_drift, K, L, yhat = e.predicted_observation;
          for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i; j < n; ++j) drift.push_back(e.P_drift[i][j]);
          for (const auto& row : e.gain) K.insert(K.end(), row.begin(), row.end());
          for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i; j < n; ++j)
              for (std::size_t r = 0; r < p; ++r) L.push_back(e.P_gain.empty() ? 0.0 : e.P_gain[r][i][j]);
          drift.insert(drift.end(), e.moment_drift.begin(), e.moment_drift.end());
          for (const auto& row : e.moment_gain) L.insert(L.end(), row.begin(), row.end());
          check_close(v.drift, drift, 1e-12, "derivatives");
          check_close(v.K, K, 1e-12, "gain");
          check_close(v.L, L, 1e-12, "covariance_gain");
          check_close(v.yhat, yhat, 1e-12, "predicted_observation");
          // sigma = [K; L], one row per filter variable.
          auto sigma = [&](const Values& at, std::size_t row, std::size_t r) {
            return row < n ? at.K[row * p + r] : at.L[(row - n) * p + r];
          };
          std::vector<double> c(size, 0.0);
          for (std::size_t row = 0; row < size; ++row)
            for (std::size_t r = 0; r < p; ++r)
              for (std::size_t q = 0; q < p; ++q)
                for (std::size_t u = 0; u < size; ++u) {
                  const double derivative =
                      (sigma(values[b + 1 + 2 * u], row, r) - sigma(values[b + 2 + 2 * u], row, r)) / (2 * eps);
                  c[row] += 0.5 * R[r][q] * derivative * sigma(v, u, q);
                }
          check_close(v.c, c, 1e-6, "stratonovich_correction");
        }
      }
    }
  }
}

TEST_CASE("generated polynomial-observation step: first order to the Ito filter on one path of the cubic sensor",
          "[codegen][polynomial][compiler]") {
  const Model model = load_model_file(example("polynomial/cubic_sensor.yaml"));
  const FilterEquations eq = derive_filter(model, FilterKind::Optimal);
  TempDir dir;
  const std::string header = write_filter(dir, model, eq, "cpp");
  // One path of x (a = 1, sigma = rho = 0.5, x0 = 0.8) and its dy on 2^16 steps of [0, 1]; the
  // generated step at 2^8, 2^10, 2^12, 2^16 steps, and the same Heun step without the correction.
  const std::string program = "#include <cmath>\n#include <cstdio>\n#include <random>\n#include <vector>\n#include \"" +
                              header + "\"\n" + R"(namespace F = pm::cubic_sensor::optimal;
int main() {
)" + kCubicSensorPath + R"(  for (std::size_t steps : {std::size_t{1} << 8, std::size_t{1} << 10, std::size_t{1} << 12, finest}) {
    double s[2] = {0.5, 0.5};
    const std::size_t per = finest / steps;
    for (std::size_t k = 0; k < steps; ++k) {
      double dY = 0;
      for (std::size_t j = k * per; j < (k + 1) * per; ++j) dY += dy[j];
      F::step(s, double(k) / steps, 1.0 / steps, &dY, params);
    }
    std::printf("%.17g %.17g\n", s[0], s[1]);
  }
  for (double v : dy) std::printf("%.17g\n", v);
  return 0;
}
)";
  std::istringstream lines(compiled_output(dir, program));
  std::vector<std::vector<double>> generated(4, std::vector<double>(2));
  for (auto& s : generated) lines >> s[0] >> s[1];
  std::vector<double> dy(std::size_t{1} << 16);
  for (double& v : dy) lines >> v;
  REQUIRE(lines);

  // Euler-Maruyama of the Ito equations from the evaluator (exact rationals, rounded once), at the
  // finest step: the Ito filter's own scheme, order 1/2; and Heun without the correction.
  const std::vector<double> s0 = {0.5, 0.5};
  auto coefficients = [&](const std::vector<double>& s) {
    EvaluationPoint point;
    point.t = 0;
    point.m = {exact(s[0])};
    point.P = {{exact(s[1])}};
    return evaluate_at(model, eq, point);
  };
  // The closed form of docs/theory.md §2.9 with a = 1, sigma = rho = 1/2, checked against the
  // evaluator at the start, then used for speed.
  auto closed = [](double m, double P) {
    return std::vector<double>{-m, 3 * P * (m * m + P) / 0.25, -2 * P + 0.25 - 9 * P * P * (m * m + P) * (m * m + P) / 0.25,
                               6 * m * P * P / 0.25, m * m * m + 3 * m * P};
  };
  const EvaluatedFilter at_start = coefficients(s0);
  const std::vector<double> start = closed(s0[0], s0[1]);
  CHECK(at_start.m_drift[0] == Approx(start[0]).epsilon(1e-14));
  CHECK(at_start.gain[0][0] == Approx(start[1]).epsilon(1e-14));
  CHECK(at_start.P_drift[0][0] == Approx(start[2]).epsilon(1e-14));
  CHECK(at_start.P_gain[0][0][0] == Approx(start[3]).epsilon(1e-14));
  CHECK(at_start.predicted_observation[0] == Approx(start[4]).epsilon(1e-14));
  auto integrate = [&](std::size_t steps, bool heun) {
    std::vector<double> s = s0;
    const std::size_t per = dy.size() / steps;
    const double h = 1.0 / static_cast<double>(steps);
    auto increment = [&](const std::vector<double>& at, double dY) {
      const std::vector<double> v = closed(at[0], at[1]);
      const double innovation = dY - v[4] * h;
      return std::vector<double>{v[0] * h + v[1] * innovation, v[2] * h + v[3] * innovation};
    };
    for (std::size_t k = 0; k < steps; ++k) {
      double dY = 0;
      for (std::size_t j = k * per; j < (k + 1) * per; ++j) dY += dy[j];
      const std::vector<double> k1 = increment(s, dY);
      if (!heun) {
        s = {s[0] + k1[0], s[1] + k1[1]};
        continue;
      }
      const std::vector<double> k2 = increment({s[0] + k1[0], s[1] + k1[1]}, dY);
      s = {s[0] + 0.5 * (k1[0] + k2[0]), s[1] + 0.5 * (k1[1] + k2[1])};
    }
    return s;
  };
  auto distance = [](const std::vector<double>& a, const std::vector<double>& b) {
    return std::hypot(a[0] - b[0], a[1] - b[1]);
  };
  const std::vector<double> euler = integrate(dy.size(), false), plain = integrate(dy.size(), true);
  const double to_finest[3] = {distance(generated[0], generated[3]), distance(generated[1], generated[3]),
                               distance(generated[2], generated[3])};
  INFO("generated step, 2^8 2^10 2^12 steps from 2^16: " << to_finest[0] << " " << to_finest[1] << " " << to_finest[2]);
  INFO("generated at 2^16 from Euler-Maruyama: " << distance(generated[3], euler)
                                                << "; uncorrected Heun from Euler-Maruyama: " << distance(plain, euler));
  // First order: 16 times the steps, at least 8 times closer.
  CHECK(to_finest[0] > 8 * to_finest[2]);
  // The Ito filter (Euler-Maruyama's limit), not the one Heun without the correction converges to.
  CHECK(distance(generated[3], euler) < 0.2 * distance(plain, euler));
}

TEST_CASE("generated moment-filter step: first order to its Ito equations on one path of the cubic sensor",
          "[codegen][polynomial][compiler]") {
  // closure4 carries m, P, M3 and M4, each with a dy term whose coefficient depends on the state: Heun's step
  // needs the Ito-Stratonovich correction. Euler-Maruyama of the Ito equations and Heun without the correction
  // are integrated here from the generated functions, which test (a) checks against the evaluator.
  const Model model = load_model_file(example("polynomial/cubic_sensor.yaml"));
  const FilterEquations eq = derive_filter(model, FilterKind::Closure4);
  REQUIRE(eq.variables.count() == 4);
  TempDir dir;
  const std::string header = write_filter(dir, model, eq, "cpp");
  const std::string program = "#include <cmath>\n#include <cstdio>\n#include <random>\n#include <vector>\n#include \"" +
                              header + "\"\n" + R"(namespace F = pm::cubic_sensor::closure4;
using State = std::vector<double>;
// Over one step of h: [drift h + sigma (dY - yhat h)] and, when `corrected`, less c h.
State increment(const State& s, double t, double h, double dY, bool corrected, const F::Params<double>& params) {
  double drift[4], K[1], L[3], yhat[1], c[4];
  F::derivatives(t, s.data(), params, drift);
  F::gain(t, s.data(), params, K);
  F::covariance_gain(t, s.data(), params, L);
  F::predicted_observation(t, s.data(), params, yhat);
  F::stratonovich_correction(t, s.data(), params, c);
  const double innovation = dY - yhat[0] * h;
  State d(4);
  for (int v = 0; v < 4; ++v) d[v] = (drift[v] - (corrected ? c[v] : 0.0)) * h + (v == 0 ? K[0] : L[v - 1]) * innovation;
  return d;
}
int main() {
)" + kCubicSensorPath + R"(  State start(4);
  F::initial_state(start.data());
  for (std::size_t steps : {std::size_t{1} << 8, std::size_t{1} << 10, std::size_t{1} << 12, finest}) {
    State s = start;
    const std::size_t per = finest / steps;
    for (std::size_t k = 0; k < steps; ++k) {
      double dY = 0;
      for (std::size_t j = k * per; j < (k + 1) * per; ++j) dY += dy[j];
      F::step(s.data(), double(k) / steps, 1.0 / steps, &dY, params);
    }
    std::printf("%.17g %.17g %.17g %.17g\n", s[0], s[1], s[2], s[3]);
  }
  // Euler-Maruyama of the Ito equations, and Heun without the correction, at the finest step.
  State euler = start, plain = start;
  double least = 1e300;
  for (std::size_t k = 0; k < finest; ++k) {
    const double t = double(k) * dt;
    const State d = increment(euler, t, dt, dy[k], false, params);
    for (int v = 0; v < 4; ++v) euler[v] += d[v];
    const State k1 = increment(plain, t, dt, dy[k], false, params);
    State mid = plain;
    for (int v = 0; v < 4; ++v) mid[v] += k1[v];
    const State k2 = increment(mid, t + dt, dt, dy[k], false, params);
    for (int v = 0; v < 4; ++v) plain[v] += 0.5 * (k1[v] + k2[v]);
    double margins[2];
    F::realisability_margins(t, euler.data(), params, margins);
    least = std::fmin(least, std::fmin(margins[0], margins[1]));
  }
  std::printf("%.17g %.17g %.17g %.17g\n%.17g %.17g %.17g %.17g\n%.17g\n", euler[0], euler[1], euler[2], euler[3],
              plain[0], plain[1], plain[2], plain[3], least);
  return 0;
}
)";
  std::istringstream lines(compiled_output(dir, program));
  std::vector<std::vector<double>> generated(4, std::vector<double>(4));
  std::vector<double> euler(4), plain(4);
  double least = 0;
  for (auto& s : generated)
    for (double& v : s) lines >> v;
  for (double& v : euler) lines >> v;
  for (double& v : plain) lines >> v;
  lines >> least;
  REQUIRE(lines);
  REQUIRE(least > 0);  // the path stays in the realisable set, so the comparison means something
  auto distance = [](const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0;
    for (std::size_t v = 0; v < a.size(); ++v) sum += (a[v] - b[v]) * (a[v] - b[v]);
    return std::sqrt(sum);
  };
  const double to_finest[3] = {distance(generated[0], generated[3]), distance(generated[1], generated[3]),
                               distance(generated[2], generated[3])};
  INFO("generated step, 2^8 2^10 2^12 steps from 2^16: " << to_finest[0] << " " << to_finest[1] << " " << to_finest[2]);
  INFO("generated at 2^16 from Euler-Maruyama: " << distance(generated[3], euler)
                                                << "; uncorrected Heun from Euler-Maruyama: " << distance(plain, euler)
                                                << "; least margin on the path " << least);
  CHECK(to_finest[0] > 8 * to_finest[2]);  // first order: 16 times the steps, at least 8 times closer
  CHECK(distance(generated[3], euler) < 0.2 * distance(plain, euler));  // the Ito filter's limit
}

TEST_CASE("a linear h generates the A0 + A x model's code byte for byte", "[codegen][polynomial][unit]") {
  const Model linear = load_model_file(example("van_der_pol.yaml"));
  const std::string text = read_file(example("van_der_pol.yaml"));
  const std::string observation = "observation:                             # dy = x1 dt + r dW2\n  A: [[\"1\", \"0\"]]\n";
  const std::size_t at = text.find(observation);
  REQUIRE(at != std::string::npos);
  std::string written = text;
  written.replace(at, observation.size(), "observation:\n  h: [\"x1\"]\n");
  const Model polynomial = load_model_text(written, example("van_der_pol.yaml"));
  for (FilterKind kind : supported_filter_kinds(linear))
    for (const codegen::Language language : {"cpp", "c"}) {
      codegen::CodegenOptions options;
      options.language = language;
      options.scalar = codegen::ScalarMode::Double;
      options.eigen_wrapper = language == "cpp";
      const codegen::GeneratedFilter expected = codegen::generate_filter_code(linear, derive_filter(linear, kind), options);
      const codegen::GeneratedFilter derived =
          codegen::generate_filter_code(polynomial, derive_filter(polynomial, kind), options);
      REQUIRE(derived.files.size() == expected.files.size());
      for (std::size_t k = 0; k < expected.files.size(); ++k) {
        INFO(filter_kind_name(kind) << " " << expected.files[k].relative_path);
        CHECK(derived.files[k].relative_path == expected.files[k].relative_path);
        CHECK(derived.files[k].contents == expected.files[k].contents);
      }
    }
}

TEST_CASE("generated polynomial-observation filters: the Eigen layer compiles warning-free and agrees with the flat API",
          "[codegen][polynomial][compiler]") {
  const Model model = load_model_file(example("polynomial/range_squared.yaml"));
  const FilterEquations eq = derive_filter(model, FilterKind::Optimal);
  TempDir dir;
  codegen::CodegenOptions options;
  options.eigen_wrapper = true;  // template code, instantiated with double
  for (const auto& file : codegen::generate_filter_code(model, eq, options).files) {
    std::filesystem::create_directories(std::filesystem::path(dir.file(file.relative_path)).parent_path());
    write_file(dir.file(file.relative_path), file.contents);
  }
  write_file(dir.file("main.cpp"), R"(#include <cmath>
#include <cstdio>
#include "range_squared/optimal_eigen.hpp"
namespace F = pfgen_models::range_squared::optimal;
int main() {
  Eigen::Matrix<double, 2, 1> m(1.0, 0.5);
  Eigen::Matrix<double, 2, 2> P;
  P << 0.2, 0.05, 0.05, 0.3;
  const F::Params<double> params{};
  const double state[5] = {1.0, 0.5, 0.2, 0.05, 0.3};
  double L[3], c[5], c_flat[5];
  F::covariance_gain(0.0, state, params, L);
  F::stratonovich_correction(0.0, state, params, c_flat);
  const auto matrices = F::covariance_gain(0.0, m, P, params);
  Eigen::Matrix<double, 2, 1> c_m;
  Eigen::Matrix<double, 2, 2> c_P;
  F::stratonovich_correction(0.0, m, P, params, c_m, c_P);
  F::pack(c_m, c_P, c);
  int bad = matrices[0](0, 0) != L[0] || matrices[0](0, 1) != L[1] || matrices[0](1, 0) != L[1] || matrices[0](1, 1) != L[2];
  for (int k = 0; k < 5; ++k) bad |= c[k] != c_flat[k];
  // L = 2 P^2 / r^2 with r = 0.5: (0.0425, 0.025, 0.0925) * 8.
  bad |= std::fabs(L[0] - 0.34) > 1e-14 || std::fabs(L[1] - 0.2) > 1e-14 || std::fabs(L[2] - 0.74) > 1e-14;
  std::printf("%d\n", bad);
  return bad;
}
)");
  const ProcessResult compiled =
      run_process("g++ -std=c++17 -O2 -Wall -Wextra -Wshadow -Werror -I " + shell_quote(dir.path()) + " -isystem " + shell_quote(PFGEN_EIGEN_INCLUDE_DIR) + " " +
                  shell_quote(dir.file("main.cpp")) + " -o " + shell_quote(dir.file("eigen")));
  INFO(compiled.err.substr(0, 4000));
  REQUIRE(compiled.exit_code == 0);
  const ProcessResult ran = run_program({dir.file("eigen")});
  INFO(ran.out);
  CHECK(ran.exit_code == 0);
}
