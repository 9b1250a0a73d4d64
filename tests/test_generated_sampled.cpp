// The generated sampled filters (generator/src/codegen/backends/cpp/templates/sampled_filter.hpp.tmpl), compiled and run: for
// paper 003's two examples (r = 1) and tests/data/sampled_two_observations.yaml (r = 2, so the
// written-out Cholesky solve meets an off-diagonal S), every sampled kind, every scalar mode
// (--scalar double, float, template instantiated with double and with float) and both g++ and
// clang++, at random points:
//  (a) predict() (one sub-step) against the evaluator's drifts (what `pfgen eval` prints):
//      cd-optimal and cd-ekf: Heun's step built here from two evaluations, at (m, P) and at the
//      Euler-predicted point; cd-euler: m + m_drift dt, P + P_drift dt + P_dt2 dt^2;
//  (b) update() against a Kalman update written here with Eigen in long double from the model's
//      C0, C and Uv (S = C P C^T + Uv Uv^T, K = P C^T S^-1 by LLT, m + K (y - C0 - C m), Joseph
//      form), independent of the derivation and of the generated code; the evaluator's S and K
//      are checked against it too;
//  (c) update() returns false and leaves the state untouched (bit for bit) when S is not positive
//      definite: P negative definite, and for r = 2 an S with a positive diagonal but a negative
//      determinant (the second pivot fails).
// Double: 1e-12 relative to the largest entry of m, and of P, separately (input or result).
// Float: kFloatTolerance.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/exact_rational.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using namespace pfgen_test;
namespace fs = std::filesystem;

namespace {

using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using VecL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

constexpr double kDoubleTolerance = 1e-12;
// Float: the inputs are rounded to float (relative 6e-8) and each output entry goes through a few
// dozen float operations (u = 6e-8 each), so errors of some 1e-6 of the block's scale are
// expected; the worst cancellation (Joseph form's A = Id - K C, about R / (R + C P C^T), enters P'
// only through A P A^T, small beside K R K^T) adds little. Measured: at most 1.4e-7 (predict) and
// 2.2e-6 (update, r = 2); the bound keeps a factor 10 over that.
constexpr double kFloatTolerance = 2e-5;

constexpr int kPoints = 25;

const char* const kKinds[] = {"cd_optimal", "cd_ekf", "cd_euler"};

FilterKind kind_of(const std::string& stem) {
  if (stem == "cd_optimal") return FilterKind::CdOptimal;
  if (stem == "cd_ekf") return FilterKind::CdEkf;
  return FilterKind::CdEuler;
}

double random_rational(std::mt19937& rng, int range) {
  std::uniform_int_distribution<int> k(-range, range);
  return k(rng) / 1000.0;
}

struct FilterState {
  std::vector<double> m;               // n
  std::vector<std::vector<double>> P;  // n x n, symmetric
};

std::vector<double> pack(const FilterState& s) {
  std::vector<double> out = s.m;
  const std::size_t n = s.m.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) out.push_back(s.P[i][j]);
  return out;
}

FilterState unpack(const std::vector<double>& v, std::size_t n) {
  FilterState s{std::vector<double>(v.begin(), v.begin() + static_cast<long>(n)),
                std::vector<std::vector<double>>(n, std::vector<double>(n))};
  std::size_t k = n;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) s.P[i][j] = s.P[j][i] = v[k++];
  return s;
}

EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, double t, const FilterState& s) {
  EvaluationPoint point;
  point.t = exact(t);
  for (double v : s.m) point.m.push_back(exact(v));
  point.P.assign(s.m.size(), std::vector<GiNaC::numeric>(s.m.size()));
  for (std::size_t i = 0; i < s.m.size(); ++i)
    for (std::size_t j = 0; j < s.m.size(); ++j) point.P[i][j] = exact(s.P[i][j]);
  return evaluate_at(model, eq, point);
}

// [m_drift, upper triangle of P_drift] (and of P_dt2).
std::vector<double> drift_vector(const EvaluatedFilter& e) {
  std::vector<double> out = e.m_drift;
  for (std::size_t i = 0; i < e.m_drift.size(); ++i)
    for (std::size_t j = i; j < e.m_drift.size(); ++j) out.push_back(e.P_drift[i][j]);
  return out;
}

// (a) the prediction sub-step the generated predict() takes, from the evaluator's values.
std::vector<double> expected_predict(const Model& model, const FilterEquations& eq, FilterKind kind, double t,
                                     double dt, const std::vector<double>& state) {
  const std::size_t n = model.n();
  const EvaluatedFilter first = evaluate(model, eq, t, unpack(state, n));
  const std::vector<double> d1 = drift_vector(first);
  std::vector<double> out(state.size());
  if (kind == FilterKind::CdEuler) {
    REQUIRE(first.P_dt2.size() == n);
    std::size_t k = n;
    for (std::size_t i = 0; i < state.size(); ++i) out[i] = state[i] + d1[i] * dt;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j, ++k) out[k] += first.P_dt2[i][j] * dt * dt;
    return out;
  }
  std::vector<double> predicted(state.size());
  for (std::size_t i = 0; i < state.size(); ++i) predicted[i] = state[i] + d1[i] * dt;
  const std::vector<double> d2 = drift_vector(evaluate(model, eq, t + dt, unpack(predicted, n)));
  for (std::size_t i = 0; i < state.size(); ++i) out[i] = state[i] + (d1[i] + d2[i]) * dt / 2;
  return out;
}

// The observation's matrices as numbers (parameters at their defaults, t given).
struct Observation {
  MatL C, R;
  VecL C0;
};

long double value_of(const Model& model, const GiNaC::ex& e, double t) {
  GiNaC::exmap values;
  for (const auto& p : model.parameters) values[p.symbol] = p.default_value;
  values[model.time] = exact(t);
  const GiNaC::ex v = GiNaC::evalf(e.subs(values));
  REQUIRE(GiNaC::is_a<GiNaC::numeric>(v));
  return static_cast<long double>(GiNaC::ex_to<GiNaC::numeric>(v).to_double());
}

Observation observation_at(const Model& model, double t) {
  REQUIRE(model.observation.rate().affine());
  const AffineRate& o = *model.observation.rate().affine();  // C0 + C x with noise Uv: A0, A, B
  const auto r = static_cast<Eigen::Index>(o.A.size()), n = static_cast<Eigen::Index>(model.n());
  const auto q = static_cast<Eigen::Index>(o.B[0].size());
  Observation out{MatL(r, n), MatL(r, r), VecL(r)};
  MatL Uv(r, q);
  for (Eigen::Index i = 0; i < r; ++i) {
    out.C0(i) = value_of(model, o.A0[static_cast<std::size_t>(i)], t);
    for (Eigen::Index j = 0; j < n; ++j)
      out.C(i, j) = value_of(model, o.A[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)], t);
    for (Eigen::Index j = 0; j < q; ++j)
      Uv(i, j) = value_of(model, o.B[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)], t);
  }
  out.R = Uv * Uv.transpose();
  return out;
}

struct KalmanReference {
  std::vector<double> state;  // updated [m, upper triangle of P]
  MatL S, K;
};

// (b) the Kalman update in Joseph form, with Eigen in long double.
KalmanReference expected_update(const Model& model, double t, const std::vector<double>& state,
                                const std::vector<double>& y) {
  const std::size_t n = model.n();
  const Observation o = observation_at(model, t);
  const FilterState s = unpack(state, n);
  const auto N = static_cast<Eigen::Index>(n), r = o.C.rows();
  VecL m(N), Y(r);
  MatL P(N, N);
  for (Eigen::Index i = 0; i < N; ++i) {
    m(i) = s.m[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < N; ++j) P(i, j) = s.P[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  for (Eigen::Index i = 0; i < r; ++i) Y(i) = y[static_cast<std::size_t>(i)];
  const MatL S = o.C * P * o.C.transpose() + o.R;
  Eigen::LLT<MatL> llt(S);
  REQUIRE(llt.info() == Eigen::Success);
  const MatL K = llt.solve(o.C * P).transpose();  // (S^-1 C P)^T = P C^T S^-1
  const VecL m_new = m + K * (Y - o.C0 - o.C * m);
  const MatL A = MatL::Identity(N, N) - K * o.C;
  const MatL P_new = A * P * A.transpose() + K * o.R * K.transpose();
  KalmanReference out{{}, S, K};
  for (Eigen::Index i = 0; i < N; ++i) out.state.push_back(static_cast<double>(m_new(i)));
  for (Eigen::Index i = 0; i < N; ++i)
    for (Eigen::Index j = i; j < N; ++j) out.state.push_back(static_cast<double>(P_new(i, j)));
  return out;
}

// Largest |generated - expected| over the m block and over the P block, each divided by that
// block's largest entry in the input state or in the expected result (rounding errors scale with
// the inputs too: m' = m + K (y - C0 - C m) may be small beside m).
double relative_deviation(const std::vector<double>& generated, const std::vector<double>& expected,
                          const std::vector<double>& input, std::size_t n) {
  REQUIRE(generated.size() == expected.size());
  REQUIRE(input.size() == expected.size());
  double worst = 0;
  using Block = std::pair<std::size_t, std::size_t>;
  for (const auto& [begin, end] : {Block{0, n}, Block{n, expected.size()}}) {
    double scale = 0, dev = 0;
    for (std::size_t k = begin; k < end; ++k) {
      scale = std::max({scale, std::abs(expected[k]), std::abs(input[k])});
      dev = std::max(dev, std::abs(generated[k] - expected[k]));
    }
    worst = std::max(worst, dev / std::max(scale, 1e-300));
  }
  return worst;
}

std::string join(const std::vector<double>& values) {
  std::ostringstream out;
  out.precision(17);
  for (double v : values) out << " " << v;
  return out.str();
}

// The driver: reads lines `KIND t dt y... state...` and writes for each
//   predict <state after predict()>
//   update <returned> <state unchanged bit for bit: 1/0> <state after update()>
// computed in Scalar (the generated one, or PFGEN_TEMPLATE_SCALAR for template code).
std::string driver_source(const std::string& model) {
  std::string s =
      "#include <cstdio>\n#include <cstring>\n#include <string>\n"
      "#include \"" + model + "/cd_optimal.hpp\"\n#include \"" + model + "/cd_ekf.hpp\"\n#include \"" + model +
      "/cd_euler.hpp\"\n"
      "template <class Scalar>\n"
      "static void print(const Scalar* v, std::size_t size) {\n"
      "  for (std::size_t i = 0; i < size; ++i) std::printf(\" %.17g\", static_cast<double>(v[i]));\n"
      "  std::printf(\"\\n\");\n"
      "}\n"
      "#define PFGEN_RUN(KIND)                                                                \\\n"
      "  if (kind == #KIND) {                                                                  \\\n"
      "    namespace k = pfgen_models::" + model + "::KIND;                                   \\\n"
      "    Scalar state[k::state_size], before[k::state_size], y[k::p];                      \\\n"
      "    double t, dt, v;                                                                  \\\n"
      "    if (std::scanf(\"%lf %lf\", &t, &dt) != 2) return 2;                               \\\n"
      "    for (std::size_t i = 0; i < k::p; ++i) {                                          \\\n"
      "      if (std::scanf(\"%lf\", &v) != 1) return 2;                                       \\\n"
      "      y[i] = static_cast<Scalar>(v);                                                  \\\n"
      "    }                                                                                 \\\n"
      "    for (std::size_t i = 0; i < k::state_size; ++i) {                                 \\\n"
      "      if (std::scanf(\"%lf\", &v) != 1) return 2;                                       \\\n"
      "      state[i] = before[i] = static_cast<Scalar>(v);                                  \\\n"
      "    }                                                                                 \\\n"
      "    const k::Params<Scalar> params{};                                                 \\\n"
      "    k::predict(state, static_cast<Scalar>(t), static_cast<Scalar>(dt), params);       \\\n"
      "    std::printf(\"predict\");                                                          \\\n"
      "    print(state, k::state_size);                                                      \\\n"
      "    std::memcpy(state, before, sizeof state);                                         \\\n"
      "    const bool ok = k::update(state, static_cast<Scalar>(t), y, params);              \\\n"
      "    std::printf(\"update %d %d\", ok ? 1 : 0, std::memcmp(state, before, sizeof state) == 0 ? 1 : 0); \\\n"
      "    print(state, k::state_size);                                                      \\\n"
      "    continue;                                                                         \\\n"
      "  }\n"
      "int main() {\n"
      "#ifdef PFGEN_TEMPLATE_SCALAR\n"
      "  using Scalar = PFGEN_TEMPLATE_SCALAR;\n"
      "#else\n"
      "  using Scalar = pfgen_models::" + model + "::cd_optimal::Scalar;\n"
      "#endif\n"
      "  char word[32];\n"
      "  while (std::scanf(\"%31s\", word) == 1) {\n"
      "    const std::string kind = word;\n"
      "    PFGEN_RUN(cd_optimal)\n"
      "    PFGEN_RUN(cd_ekf)\n"
      "    PFGEN_RUN(cd_euler)\n"
      "    return 3;\n"
      "  }\n"
      "  return 0;\n"
      "}\n";
  return s;
}

struct Case {
  std::string kind;
  double t = 0, dt = 0;
  std::vector<double> y, state;
  bool positive_definite = true;  // false: update() must refuse
  std::vector<double> predicted, updated;
};

std::vector<double> numbers(std::istringstream& in, std::size_t count) {
  std::vector<double> out(count);
  for (double& v : out) in >> v;
  return out;
}

void check_model(const std::string& model_path) {
  for (const char* compiler : {"g++", "clang++"}) {
    INFO(compiler << " is not on PATH: it is a test requirement (scripts/install-deps.sh installs g++ and clang)");
    REQUIRE(run_process(std::string("command -v ") + compiler).exit_code == 0);
  }
  const Model model = load_model_file(model_path);
  REQUIRE(model.observation.is_sampled());
  const std::size_t n = model.n(), r = model.p(), size = n + n * (n + 1) / 2;
  std::mt19937 rng(20240611);

  // Points and their expected results, in double, computed once for all builds.
  std::vector<Case> cases;
  for (const char* kind : kKinds) {
    const FilterEquations eq = derive_filter(model, kind_of(kind));
    for (int point = 0; point < kPoints; ++point) {
      Case c;
      c.kind = kind;
      c.t = std::abs(random_rational(rng, 3000));
      // dt from 0.01 to 0.05: the drift terms count, and Heun's Euler-predicted P stays positive
      // definite (the evaluator's Gaussian expectations require it) under the cubic drift.
      c.dt = 0.01 + std::abs(random_rational(rng, 40));
      FilterState s{std::vector<double>(n), std::vector<std::vector<double>>(n, std::vector<double>(n, 0))};
      std::vector<std::vector<double>> L(n, std::vector<double>(n, 0));
      for (std::size_t i = 0; i < n; ++i) {
        s.m[i] = random_rational(rng, 3000);
        for (std::size_t j = 0; j <= i; ++j) L[i][j] = random_rational(rng, 2000);
      }
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
          long double sum = i == j ? 0.1L : 0.0L;
          for (std::size_t l = 0; l < n; ++l) sum += static_cast<long double>(L[i][l]) * L[j][l];
          s.P[i][j] = static_cast<double>(sum);
        }
      c.state = pack(s);
      for (std::size_t i = 0; i < r; ++i) c.y.push_back(random_rational(rng, 10000));
      c.predicted = expected_predict(model, eq, kind_of(kind), c.t, c.dt, c.state);
      const KalmanReference ref = expected_update(model, c.t, c.state, c.y);
      c.updated = ref.state;
      // The evaluator (`pfgen eval`) agrees with the reference's S and K.
      const EvaluatedFilter e = evaluate(model, eq, c.t, s);
      for (std::size_t i = 0; i < r; ++i)
        for (std::size_t j = 0; j < r; ++j) {
          const long double Sij = ref.S(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
          CHECK(std::abs(e.innovation_covariance[i][j] - static_cast<double>(Sij)) <=
                1e-13 * static_cast<double>(ref.S.cwiseAbs().maxCoeff()));
        }
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < r; ++j) {
          const long double Kij = ref.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
          CHECK(std::abs(e.gain[i][j] - static_cast<double>(Kij)) <=
                1e-13 * static_cast<double>(ref.K.cwiseAbs().maxCoeff()));
        }
      cases.push_back(c);
    }
    // (c) S not positive definite: P = -I (S = R - C C^T, negative definite here) ...
    Case negative;
    negative.kind = kind;
    negative.t = 0.5;
    negative.dt = 0.1;
    negative.positive_definite = false;
    FilterState s{std::vector<double>(n, 0.3), std::vector<std::vector<double>>(n, std::vector<double>(n, 0))};
    for (std::size_t i = 0; i < n; ++i) s.P[i][i] = -1;
    negative.state = pack(s);
    negative.y.assign(r, 1.0);
    {
      const Observation o = observation_at(model, negative.t);
      MatL P = -MatL::Identity(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
      REQUIRE(Eigen::LLT<MatL>(o.C * P * o.C.transpose() + o.R).info() != Eigen::Success);
    }
    cases.push_back(negative);
    // ... and, with r = n = 2, P = C^-1 (S - R) C^-T for S = [[1, 3], [3, 1]]: a positive diagonal,
    // so the first pivot passes and the second (1 - 9 < 0) fails.
    if (r == 2 && n == 2) {
      const Observation o = observation_at(model, negative.t);
      MatL S(2, 2);
      S << 1, 3, 3, 1;
      const MatL Cinv = o.C.inverse();
      const MatL P = Cinv * (S - o.R) * Cinv.transpose();
      Case indefinite = negative;
      FilterState si{{0.3, -0.2}, {{static_cast<double>(P(0, 0)), static_cast<double>(P(0, 1))},
                                   {static_cast<double>(P(0, 1)), static_cast<double>(P(1, 1))}}};
      indefinite.state = pack(si);
      cases.push_back(indefinite);
    }
  }

  std::string input;
  for (const Case& c : cases) input += c.kind + " " + join({c.t, c.dt}) + join(c.y) + join(c.state) + "\n";

  TempDir dir;
  write_file(dir.file("input.txt"), input);
  std::size_t builds = 0;
  for (const std::string scalar : {"double", "float", "template"}) {
    const std::string out = dir.file(scalar);
    ProcessResult generated = run_pfgen({"codegen", model_path, "-o", out, "--scalar", scalar});
    INFO("pfgen codegen " << model_path << " --scalar " << scalar << ": " << generated.err);
    REQUIRE(generated.exit_code == 0);
    write_file(out + "/driver.cpp", driver_source(model.name));
    const std::vector<std::string> template_scalars =
        scalar == "template" ? std::vector<std::string>{"double", "float"} : std::vector<std::string>{""};
    for (const std::string& template_scalar : template_scalars) {
      const bool is_float = scalar == "float" || template_scalar == "float";
      const double tolerance = is_float ? kFloatTolerance : kDoubleTolerance;
      for (const std::string compiler : {"g++", "clang++"}) {
        const std::string binary = out + "/driver-" + compiler + "-" + template_scalar;
        const std::string command =
            compiler + " -std=c++17 -O2 -Wall -Wextra -Werror -I " + shell_quote(out) +
            (template_scalar.empty() ? "" : " -DPFGEN_TEMPLATE_SCALAR=" + template_scalar) + " " +
            shell_quote(out + "/driver.cpp") + " -o " + shell_quote(binary);
        ProcessResult compiled = run_process(command);
        INFO(command << "\n" << compiled.err.substr(0, 4000));
        REQUIRE(compiled.exit_code == 0);
        ProcessResult ran = run_process(shell_quote(binary) + " < " + shell_quote(dir.file("input.txt")));
        INFO(ran.err);
        REQUIRE(ran.exit_code == 0);
        ++builds;

        std::istringstream lines(ran.out);
        std::size_t refused = 0;
        for (const Case& c : cases) {
          INFO(c.kind << " at t = " << c.t << ", dt = " << c.dt << ", state" << join(c.state) << ", y" << join(c.y));
          std::string word;
          lines >> word;
          REQUIRE(word == "predict");
          const std::vector<double> predicted = numbers(lines, size);
          int ok = -1, unchanged = -1;
          lines >> word >> ok >> unchanged;
          REQUIRE(word == "update");
          const std::vector<double> updated = numbers(lines, size);
          REQUIRE(lines);
          if (!c.positive_definite) {
            CHECK(ok == 0);
            CHECK(unchanged == 1);  // "leaving the state unchanged" (the template's promise)
            ++refused;
            continue;
          }
          REQUIRE(ok == 1);
          CHECK(unchanged == 0);
          const double dev_predict = relative_deviation(predicted, c.predicted, c.state, n);
          const double dev_update = relative_deviation(updated, c.updated, c.state, n);
          INFO("predict: generated" << join(predicted) << ", expected" << join(c.predicted) << "; update: generated"
                                    << join(updated) << ", expected" << join(c.updated));
          CHECK(dev_predict <= tolerance);
          CHECK(dev_update <= tolerance);
        }
        CHECK(refused == (r == 2 && n == 2 ? 6u : 3u));
        std::string rest;
        CHECK(!(lines >> rest));  // nothing beyond the cases
      }
    }
  }
  CHECK(builds == 8);
}

}  // namespace

TEST_CASE("generated sampled filters of paper 003's example, gamma = 1: predict and update agree with independent references",
          "[codegen][sampled][compiler]") {
  check_model(example("allahyani_date_example1_gamma1.yaml"));
}

TEST_CASE("generated sampled filters of paper 003's example, gamma = 0.5: predict and update agree with independent references",
          "[codegen][sampled][compiler]") {
  check_model(example("allahyani_date_example1_gamma05.yaml"));
}

TEST_CASE("generated sampled filters with two observations (off-diagonal S): predict and update agree with independent references",
          "[codegen][sampled][compiler]") {
  check_model(test_data_dir() + "/sampled_two_observations.yaml");
}
