// Stratonovich noise (`noise: stratonovich`): the Ito correction c_i = 1/2 sum_jk g_jk dg_ik/dx_j
// against corrections worked out by hand, its place in the reports, the models it refuses, and
// the truth it simulates checked in law. Paper 000's state read with Stratonovich noise is
// u = -10/x with du = dt + dW (Stratonovich chain rule), so x blows up when Brownian motion with
// drift 1 from -10/1.1 first reaches 0: an inverse Gaussian time, mean mu = 100/11, shape mu^2.
// pfgen simulates the Ito form (drift 0.1x^2 + 0.01x^3) with its adaptive Euler scheme; the
// empirical law of its blow-up times must be that one.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/stratonovich.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen;
using namespace pfgen_test;
using Catch::Matchers::Contains;

namespace {

bool same(const GiNaC::ex& a, const GiNaC::ex& b) { return (a - b).expand().is_zero(); }

// The inverse Gaussian distribution function with mean mu and shape lambda.
double inverse_gaussian_cdf(double t, double mu, double lambda) {
  const double a = std::sqrt(lambda / t);
  auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  return Phi(a * (t / mu - 1)) + std::exp(2 * lambda / mu) * Phi(-a * (t / mu + 1));
}

}  // namespace

TEST_CASE("stratonovich: the Ito correction against hand-worked cases", "[stratonovich][unit]") {
  GiNaC::symbol x("x"), y("y"), t("t"), a("a");
  SECTION("paper 000: g = 0.1 x^2 gives 0.01 x^3") {
    const ExVector c = stratonovich_correction({{GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)}}, {x});
    CHECK(same(c[0], GiNaC::numeric(1, 100) * GiNaC::pow(x, 3)));
  }
  SECTION("geometric noise g = a x gives a^2 x / 2") {
    const ExVector c = stratonovich_correction({{a * x}}, {x});
    CHECK(same(c[0], a * a * x / 2));
  }
  SECTION("two states, three noises, time in g: each sum_jk g_jk dg_ik/dx_j by hand") {
    // g = [x y, 0, sin(t); 1, x^2, y]
    const ExMatrix g = {{x * y, 0, GiNaC::sin(t)}, {1, GiNaC::pow(x, 2), y}};
    const ExVector c = stratonovich_correction(g, {x, y});
    // i = 1: g_11 d(xy)/dx + g_21 d(xy)/dy = x y * y + 1 * x (the other columns of row 1 are constant)
    CHECK(same(c[0], (x * y * y + x) / 2));
    // i = 2: column 2, g_12 d(x^2)/dx + g_22 d(x^2)/dy = 0; column 3, g_13 d(y)/dx + g_23 d(y)/dy = y
    CHECK(same(c[1], y / 2));
  }
  SECTION("state-independent noise has none") {
    const ExVector c = stratonovich_correction({{1, t}, {a, 0}}, {x, y});
    CHECK(c[0].is_zero());
    CHECK(c[1].is_zero());
  }
}

TEST_CASE("stratonovich: the model keeps the drift as written and derives from the Ito drift",
          "[stratonovich][unit]") {
  const Model strat = load_model_file(example("paper000/stratonovich.yaml"));
  const Model ito = load_model_file(example("basin2006_quadratic.yaml"));
  const GiNaC::ex x = strat.states[0];
  REQUIRE(strat.noise == NoiseCalculus::Stratonovich);
  CHECK(ito.noise == NoiseCalculus::Ito);
  CHECK(ito.stated_drift.empty());
  CHECK(same(strat.stated_drift[0], GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)));
  CHECK(same(strat.noise_correction[0], GiNaC::numeric(1, 100) * GiNaC::pow(x, 3)));
  CHECK(same(strat.drift[0], strat.stated_drift[0] + strat.noise_correction[0]));
  // Every filter reads the Ito drift: optimal's dm is E[0.1 x^2 + 0.01 x^3] = 0.1 (m^2 + P) + 0.01 (m^3 + 3 m P).
  const FilterEquations eq = derive_filter(strat, FilterKind::Optimal);
  const auto& v = eq.variables.symbols();
  const GiNaC::ex m = v[0], P = v[1];
  CHECK(same(eq.m_drift[0].to_ex(v), GiNaC::numeric(1, 10) * (m * m + P) + GiNaC::numeric(1, 100) * (m * m * m + 3 * m * P)));
}

TEST_CASE("stratonovich: derive shows f, c and f + c in text, LaTeX and JSON; Ito output has none",
          "[stratonovich][cli][integration]") {
  const std::string model = example("paper000/stratonovich.yaml");
  const ProcessResult text = run_pfgen({"derive", model});
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.out, Contains("model: basin2006_stratonovich\nnoise: stratonovich (dx = f dt + g o dW); the equations "
                                "use the Ito drift f + c, c_i = 1/2 sum_jk g_jk d(g_ik)/d(x_j)\n"
                                "  f1 = 0.1*x^2;  c1 = 0.01*x^3;  f1 + c1 = 0.01*x^3 + 0.1*x^2\nfilter: optimal"));
  const ProcessResult latex = run_pfgen({"derive", model, "--format", "latex"});
  REQUIRE(latex.exit_code == 0);
  CHECK_THAT(latex.out, Contains("c_{1} &= 0.01\\,x^{3} \\\\\nf_{1} + c_{1} &= 0.01\\,x^{3} + 0.1\\,x^{2}\n"));
  const ProcessResult json = run_pfgen({"derive", model, "--format", "json"});
  REQUIRE(json.exit_code == 0);
  CHECK_THAT(json.out, Contains("\"noise\": {\n    \"calculus\": \"stratonovich\",\n    \"drift_as_written\": "
                                "[\"0.1*x^2\"],\n    \"correction\": [\"0.01*x^3\"],\n    \"ito_drift\": "
                                "[\"0.01*x^3 + 0.1*x^2\"]\n  },"));
  const ProcessResult ito = run_pfgen({"derive", example("basin2006_quadratic.yaml"), "--format", "json"});
  REQUIRE(ito.exit_code == 0);
  CHECK(ito.out.find("\"noise\":") == std::string::npos);
}

TEST_CASE("stratonovich: needs g, and only ito or stratonovich", "[stratonovich][api][unit]") {
  ModelBuilder b("covariance_only");
  GiNaC::symbol x = b.state("x");
  b.drift({-x});
  b.diffusion_covariance({{x * x}});
  b.observation({0}, {{1}}, {{1}});
  b.noise(NoiseCalculus::Stratonovich);
  CHECK_THROWS_WITH(b.build(), Contains("field 'noise': stratonovich needs the diffusion as g"));
}

TEST_CASE("stratonovich: paper 000's truth blows up with the inverse Gaussian law of u = -10/x",
          "[stratonovich][simulate][statistical]") {
  TempDir dir;
  const ProcessResult r = run_pfgen({"simulate", example("paper000/stratonovich.yaml"), "--filters", "optimal", "--runs",
                                     "1000", "--T", "20", "--dt", "1e-3", "--threads", "2", "-q", "--stops-csv",
                                     dir.file("stops.csv")});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::vector<double> times;
  std::istringstream csv(read_file(dir.file("stops.csv")));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "source,event,run,t");
  while (std::getline(csv, line))
    if (line.rfind("truth,diverged,", 0) == 0) times.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  std::sort(times.begin(), times.end());
  const double mu = 100.0 / 11, lambda = mu * mu;
  // 995.7 of 1000 expected by t = 20 (binomial sd 2.1); the Ito form integrated past the bound
  // inside a grid step once carried ~5% of the paths through infinity to negative x.
  CHECK(times.size() >= 985);
  // Kolmogorov-Smirnov distance on [0, 20] (the censored runs count in the denominator); the
  // 0.1% critical value for 1000 draws is 1.95/sqrt(1000) = 0.062. Grid times are later than the
  // blow-up by at most dt = 0.001.
  double distance = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double F = inverse_gaussian_cdf(times[k], mu, lambda);
    distance = std::max({distance, std::abs(F - static_cast<double>(k + 1) / 1000), std::abs(F - static_cast<double>(k) / 1000)});
  }
  INFO("KS distance " << distance << " over " << times.size() << " blow-ups");
  CHECK(distance < 0.062);
  // And the Ito reading never blows up (z = 10/x never reaches 0).
  const ProcessResult ito = run_pfgen({"simulate", example("basin2006_quadratic.yaml"), "--filters", "optimal",
                                       "--runs", "200", "--T", "20", "--dt", "1e-3", "-q"});
  REQUIRE(ito.exit_code == 0);
  CHECK_THAT(ito.out, Contains("Truth diverged: no run"));
}

// scripts/paper000-blowup.sh with small settings: its table (both readings beside the exact law)
// and the simulate sections it quotes. The figures of the full run are in docs/reproductions/basin-perez-skliar-2006.md.
TEST_CASE("stratonovich: the paper 000 blow-up script runs with small settings", "[stratonovich][simulate][compiler]") {
  TempDir dir;
  const auto result = run_program({"env", "PFGEN=" + pfgen_executable(), "THREADS=1",
                                   source_dir() + "/scripts/paper000-blowup.sh", "60", "0.01", "15", dir.file("out")});
  INFO(result.out << result.err);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.out, Contains("reading                   blown up by 9.2  blown up by T"));
  // The exact law's line: its quantiles do not depend on the run (only its counts on RUNS and T).
  CHECK(std::regex_search(result.out, std::regex(R"(\nexact \(inverse Gaussian\) +[0-9.]+ of 60 +[0-9.]+ of 60 +[0-9.]+ +)"
                                                 R"(5\.075 +6\.919 +8\.621 +10\.749 +14\.710\n)")));
  CHECK_THAT(result.out, Contains("\nito                       0 of 60          0 of 60"));
  CHECK_THAT(result.out, Contains("Stratonovich reading: the filters up to the blow-up"));
  CHECK_THAT(result.out, Contains("Truth diverged: no run"));
}
