// The sampled moment filters' update (cd-closure3, cd-closure4; observations/sampled/sampled_moment_update.hpp)
// against an enumeration: a prior law on five points of the plane and a noise whose components take -sqrt(3), 0
// and sqrt(3) with probabilities 1/6, 2/3, 1/6 (N(0, 1)'s moments up to order 5, so the updated law's moments up to
// order 4 are those of Gaussian noise). x+ = x + K (y - C0 - C x - Uv z), taken point by point over the 5 x 9 pairs,
// gives the updated law's moments exactly; eval's moments after the update, and the generated C++ update's m, P
// and higher moments, must equal them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"
#include "support/process.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;
using pfgen_test::run_pfgen;
using pfgen_test::TempDir;
using pfgen_test::ProcessResult;

namespace {

using Vec = std::vector<double>;

const std::string kModel = pfgen_test::test_data_dir() + "/sampled_two_sensors.yaml";
// The model file's samples.
const double kC0[2] = {0.1, -0.3}, kC[2][2] = {{1, 0.5}, {0.2, -1}}, kUv[2][2] = {{0.3, 0}, {0.1, 0.4}};
const double kY[2] = {0.7, -0.2};

// The prior: five weighted points of the plane.
const std::vector<Vec> kPrior = {{0.3, -0.2}, {1.4, 0.5}, {-0.6, 0.9}, {0.1, -1.3}, {2.2, 0.4}};
const Vec kWeights = {0.3, 0.15, 0.25, 0.2, 0.1};

Vec mean_of(const std::vector<Vec>& points, const Vec& weights) {
  Vec mean(2, 0);
  for (std::size_t s = 0; s < points.size(); ++s)
    for (std::size_t i = 0; i < 2; ++i) mean[i] += weights[s] * points[s][i];
  return mean;
}

// Central moment E[prod (x - mean)_i over the indices] of a weighted point set.
double central(const std::vector<Vec>& points, const Vec& weights, const std::vector<std::size_t>& indices) {
  const Vec mean = mean_of(points, weights);
  double out = 0;
  for (std::size_t s = 0; s < points.size(); ++s) {
    double product = weights[s];
    for (std::size_t i : indices) product *= points[s][i] - mean[i];
    out += product;
  }
  return out;
}

// The updated law with gain K (2 x 2): every prior point with every noise value.
void updated_law(const std::vector<Vec>& K, std::vector<Vec>& points, Vec& weights) {
  const double root3 = std::sqrt(3.0), z_values[3] = {-root3, 0, root3}, z_weights[3] = {1.0 / 6, 2.0 / 3, 1.0 / 6};
  for (std::size_t s = 0; s < kPrior.size(); ++s)
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = 0; b < 3; ++b) {
        const double z[2] = {z_values[a], z_values[b]};
        Vec x = kPrior[s];
        double innovation[2];
        for (std::size_t r = 0; r < 2; ++r)
          innovation[r] = kY[r] - kC0[r] - kC[r][0] * x[0] - kC[r][1] * x[1] - kUv[r][0] * z[0] - kUv[r][1] * z[1];
        for (std::size_t i = 0; i < 2; ++i) x[i] += K[i][0] * innovation[0] + K[i][1] * innovation[1];
        points.push_back(x);
        weights.push_back(kWeights[s] * z_weights[a] * z_weights[b]);
      }
}

// The filter state (m, P's upper triangle, the higher moments) of a weighted point set.
Vec filter_state(const FilterVariables& vars, const std::vector<Vec>& points, const Vec& weights) {
  Vec state = mean_of(points, weights);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = i; j < 2; ++j) state.push_back(central(points, weights, {i, j}));
  for (const auto& indices : vars.higher_moments()) state.push_back(central(points, weights, indices));
  return state;
}

}  // namespace

TEST_CASE("the sampled moment filters' update gives the central moments of the Kalman-updated law",
          "[closure][sampled][unit]") {
  const Model model = load_model_file(kModel);
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    INFO(eq.name);
    EvaluationPoint point;
    for (double m : mean_of(kPrior, kWeights)) point.m.push_back(GiNaC::numeric(m));
    point.P.assign(2, std::vector<GiNaC::numeric>(2));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t j = 0; j < 2; ++j) point.P[i][j] = GiNaC::numeric(central(kPrior, kWeights, {i, j}));
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q)
      point.moments[vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q))] =
          GiNaC::numeric(central(kPrior, kWeights, vars.higher_moments()[q]));
    const EvaluatedFilter value = evaluate_at(model, eq, point);
    REQUIRE(value.moments_after_update.size() == vars.higher_moments().size());
    std::vector<Vec> after;
    Vec after_weights;
    updated_law(value.gain, after, after_weights);
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
      const double expected = central(after, after_weights, vars.higher_moments()[q]);
      INFO(vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q))
           << ": eval " << value.moments_after_update[q] << ", enumeration " << expected);
      CHECK(std::abs(value.moments_after_update[q] - expected) <= 1e-12 + 1e-9 * std::abs(expected));
    }
  }
}

TEST_CASE("generated sampled moment filters: the update's m, P and higher moments are the Kalman-updated law's, and "
          "the margins hold at a realisable state",
          "[closure][sampled][codegen][compiler]") {
  const Model model = load_model_file(kModel);
  TempDir dir;
  const ProcessResult generated =
      run_pfgen({"codegen", kModel, "--filter", "cd-closure3,cd-closure4", "--language", "cpp", "-o", dir.path()});
  INFO(generated.err);
  REQUIRE(generated.exit_code == 0);
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    const std::string ns = eq.name == "cd-closure3" ? "cd_closure3" : "cd_closure4";
    INFO(eq.name);
    const Vec prior = filter_state(vars, kPrior, kWeights);
    std::ostringstream state;
    state.precision(17);
    for (double v : prior) state << v << ", ";
    const std::string program = "#include <cstdio>\n#include \"sampled_two_sensors/" + ns + ".hpp\"\n" +
                                "namespace F = pfgen_models::sampled_two_sensors::" + ns + ";\n" +
                                "int main() {\n  double state[F::state_size] = {" + state.str() + "};\n" +
                                "  double margins[F::margin_count];\n  F::realisability_margins(0.0, state, {}, margins);\n" +
                                "  for (double v : margins) std::printf(\"%.17g \", v);\n  std::printf(\"\\n\");\n" +
                                "  const double y[2] = {0.7, -0.2};\n  if (!F::update(state, 0.5, y, {})) return 1;\n" +
                                "  for (double v : state) std::printf(\"%.17g \", v);\n  std::printf(\"\\n\");\n}\n";
    pfgen_test::write_file(dir.file("main.cpp"), program);
    const std::string command = "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + pfgen_test::shell_quote(dir.path()) +
                                " " + pfgen_test::shell_quote(dir.file("main.cpp")) + " -o " +
                                pfgen_test::shell_quote(dir.file("update"));
    const ProcessResult compiled = pfgen_test::run_process(command);
    INFO(compiled.err.substr(0, 4000));
    REQUIRE(compiled.exit_code == 0);
    const ProcessResult ran = pfgen_test::run_process(pfgen_test::shell_quote(dir.file("update")));
    REQUIRE(ran.exit_code == 0);
    std::istringstream lines(ran.out);
    // The prior is a law: every margin is positive.
    for (std::size_t k = 0; k < eq.realisability.size(); ++k) {
      double margin = 0;
      lines >> margin;
      INFO(eq.realisability_meaning[k] << " = " << margin);
      CHECK(margin > 0);
    }
    Vec updated(prior.size());
    for (double& v : updated) lines >> v;
    REQUIRE(lines);
    // K = P C^T S^-1 from the prior's P, by hand.
    const double P[2][2] = {{prior[2], prior[3]}, {prior[3], prior[4]}};
    double PCt[2][2] = {}, S[2][2] = {};
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t a = 0; a < 2; ++a)
        for (std::size_t k = 0; k < 2; ++k) PCt[i][a] += P[i][k] * kC[a][k];
    for (std::size_t a = 0; a < 2; ++a)
      for (std::size_t b = 0; b < 2; ++b) {
        S[a][b] = kUv[a][0] * kUv[b][0] + kUv[a][1] * kUv[b][1];
        for (std::size_t k = 0; k < 2; ++k) S[a][b] += kC[a][k] * PCt[k][b];
      }
    const double det = S[0][0] * S[1][1] - S[0][1] * S[1][0];
    const double Si[2][2] = {{S[1][1] / det, -S[0][1] / det}, {-S[1][0] / det, S[0][0] / det}};
    std::vector<Vec> K(2, Vec(2, 0));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t a = 0; a < 2; ++a)
        for (std::size_t b = 0; b < 2; ++b) K[i][a] += PCt[i][b] * Si[b][a];
    std::vector<Vec> after;
    Vec after_weights;
    updated_law(K, after, after_weights);
    const Vec expected = filter_state(vars, after, after_weights);
    for (std::size_t v = 0; v < expected.size(); ++v) {
      INFO(vars.text_name(static_cast<std::uint32_t>(v)) << ": generated " << updated[v] << ", enumeration "
                                                         << expected[v]);
      CHECK(std::abs(updated[v] - expected[v]) <= 1e-12 + 1e-9 * std::abs(expected[v]));
    }
  }
}

// Samples through a polynomial c (closure_sampled_update.hpp), checked where the closed law is known: from a Gaussian
// prior (M3 = 0 and M4 = Isserlis', so that every cumulant above order 2 is zero) the closed law is N(m, P), and the
// update's gain, S and moments are those of x + K (y - c(x) - Uv z) with x ~ N(m, P). A 5 x 5 Gauss-Hermite grid (exact
// for polynomials of degree <= 9 in each coordinate; the moments of order 4 are of degree 8) and the 3 x 3 noise
// points above give them, independently of the derivation.
namespace {

const std::string kPolynomialModel = pfgen_test::test_data_dir() + "/sampled_polynomial_two_outputs.yaml";
const Vec kGaussMean = {0.4, -0.3};
const double kGaussP[2][2] = {{0.5, 0.1}, {0.1, 0.4}}, kPolyUv[2][2] = {{0.2, 0}, {0.1, 0.3}};

// The model file's c.
Vec sample_of(const Vec& x) { return {x[0] * x[0] + x[1] * x[1], x[0] * x[1] + 0.5 * x[0]}; }

// N(kGaussMean, kGaussP) as 25 weighted points: x = m + L xi, L the Cholesky factor, xi on the 5-point grid.
void gaussian_prior(std::vector<Vec>& points, Vec& weights) {
  const double s = std::sqrt(10.0), inner = std::sqrt(5 - s), outer = std::sqrt(5 + s);
  const double xi[5] = {-outer, -inner, 0, inner, outer};
  const double w[5] = {(7 - 2 * s) / 60, (7 + 2 * s) / 60, 8.0 / 15, (7 + 2 * s) / 60, (7 - 2 * s) / 60};
  const double l11 = std::sqrt(kGaussP[0][0]), l21 = kGaussP[1][0] / l11, l22 = std::sqrt(kGaussP[1][1] - l21 * l21);
  for (std::size_t a = 0; a < 5; ++a)
    for (std::size_t b = 0; b < 5; ++b) {
      points.push_back({kGaussMean[0] + l11 * xi[a], kGaussMean[1] + l21 * xi[a] + l22 * xi[b]});
      weights.push_back(w[a] * w[b]);
    }
}

// Cov(x, c) S^-1, S = Cov(c) + Uv Uv^T, over the prior's points; S into `S`.
std::vector<Vec> moment_matching_gain(const std::vector<Vec>& points, const Vec& weights, std::vector<Vec>& S) {
  Vec Ec(2, 0);
  for (std::size_t s = 0; s < points.size(); ++s)
    for (std::size_t a = 0; a < 2; ++a) Ec[a] += weights[s] * sample_of(points[s])[a];
  const Vec m = mean_of(points, weights);
  std::vector<Vec> cross(2, Vec(2, 0));
  S.assign(2, Vec(2, 0));
  for (std::size_t s = 0; s < points.size(); ++s) {
    const Vec c = sample_of(points[s]);
    for (std::size_t a = 0; a < 2; ++a) {
      for (std::size_t i = 0; i < 2; ++i) cross[i][a] += weights[s] * (points[s][i] - m[i]) * (c[a] - Ec[a]);
      for (std::size_t b = 0; b < 2; ++b) S[a][b] += weights[s] * (c[a] - Ec[a]) * (c[b] - Ec[b]);
    }
  }
  for (std::size_t a = 0; a < 2; ++a)
    for (std::size_t b = 0; b < 2; ++b) S[a][b] += kPolyUv[a][0] * kPolyUv[b][0] + kPolyUv[a][1] * kPolyUv[b][1];
  const double det = S[0][0] * S[1][1] - S[0][1] * S[1][0];
  const double Si[2][2] = {{S[1][1] / det, -S[0][1] / det}, {-S[1][0] / det, S[0][0] / det}};
  std::vector<Vec> K(2, Vec(2, 0));
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t a = 0; a < 2; ++a)
      for (std::size_t b = 0; b < 2; ++b) K[i][a] += cross[i][b] * Si[b][a];
  return K;
}

// x + K (y - c(x) - Uv z) over the prior's points and the noise's.
void polynomial_updated_law(const std::vector<Vec>& prior, const Vec& prior_weights, const std::vector<Vec>& K,
                            std::vector<Vec>& points, Vec& weights) {
  const double root3 = std::sqrt(3.0), z_values[3] = {-root3, 0, root3}, z_weights[3] = {1.0 / 6, 2.0 / 3, 1.0 / 6};
  for (std::size_t s = 0; s < prior.size(); ++s)
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = 0; b < 3; ++b) {
        const double z[2] = {z_values[a], z_values[b]};
        Vec x = prior[s];
        const Vec c = sample_of(x);
        double innovation[2];
        for (std::size_t r = 0; r < 2; ++r) innovation[r] = kY[r] - c[r] - kPolyUv[r][0] * z[0] - kPolyUv[r][1] * z[1];
        for (std::size_t i = 0; i < 2; ++i) x[i] += K[i][0] * innovation[0] + K[i][1] * innovation[1];
        points.push_back(x);
        weights.push_back(prior_weights[s] * z_weights[a] * z_weights[b]);
      }
}

bool close(double value, double expected) { return std::abs(value - expected) <= 1e-12 + 1e-9 * std::abs(expected); }

// The prior N(kGaussMean, kGaussP) as points, its moment-matching gain and S, and the updated law as points.
struct GaussianUpdate {
  std::vector<Vec> prior, K, S, after;
  Vec prior_weights, after_weights;
};

GaussianUpdate gaussian_update() {
  GaussianUpdate law;
  gaussian_prior(law.prior, law.prior_weights);
  law.K = moment_matching_gain(law.prior, law.prior_weights, law.S);
  polynomial_updated_law(law.prior, law.prior_weights, law.K, law.after, law.after_weights);
  return law;
}

}  // namespace

TEST_CASE("moment filters with samples through a polynomial c: from a Gaussian prior, eval's gain, S and moments "
          "after the update are those of the moment-matching update of N(m, P) (Gauss-Hermite)",
          "[closure][sampled][unit]") {
  const Model model = load_model_file(kPolynomialModel);
  const GaussianUpdate law = gaussian_update();
  const std::vector<Vec>& K = law.K;
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    INFO(eq.name);
    REQUIRE(eq.update.closed_law);
    EvaluationPoint point;
    for (double m : kGaussMean) point.m.push_back(GiNaC::numeric(m));
    point.P.assign(2, std::vector<GiNaC::numeric>(2));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t j = 0; j < 2; ++j) point.P[i][j] = GiNaC::numeric(kGaussP[i][j]);
    // Left out, the higher moments take the Gaussian values.
    const EvaluatedFilter value = evaluate_at(model, eq, point);
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t a = 0; a < 2; ++a) {
        INFO("K" << i + 1 << a + 1 << ": eval " << value.gain[i][a] << ", quadrature " << K[i][a]);
        CHECK(close(value.gain[i][a], K[i][a]));
        INFO("S" << i + 1 << a + 1 << ": eval " << value.innovation_covariance[i][a] << ", quadrature " << law.S[i][a]);
        CHECK(close(value.innovation_covariance[i][a], law.S[i][a]));
      }
    REQUIRE(value.moments_after_update.size() == vars.higher_moments().size());
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
      const double expected = central(law.after, law.after_weights, vars.higher_moments()[q]);
      INFO(vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q))
           << ": eval " << value.moments_after_update[q] << ", quadrature " << expected);
      CHECK(close(value.moments_after_update[q], expected));
    }
  }
}

TEST_CASE("moment filters with samples through x^2: z's joint moments are the closed law's, by the scalar "
          "moment-cumulant relation",
          "[closure][sampled][unit]") {
  // e = x - m, d = e^2 - P (c = x^2, C = E[2 x] = 2 m). With kappa_2 = P, kappa_3 = M3, kappa_4 = M4 - 3 P^2 (0 for
  // cd-closure3, whose M4 is 3 P^2) and every higher cumulant zero, the central moments follow from
  // mu_j = sum_{i=2}^{j} binom(j - 1, i - 1) kappa_i mu_(j-i).
  const Model model = load_model_file(pfgen_test::test_data_dir() + "/sampled_square_sensor.yaml");
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    INFO(eq.name);
    const std::vector<GiNaC::ex>& symbols = vars.symbols();
    const GiNaC::ex P = symbols[vars.P(0, 0)], M3 = symbols[vars.higher_moment({0, 0, 0})];
    const GiNaC::ex M4 = vars.order() >= 4 ? symbols[vars.higher_moment({0, 0, 0, 0})] : 3 * P * P;
    const GiNaC::ex kappa[5] = {0, 0, P, M3, M4 - 3 * P * P};
    std::vector<GiNaC::ex> mu = {1, 0};
    for (unsigned j = 2; j <= 8; ++j) {
      GiNaC::ex sum = 0;
      for (unsigned i = 2; i <= std::min(j, 4u); ++i) sum += GiNaC::binomial(j - 1, i - 1) * kappa[i] * mu[j - i];
      mu.push_back(sum.expand());
    }
    // E[e^a d^b] from the binomial expansion of d^b = (e^2 - P)^b.
    auto joint = [&](unsigned a, unsigned b) {
      GiNaC::ex sum = 0;
      for (unsigned k = 0; k <= b; ++k) sum += GiNaC::binomial(b, k) * mu[a + 2 * k] * GiNaC::pow(-P, b - k);
      return sum.expand();
    };
    REQUIRE(eq.update.joint.size() == eq.update.joint_indices.size());
    std::size_t checked = 0;
    for (std::size_t q = 0; q < eq.update.joint.size(); ++q) {
      const std::vector<std::size_t>& t = eq.update.joint_indices[q];
      const unsigned b = static_cast<unsigned>(std::count(t.begin(), t.end(), 1));
      const GiNaC::ex derived = eq.update.joint[q].to_ex(symbols);
      const GiNaC::ex expected = joint(static_cast<unsigned>(t.size()) - b, b);
      INFO("E[e^" << t.size() - b << " d^" << b << "]: derived " << derived << ", expected " << expected);
      CHECK((derived - expected).expand().is_zero());
      ++checked;
    }
    CHECK(checked == (vars.order() == 3 ? 5u : 9u));  // (a, b) with 1 <= b, 2 <= a + b <= k
  }
}

TEST_CASE("generated moment filters with samples through a polynomial c: from a Gaussian prior the C++ and C "
          "updates give the moment-matching update of N(m, P) (Gauss-Hermite)",
          "[closure][sampled][codegen][compiler]") {
  const Model model = load_model_file(kPolynomialModel);
  const GaussianUpdate law = gaussian_update();
  TempDir dir;
  for (const std::string language : {"cpp", "c"}) {
    const ProcessResult generated = run_pfgen({"codegen", kPolynomialModel, "--filter", "cd-closure3,cd-closure4",
                                               "--language", language, "-o", dir.file(language)});
    INFO(generated.err);
    REQUIRE(generated.exit_code == 0);
  }
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    const std::string file = eq.name == "cd-closure3" ? "cd_closure3" : "cd_closure4";
    INFO(eq.name);
    Vec state = filter_state(vars, law.prior, law.prior_weights);  // the grid is exact: N(m, P)'s moments
    std::ostringstream values;
    values.precision(17);
    for (double v : state) values << v << ", ";
    const std::string body = "  const double y[2] = {0.7, -0.2};\n  if (!UPDATE) return 1;\n"
                             "  for (unsigned k = 0; k < sizeof state / sizeof *state; ++k) printf(\"%.17g \", state[k]);\n"
                             "  printf(\"\\n\");\n  return 0;\n}\n";
    const std::string cpp = "#include <cstdio>\n#include \"sampled_polynomial_two_outputs/" + file + ".hpp\"\n" +
                            "namespace F = pfgen_models::sampled_polynomial_two_outputs::" + file + ";\nusing std::printf;\n" +
                            "int main() {\n  double state[F::state_size] = {" + values.str() + "};\n" +
                            std::regex_replace(body, std::regex("UPDATE"), "F::update(state, 0.5, y, {})");
    const std::string prefix = "pfgen_models_sampled_polynomial_two_outputs_" + file;
    const std::string c = "#include <stdio.h>\n#include \"" + file + ".h\"\nint main(void) {\n  double state[] = {" +
                          values.str() + "};\n  " + prefix + "_params params;\n  " + prefix + "_default_params(&params);\n" +
                          std::regex_replace(body, std::regex("UPDATE"), prefix + "_update(state, 0.5, y, &params)");
    pfgen_test::write_file(dir.file("main.cpp"), cpp);
    pfgen_test::write_file(dir.file("main.c"), c);
    const std::string source_dir = dir.file("c") + "/sampled_polynomial_two_outputs";
    const std::vector<std::string> commands = {
        "g++ -std=c++17 -O2 -Wall -Wextra -Werror -I " + pfgen_test::shell_quote(dir.file("cpp")) + " " +
            pfgen_test::shell_quote(dir.file("main.cpp")) + " -o " + pfgen_test::shell_quote(dir.file("update_cpp")),
        "gcc -std=c99 -O2 -Wall -Wextra -Werror -I " + pfgen_test::shell_quote(source_dir) + " " +
            pfgen_test::shell_quote(dir.file("main.c")) + " " + pfgen_test::shell_quote(source_dir + "/" + file + ".c") +
            " -lm -o " + pfgen_test::shell_quote(dir.file("update_c"))};
    const Vec expected = filter_state(vars, law.after, law.after_weights);
    for (std::size_t b = 0; b < commands.size(); ++b) {
      INFO(commands[b]);
      const ProcessResult compiled = pfgen_test::run_process(commands[b]);
      INFO(compiled.err.substr(0, 4000));
      REQUIRE(compiled.exit_code == 0);
      const ProcessResult ran = pfgen_test::run_process(pfgen_test::shell_quote(dir.file(b == 0 ? "update_cpp" : "update_c")));
      REQUIRE(ran.exit_code == 0);
      std::istringstream line(ran.out);
      Vec updated(expected.size());
      for (double& v : updated) line >> v;
      REQUIRE(line);
      for (std::size_t v = 0; v < expected.size(); ++v) {
        INFO(vars.text_name(static_cast<std::uint32_t>(v)) << ": generated " << updated[v] << ", quadrature "
                                                           << expected[v]);
        CHECK(std::abs(updated[v] - expected[v]) <= 1e-12 + 1e-9 * std::abs(expected[v]));
      }
    }
  }
}

TEST_CASE("moment filters with samples through a polynomial c: the derivation budget refuses, in one line naming "
          "observation.sampled.c, a c whose joint moments would take too long",
          "[closure][sampled][derivation_budget][unit]") {
  // x1^8 + x2^8 + x3^8: z's fourth moments read E[e^g] up to order 32 (unbudgeted this took more than 5 minutes).
  const std::string text = R"(name: octic_samples
states: [x1, x2, x3]
drift: ["-x1", "-x2", "-x3"]
diffusion: [["0.3", "0", "0"], ["0", "0.3", "0"], ["0", "0", "0.3"]]
observation:
  sampled: {period: 0.2, c: ["x1^8 + x2^8 + x3^8 + x1*x2", "x1^2 + x3^3"], Uv: [["0.3", "0"], ["0", "0.3"]]}
initial: {x0: [1, 1, 1], m0: [1, 1, 1], P0: [[0.3, 0, 0], [0, 0.3, 0], [0, 0, 0.3]]}
)";
  const Model model = load_model_text(text, "octic_samples.yaml");
  try {
    derive_filter(model, FilterKind::CdClosure4);
    FAIL("cd-closure4 derived");
  } catch (const ModelError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("octic_samples.yaml") != std::string::npos);
    CHECK(message.find("observation.sampled.c") != std::string::npos);
    CHECK(message.find("products of terms (limit 10000000") != std::string::npos);
    CHECK(message.find("moments up to order 32") != std::string::npos);
    CHECK(message.find('\n') == std::string::npos);
  }
  // Order 3 reads them up to order 24, within the budget.
  CHECK(derive_filter(model, FilterKind::CdClosure3).update.joint.size() == 34);
}

TEST_CASE("eval of a sampled moment filter refuses a point where S is not positive definite or c has a pole, "
          "naming what", "[closure][sampled][unit]") {
  const Model square = load_model_file(pfgen_test::test_data_dir() + "/sampled_square_sensor.yaml");
  const FilterEquations eq = derive_filter(square, FilterKind::CdClosure4);
  EvaluationPoint point;
  point.m = {GiNaC::numeric(1)};
  point.P = {{GiNaC::numeric(1, 5)}};
  // S = M4 - P^2 + 4 m^2 P + 4 m M3 + 0.09 = -1 - 0.04 + 0.8 + 0.09 < 0: generated update() returns false there.
  point.moments["M4_1111"] = GiNaC::numeric(-1);
  CHECK_THROWS_WITH(evaluate_at(square, eq, point),
                    Catch::Contains("the innovation covariance S is not positive definite at the point that --m, "
                                    "--P and --moment give"));
  // c = x^2 / a at a = 0.
  const Model pole = load_model_text(R"(name: pole_samples
states: [x]
parameters: {a: 0}
drift: ["-x"]
diffusion: [["0.5"]]
observation:
  sampled: {period: 0.2, c: ["x^2/a"], Uv: [["0.3"]]}
initial: {x0: [1], m0: [1], P0: [[0.2]]}
)",
                                     "pole_samples.yaml");
  for (FilterKind kind : {FilterKind::CdOptimal, FilterKind::CdClosure3}) {
    point.moments.clear();
    CHECK_THROWS_WITH(evaluate_at(pole, derive_filter(pole, kind), point),
                      Catch::Contains("cannot be computed at this point (a pole of a function"));
  }
}
