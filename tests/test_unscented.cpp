// The unscented kind (`ukf`, docs/theory.md §2.8) against what does not share its code:
// - the Gaussian closure (`optimal`) where the sigma-point rule is exact: affine f and constant g
//   (Kalman-Bucy, n = 2 symbolically, n = 4 with kappa = 0 at a point), paper 000 (n = 1, degrees
//   <= 4 <= 5), paper 001 (quadratic f), the double well (cubic only in x1, the first Cholesky axis);
// - the double well with its states swapped, where the rule is not exact: the difference from
//   optimal is the one derived by hand, 6 P12 det P / P11 and 6 P12^2 det P / P11^2;
// - a numeric sigma-point filter written here with doubles (Cholesky, sigma points, hand-coded f),
//   against `pfgen eval --filter ukf`.
// examples/reference/double_well_velocity_first.yaml is the double well with its states swapped.
#include <catch2/catch.hpp>

#include <regex>

#include <cmath>
#include <functional>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/derivation/unscented.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/json_reader.hpp"
#include "support/symbolic_mismatch.hpp"

using namespace pfgen;
using namespace pfgen_test;
using GiNaC::ex;

namespace {

// A polynomial of the filter with the definitions (L's entries) put in, in their order.
struct Substituted {
  const FilterEquations& eq;
  GiNaC::exmap values;
  explicit Substituted(const FilterEquations& e) : eq(e) {
    // Where P is positive definite the pivots are positive: max(0, d) = (d + |d|) / 2 is d.
    for (const auto& d : eq.definitions) values[d.name] = d.value.subs(values).subs(GiNaC::abs(GiNaC::wild()) == GiNaC::wild());
  }
  ex operator()(const Polynomial& p) const { return p.to_ex(eq.variables.symbols()).subs(values); }
};

// Every equation of ukf equals optimal's, exactly.
void check_equals_optimal(const Model& model) {
  const FilterEquations ukf = derive_filter(model, FilterKind::Ukf);
  const FilterEquations optimal = derive_filter(model, FilterKind::Optimal);
  const Substituted of(ukf);
  // Each derivation names its variables with symbols of its own: read both in ukf's, which its
  // definitions use.
  const auto& symbols = ukf.variables.symbols();
  for (std::size_t i = 0; i < model.n(); ++i) {
    INFO("m_drift " << i + 1);
    CHECK(mismatch(optimal.m_drift[i].to_ex(symbols), of(ukf.m_drift[i])) == "");
    for (std::size_t r = 0; r < model.p(); ++r) CHECK(mismatch(optimal.gain[i][r].to_ex(symbols), of(ukf.gain[i][r])) == "");
  }
  for (std::size_t u = 0; u < optimal.P_moment.size(); ++u) {
    INFO("P entry " << u + 1 << " of the upper triangle");
    CHECK(mismatch(optimal.P_moment[u].to_ex(symbols), of(ukf.P_moment[u])) == "");
    CHECK(mismatch(optimal.P_diffusion[u].to_ex(symbols), of(ukf.P_diffusion[u])) == "");
    CHECK(mismatch(optimal.P_correction[u].to_ex(symbols), of(ukf.P_correction[u])) == "");
  }
  for (std::size_t r = 0; r < model.p(); ++r)
    CHECK(mismatch(optimal.predicted_observation[r].to_ex(symbols), ukf.predicted_observation[r].to_ex(symbols)) == "");
}

const char* kLinear2 = R"(name: linear2
states: [x1, x2]
parameters: {a: 0.3}
drift: ["-x1 + 2*x2 + 1", "a*x1 - 3*x2 + t"]
diffusion: [["1", "0.5"], ["a", "2"]]
observation:
  A0: ["0", "1"]
  A: [["1", "0"], ["1", "1"]]
  B: [["1", "0"], ["0", "2"]]
)";

const char* kLinear4 = R"(name: linear4
states: [x1, x2, x3, x4]
drift: ["-x1 + x2", "-2*x2 + x3 + 1", "x4 - x1", "-x4 + 0.5*x2"]
diffusion: [["1"], ["0.5"], ["0"], ["2"]]
observation:
  A0: ["0"]
  A: [["1", "0", "1", "0"]]
  B: [["1"]]
)";


}  // namespace

TEST_CASE("ukf: sigma-point weights and the Cholesky definitions", "[unit][ukf]") {
  const SigmaPointWeights one = sigma_point_weights(1), three = sigma_point_weights(3), four = sigma_point_weights(4);
  CHECK(one.c == 3);
  CHECK(one.w0 == GiNaC::numeric(2, 3));
  CHECK(one.w == GiNaC::numeric(1, 6));
  CHECK(three.c == 3);
  CHECK(three.w0 == 0);
  CHECK(four.c == 4);  // kappa = 0 above n = 3: w0 = 0, never negative
  CHECK(four.w0 == 0);
  CHECK(four.w == GiNaC::numeric(1, 8));
  for (std::size_t n = 1; n <= 6; ++n) {
    const SigmaPointWeights w = sigma_point_weights(n);
    CHECK(w.w0 + 2 * GiNaC::numeric(static_cast<long>(n)) * w.w == 1);  // the weights sum to one
    CHECK(w.w0 >= 0);
  }

  // The definitions, numerically: L L^T = P at a positive definite P.
  const Model model = load_model_text(kLinear4, "linear4.yaml");
  const FilterEquations eq = derive_filter(model, FilterKind::Ukf);
  REQUIRE(eq.definitions.size() == 10);
  const std::vector<std::string> names = {"L11", "L21", "L31", "L41", "L22", "L32", "L42", "L33", "L43", "L44"};
  const double P[4][4] = {{2.0, 0.3, -0.4, 0.1}, {0.3, 1.5, 0.2, 0.0}, {-0.4, 0.2, 1.1, 0.3}, {0.1, 0.0, 0.3, 0.9}};
  GiNaC::exmap values;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i; j < 4; ++j) values[eq.variables.symbols()[eq.variables.P(i, j)]] = P[i][j];
  double L[4][4] = {};
  for (std::size_t k = 0; k < eq.definitions.size(); ++k) {
    CHECK(eq.definitions[k].name.get_name() == names[k]);
    const ex value = eq.definitions[k].value.subs(values).evalf();
    values[eq.definitions[k].name] = value;
    const std::size_t i = names[k][1] - '1', j = names[k][2] - '1';
    L[i][j] = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
  }
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) {
      double LLt = 0;
      for (std::size_t k = 0; k < 4; ++k) LLt += L[i][k] * L[j][k];
      CHECK(LLt == Approx(P[i][j]).margin(1e-14));
    }
  // No sqrt(c) survives: every coefficient is rational in c (the equations hold L, never sqrt(3)).
  for (const auto* part : {&eq.m_drift, &eq.P_moment, &eq.P_diffusion})
    for (const auto& p : *part)
      for (const auto& [monomial, coefficient] : p.terms()) CHECK(!coefficient.has(GiNaC::sqrt(GiNaC::wild())));
}

TEST_CASE("ukf: affine f and constant g give Kalman-Bucy, equal to optimal", "[unit][ukf]") {
  const Model linear2 = load_model_text(kLinear2, "linear2.yaml");
  check_equals_optimal(linear2);
  const ExactnessReport report = derive_filter(linear2, FilterKind::Ukf).exactness;
  CHECK(report.exact);
  CHECK(report.condition == "Kalman-Bucy");

  // n = 4 (kappa = 0, c = 4, w0 = 0): at a positive definite P with exact rational entries, the
  // Cholesky entries are exact square roots; every equation agrees with optimal to rounding.
  const Model linear4 = load_model_text(kLinear4, "linear4.yaml");
  const FilterEquations ukf = derive_filter(linear4, FilterKind::Ukf);
  const FilterEquations optimal = derive_filter(linear4, FilterKind::Optimal);
  const auto& symbols = ukf.variables.symbols();
  GiNaC::exmap point;
  const int P[4][4] = {{4, 1, -1, 0}, {1, 3, 1, 1}, {-1, 1, 5, 2}, {0, 1, 2, 6}};
  for (std::size_t i = 0; i < 4; ++i) {
    point[symbols[ukf.variables.m(i)]] = GiNaC::numeric(static_cast<long>(i) - 1, 3);
    for (std::size_t j = i; j < 4; ++j) point[symbols[ukf.variables.P(i, j)]] = GiNaC::numeric(P[i][j], 2);
  }
  for (const auto& d : ukf.definitions) point[d.name] = d.value.subs(point);
  auto close = [&](const Polynomial& a, const Polynomial& b) {
    const double x = GiNaC::ex_to<GiNaC::numeric>(a.to_ex(symbols).subs(point).evalf()).to_double();
    const double y = GiNaC::ex_to<GiNaC::numeric>(b.to_ex(symbols).subs(point).evalf()).to_double();
    return std::fabs(x - y) <= 1e-12 * (1 + std::fabs(y));
  };
  for (std::size_t i = 0; i < 4; ++i) CHECK(close(ukf.m_drift[i], optimal.m_drift[i]));
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i; j < 4; ++j) {
      INFO("P entry " << i + 1 << j + 1);
      CHECK(close(ukf.P_drift(i, j), optimal.P_drift(i, j)));
    }
}

TEST_CASE("ukf: exact where the sigma-point rule is (papers 000 and 001, the double well)", "[unit][ukf]") {
  // Paper 000 (n = 1, c = 3): f = 0.1 x^2, (x - m) f and G = 0.01 x^4 have degrees 2, 3, 4, within
  // the three-point Gauss-Hermite rule's 5.
  const Model paper000 = load_model_file(example("basin2006_quadratic.yaml"));
  check_equals_optimal(paper000);
  // Paper 001 (n = 2): f quadratic and g = 0. E[f] needs second moments and E[(x - m) f^T] second
  // and third central moments, which the sigma points match for any c (the odd ones vanish).
  check_equals_optimal(load_model_file(example("basin_skliar_partial.yaml")));
  // The double well: x1^3 only, and x1 - m1 = L11 u1 moves along the first sigma axis alone, where
  // the points are the one-dimensional rule (exact to degree 5): E[(x1-m1)^4] = 3 P11^2 and
  // E[(x2-m2)(x1-m1)^3] = 3 P11 P12 both hold for the sigma points.
  check_equals_optimal(load_model_file(example("reference/double_well.yaml")));
  // Not exact by any published condition, and the report says so.
  const ExactnessReport report = derive_filter(paper000, FilterKind::Ukf).exactness;
  CHECK_FALSE(report.exact);
  CHECK(report.condition == "none");
  CHECK(report.explanation.find("sigma points") != std::string::npos);
}

TEST_CASE("ukf: the double well with the velocity first differs from optimal by the derived amount", "[unit][ukf]") {
  // With the cubic in x, the second state, x - m_x = L21 u1 + L22 u2 spreads over two sigma axes:
  //   E[(v - m_v)(x - m_x)^3] = 3 P12 P22,   sigma points: c L11 L21^3 = 3 P12^3 / P11;
  //   E[(x - m_x)^4] = 3 P22^2,              sigma points: 3 (L21^4 + L22^4).
  // The drift -x^3 of v gives P_moment_11 = 2 E[(v - m_v) f_v] and P_moment_12 = E[f_v (x - m_x)] + ...,
  // so ukf - optimal = 6 P12 det P / P11 (entry 11) and 6 P12^2 det P / P11^2 (entry 12); the rest agree.
  const Model model = load_model_file(example("reference/double_well_velocity_first.yaml"));
  const FilterEquations ukf = derive_filter(model, FilterKind::Ukf);
  const FilterEquations optimal = derive_filter(model, FilterKind::Optimal);
  const Substituted of(ukf);
  const auto& s = ukf.variables.symbols();
  const ex P11 = s[optimal.variables.P(0, 0)], P12 = s[optimal.variables.P(0, 1)], P22 = s[optimal.variables.P(1, 1)];
  const ex det = P11 * P22 - P12 * P12;
  for (std::size_t i = 0; i < 2; ++i) CHECK(mismatch(optimal.m_drift[i].to_ex(s), of(ukf.m_drift[i])) == "");
  const std::vector<ex> difference = {6 * P12 * det / P11, 6 * P12 * P12 * det / (P11 * P11), 0};
  for (std::size_t u = 0; u < 3; ++u) {
    INFO("upper-triangle entry " << u + 1);
    CHECK(mismatch(optimal.P_moment[u].to_ex(s) + difference[u], of(ukf.P_moment[u])) == "");
    CHECK(mismatch(optimal.P_diffusion[u].to_ex(s), of(ukf.P_diffusion[u])) == "");
  }
  CHECK(mismatch(0, difference[0]) != "");  // the difference is not zero: the check can fail
}

TEST_CASE("ukf: L's names keep clear of the model's names", "[unit][ukf]") {
  const std::string clashing = R"(name: clash
states: [L11, x]
parameters: {L21: 0.1}
drift: ["L21*L11^2 + x", "-x"]
diffusion: [["1"], ["0"]]
observation:
  A0: ["0"]
  A: [["1", "0"]]
  B: [["1"]]
)";
  const Model model = load_model_text(clashing, "clash.yaml");
  const FilterEquations ukf = derive_filter(model, FilterKind::Ukf);
  std::vector<std::string> names;
  for (const auto& d : ukf.definitions) names.push_back(d.name.get_name());
  CHECK(names == std::vector<std::string>{"L_11", "L_21", "L_22"});
  check_equals_optimal(model);  // quadratic drift: exact, whatever the names
}

// ---- the numeric sigma-point filter, with doubles ----

namespace {

using Vector = std::vector<double>;
using Matrix = std::vector<Vector>;

struct NumericModel {
  std::function<Vector(const Vector&)> f;
  std::function<Matrix(const Vector&)> G;  // g g^T
  Matrix A;                                // p x n
  Matrix R_inverse;                        // p x p
};

struct NumericFilter {
  Vector m_drift;
  Matrix P_drift, gain;
};

// Sarkka's continuous-time unscented filter at (m, P), written from its definition.
NumericFilter sigma_point_filter(const NumericModel& model, const Vector& m, const Matrix& P) {
  const std::size_t n = m.size(), p = model.A.size();
  Matrix L(n, Vector(n, 0.0));  // Cholesky-Banachiewicz, row by row
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j) {
      double sum = P[i][j];
      for (std::size_t k = 0; k < j; ++k) sum -= L[i][k] * L[j][k];
      L[i][j] = i == j ? std::sqrt(sum) : sum / L[j][j];
    }
  const double c = n <= 3 ? 3.0 : static_cast<double>(n);
  std::vector<Vector> X{m};
  std::vector<double> w{1.0 - n / c};
  for (double sign : {1.0, -1.0})
    for (std::size_t j = 0; j < n; ++j) {
      Vector x = m;
      for (std::size_t i = 0; i < n; ++i) x[i] += sign * std::sqrt(c) * L[i][j];
      X.push_back(x);
      w.push_back(1.0 / (2.0 * c));
    }
  NumericFilter out{Vector(n, 0.0), Matrix(n, Vector(n, 0.0)), Matrix(n, Vector(p, 0.0))};
  for (std::size_t k = 0; k < X.size(); ++k) {
    const Vector fx = model.f(X[k]);
    const Matrix Gx = model.G(X[k]);
    for (std::size_t a = 0; a < n; ++a) {
      out.m_drift[a] += w[k] * fx[a];
      for (std::size_t b = 0; b < n; ++b)
        out.P_drift[a][b] += w[k] * ((X[k][a] - m[a]) * fx[b] + fx[a] * (X[k][b] - m[b]) + Gx[a][b]);
    }
  }
  // K = P A^T R^-1; the correction K A P.
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t r = 0; r < p; ++r)
      for (std::size_t b = 0; b < n; ++b)
        for (std::size_t q = 0; q < p; ++q) out.gain[a][r] += P[a][b] * model.A[q][b] * model.R_inverse[q][r];
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      for (std::size_t r = 0; r < p; ++r)
        for (std::size_t k = 0; k < n; ++k) out.P_drift[a][b] -= out.gain[a][r] * model.A[r][k] * P[k][b];
  return out;
}

std::vector<double> numbers(const JsonValue& array) {
  std::vector<double> out;
  for (const auto& item : array.items) out.push_back(item.number);
  return out;
}

NumericFilter pfgen_eval(const std::string& model, const std::string& filter, const std::string& m, const std::string& P) {
  const ProcessResult r = run_pfgen({"eval", model, "--filter", filter, "--m=" + m, "--P=" + P});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const JsonValue j = parse_json(r.out);
  NumericFilter out;
  out.m_drift = numbers(j["m_drift"]);
  for (const auto& row : j["P_drift"].items) out.P_drift.push_back(numbers(row));
  for (const auto& row : j["gain"].items) out.gain.push_back(numbers(row));
  return out;
}

void check_close(const NumericFilter& expected, const NumericFilter& actual, double tolerance) {
  REQUIRE(actual.m_drift.size() == expected.m_drift.size());
  for (std::size_t a = 0; a < expected.m_drift.size(); ++a) {
    INFO("row " << a + 1);
    CHECK(actual.m_drift[a] == Approx(expected.m_drift[a]).margin(tolerance));
    for (std::size_t b = 0; b < expected.P_drift[a].size(); ++b)
      CHECK(actual.P_drift[a][b] == Approx(expected.P_drift[a][b]).margin(tolerance));
    for (std::size_t r = 0; r < expected.gain[a].size(); ++r)
      CHECK(actual.gain[a][r] == Approx(expected.gain[a][r]).margin(tolerance));
  }
}

}  // namespace

TEST_CASE("ukf: pfgen eval agrees with a numeric sigma-point filter on the double well, both state orders",
          "[integration][ukf]") {
  const double c = 0.5, s = 0.5, r = 0.5;
  const Vector m{0.3, -0.7};
  const Matrix P{{0.8, 0.3}, {0.3, 0.5}};
  // examples/reference/double_well.yaml: x1' = x2, x2' = x1 - x1^3 - c x2 + s W', y' = x1 + r V'.
  NumericModel well;
  well.f = [&](const Vector& x) { return Vector{x[1], x[0] - x[0] * x[0] * x[0] - c * x[1]}; };
  well.G = [&](const Vector&) { return Matrix{{0, 0}, {0, s * s}}; };
  well.A = {{1, 0}};
  well.R_inverse = {{1 / (r * r)}};
  const NumericFilter expected = sigma_point_filter(well, m, P);
  check_close(expected, pfgen_eval(example("reference/double_well.yaml"), "ukf", "0.3,-0.7", "0.8,0.3;0.3,0.5"), 1e-12);
  // Here ukf is optimal (see above): the Gaussian closure's numbers are the same.
  check_close(expected, pfgen_eval(example("reference/double_well.yaml"), "optimal", "0.3,-0.7", "0.8,0.3;0.3,0.5"),
              1e-12);

  // The same model with the velocity first (v, x): ukf is not optimal, and still the numeric filter.
  const std::string velocity_first = example("reference/double_well_velocity_first.yaml");
  NumericModel swapped;
  swapped.f = [&](const Vector& x) { return Vector{x[1] - x[1] * x[1] * x[1] - c * x[0], x[0]}; };
  swapped.G = [&](const Vector&) { return Matrix{{s * s, 0}, {0, 0}}; };
  swapped.A = {{0, 1}};
  swapped.R_inverse = {{1 / (r * r)}};
  const NumericFilter expected_swapped = sigma_point_filter(swapped, m, P);
  const NumericFilter ukf = pfgen_eval(velocity_first, "ukf", "0.3,-0.7", "0.8,0.3;0.3,0.5");
  check_close(expected_swapped, ukf, 1e-12);
  const NumericFilter optimal = pfgen_eval(velocity_first, "optimal", "0.3,-0.7", "0.8,0.3;0.3,0.5");
  // 6 P12 det P / P11 = 6 * 0.3 * 0.31 / 0.8 apart in dP11.
  CHECK(ukf.P_drift[0][0] - optimal.P_drift[0][0] == Approx(6 * 0.3 * 0.31 / 0.8).margin(1e-12));
}

TEST_CASE("ukf: opt-in, refused for sampled and delayed observations, deterministic, a zero pivot named",
          "[integration][ukf]") {
  const std::string well = example("reference/double_well.yaml");
  // Not among the defaults: derive's first filter and codegen's files are as before.
  const Model model = load_model_file(well);
  const std::vector<std::string> defaults = default_filter_names(model);
  CHECK(std::find(defaults.begin(), defaults.end(), "ukf") == defaults.end());
  const std::vector<std::string> available = available_filter_names(model);
  CHECK(std::find(available.begin(), available.end(), "ukf") != available.end());
  TempDir dir;
  REQUIRE(run_pfgen({"codegen", well, "-o", dir.path()}).exit_code == 0);
  CHECK_FALSE(std::filesystem::exists(dir.file("double_well/ukf.hpp")));
  REQUIRE(run_pfgen({"codegen", well, "--filter", "ukf", "-o", dir.file("ukf")}).exit_code == 0);
  CHECK(std::filesystem::exists(dir.file("ukf/double_well/ukf.hpp")));
  // An unknown name lists it among the known ones.
  const ProcessResult unknown = run_pfgen({"derive", well, "--filter", "kalman"});
  CHECK(unknown.exit_code != 0);
  CHECK(unknown.err.find("ukf") != std::string::npos);

  // Deterministic: the same bytes from separate processes, in every format; L's definitions listed.
  for (const std::string format : {"text", "latex", "json"}) {
    const ProcessResult one = run_pfgen({"derive", well, "--filter", "ukf", "--format", format});
    const ProcessResult two = run_pfgen({"derive", well, "--filter", "ukf", "--format", format});
    REQUIRE(one.exit_code == 0);
    CHECK(one.out == two.out);
    CHECK(one.out.find(format == "latex" ? "L_{21}" : "L21") != std::string::npos);
    if (format != "json")  // the sigma points and weights (n = 2: c = 3, w0 = 1/3, w = 1/6) head the report
      CHECK(one.out.find(format == "latex" ? "weights $w_0 = \\frac{1}{3}$, $w_i = \\frac{1}{6}$"
                                           : "weights w_0 = 1/3, w_i = 1/6") != std::string::npos);
  }

  // Sampled and delayed models: the registry's one message.
  for (const auto& [file, kind] : {std::pair<std::string, std::string>{example("allahyani_date_example1_gamma1.yaml"), "sampled"},
                                   {test_data_dir() + "/delayed_scalar.yaml", "delayed"}}) {
    INFO(file);
    for (const auto& args : {std::vector<std::string>{"derive", file, "--filter", "ukf"},
                                                {"codegen", file, "--filter", "ukf", "-o", dir.file("never")}}) {
      const ProcessResult r = run_pfgen(args);
      CHECK(r.exit_code != 0);
      CHECK(r.err.find("'ukf' is not derived for " + kind + " observations") != std::string::npos);
      CHECK(count_lines(r.err) == 1);
    }
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("never")));

  // A zero pivot clamps to 0 (a singular P, [[1, 1], [1, 1]], has the factor [[1, 0], [1, 0]]), and
  // the column below a zero pivot is 0: a positive semi-definite P with a zero variance, such as
  // the prior [[0, 0], [0, 5]], has the factor [[0, 0], [0, sqrt 5]] (0/0 as written, which stopped
  // the filter at t = 0). On this model ukf is optimal exactly, so eval agrees with optimal's there.
  const ProcessResult singular = run_pfgen({"eval", well, "--filter", "ukf", "--m=0,0", "--P=1,1;1,1"});
  CHECK(singular.exit_code == 0);
  for (const std::string P : {"--P=0,0;0,5", "--P=5,0;0,0", "--P=0,0;0,0"}) {
    INFO(P);
    const ProcessResult zero_pivot = run_pfgen({"eval", well, "--filter", "ukf", "--m=0.3,-0.2", P});
    const ProcessResult optimal = run_pfgen({"eval", well, "--filter", "optimal", "--m=0.3,-0.2", P});
    CHECK(zero_pivot.exit_code == 0);
    REQUIRE(optimal.exit_code == 0);
    CHECK(zero_pivot.out.substr(zero_pivot.out.find("\"m_drift\"")) == optimal.out.substr(optimal.out.find("\"m_drift\"")));
  }
}

TEST_CASE("ukf: a prior with a zero variance starts and runs beside optimal and ekf", "[compiler][ukf]") {
  TempDir dir;
  // The double well with the velocity first (where ukf is not optimal) and a known velocity, v0 = 0.
  write_file(dir.file("known_v0.yaml"),
             "name: known_v0\nstates: [v, x]\nparameters: {c: 0.5, s: 0.5, r: 0.5}\n"
             "drift: [\"x - x^3 - c*v\", \"v\"]\ndiffusion: [[\"s\"], [\"0\"]]\n"
             "observation: {A: [[\"0\", \"1\"]], B: [[\"r\"]]}\n"
             "initial: {x0: [0, 1], m0: [0, 0], P0: [[0, 0], [0, 5]]}\n");
  const ProcessResult r = run_pfgen({"simulate", dir.file("known_v0.yaml"), "--filters", "optimal,ekf,ukf", "--runs",
                                     "10", "--T", "1", "--cache-dir", dir.file("cache"), "-q"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("too stiff") == std::string::npos);
  CHECK(r.out.find("not finite at its own state") == std::string::npos);
  CHECK(std::regex_search(r.out, std::regex("\nukf +v +[0-9.]+ +[0-9.]+ +[0-9.]+ +0 ")));  // not diverged
}

TEST_CASE("ukf: generated code compiles and simulate runs it beside optimal and ekf", "[compiler][ukf]") {
  TempDir dir;
  const std::string well = example("reference/double_well.yaml");
  const ProcessResult r = run_pfgen({"simulate", well, "--filters", "optimal,ekf,ukf", "--runs", "20", "--T", "2",
                                     "--cache-dir", dir.file("cache"), "-o", dir.file("r.csv"), "-q"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("ukf") != std::string::npos);
  const std::string csv = read_file(dir.file("r.csv"));
  CHECK(csv.find("ukf") != std::string::npos);
  // Here ukf's equations are optimal's (see the unit cases), so their errors agree to rounding: the
  // rows of the summary that name them carry the same numbers.
  // the summary's numbers in the filter's rows, before the paired differences (which are ukf's own:
  // 1e-17, the rounding by which the two agree)
  auto row = [&](const std::string& name) {
    std::istringstream in(r.out.substr(0, r.out.find("\nPaired against")));
    std::string line, rows;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string first, word;
      words >> first;
      if (first != name) continue;
      while (words >> word) rows += word + " ";
      rows += "\n";
    }
    return rows;
  };
  CHECK(!row("ukf").empty());
  CHECK(row("ukf") == row("optimal"));
  // Header-only code for the filter: the template compiles warning-free with the wrapper.
  REQUIRE(run_pfgen({"codegen", well, "--filter", "ukf", "--scalar", "double", "-o", dir.path()}).exit_code == 0);
  write_file(dir.file("use.cpp"),
             "#include \"double_well/ukf.hpp\"\n#include <cmath>\n#include <cstdio>\n"
             "int main() {\n"
             "  namespace f = pfgen_models::double_well::ukf;\n"
             "  double state[f::state_size];\n  f::initial_state(state);\n"
             "  const double dy[1] = {0.001};\n  const f::Params<double> params{};\n"
             "  for (int k = 0; k < 1000; ++k) f::step(state, 1e-3 * k, 1e-3, dy, params);\n"
             "  for (double v : state) if (!std::isfinite(v)) return 1;\n"
             "  std::printf(\"%.6f\\n\", state[0]);\n  return 0;\n}\n");
  const ProcessResult compiled = run_program({"g++", "-std=c++17", "-O1", "-Wall", "-Wextra", "-Werror", "-I", dir.path(),
                                              dir.file("use.cpp"), "-o", dir.file("use")});
  INFO(compiled.err);
  REQUIRE(compiled.exit_code == 0);
  const ProcessResult ran = run_program({dir.file("use")});
  CHECK(ran.exit_code == 0);
}
