// The sampled moment filters' update (cd-closure3, cd-closure4; observations/sampled/sampled_moment_update.hpp)
// against an enumeration: a prior law on five points of the plane and a noise whose components take -sqrt(3), 0
// and sqrt(3) with probabilities 1/6, 2/3, 1/6 (N(0, 1)'s moments up to order 5, so the updated law's moments up to
// order 4 are those of Gaussian noise). x+ = x + K (y - C0 - C x - Uv z), taken point by point over the 5 x 9 pairs,
// gives the updated law's central moments exactly; eval's moments after the update must equal them.
#include <catch2/catch.hpp>

#include <cmath>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

using namespace pfgen;

namespace {

const char* kModel = R"(name: sampled_two_sensors
states: [x1, x2]
drift: ["-x1 + x2^2", "-x2"]
diffusion: [["0.3", "0"], ["0", "0.2*x1"]]
observation:
  sampled:
    period: 0.5
    C0: ["0.1", "-0.3"]
    C: [["1", "0.5"], ["0.2", "-1"]]
    Uv: [["0.3", "0"], ["0.1", "0.4"]]
initial: {x0: [0, 0], m0: [0, 0], P0: [[1, 0], [0, 1]]}
)";

using Vec = std::vector<double>;

// Central moment E[prod (x - mean)_i over the indices] of a weighted point set.
double central(const std::vector<Vec>& points, const Vec& weights, const std::vector<std::size_t>& indices) {
  Vec mean(2, 0);
  for (std::size_t s = 0; s < points.size(); ++s)
    for (std::size_t i = 0; i < 2; ++i) mean[i] += weights[s] * points[s][i];
  double out = 0;
  for (std::size_t s = 0; s < points.size(); ++s) {
    double product = weights[s];
    for (std::size_t i : indices) product *= points[s][i] - mean[i];
    out += product;
  }
  return out;
}

}  // namespace

TEST_CASE("the sampled moment filters' update gives the central moments of the Kalman-updated law",
          "[closure][sampled][unit]") {
  const Model model = load_model_text(kModel, "sampled_two_sensors.yaml");
  const std::vector<Vec> prior = {{0.3, -0.2}, {1.4, 0.5}, {-0.6, 0.9}, {0.1, -1.3}, {2.2, 0.4}};
  const Vec weights = {0.3, 0.15, 0.25, 0.2, 0.1};
  for (FilterKind kind : {FilterKind::CdClosure3, FilterKind::CdClosure4}) {
    const FilterEquations eq = derive_filter(model, kind);
    const FilterVariables& vars = eq.variables;
    INFO(eq.name);
    EvaluationPoint point;
    for (std::size_t i = 0; i < 2; ++i) {
      double mean = 0;
      for (std::size_t s = 0; s < prior.size(); ++s) mean += weights[s] * prior[s][i];
      point.m.push_back(GiNaC::numeric(mean));
    }
    point.P.assign(2, std::vector<GiNaC::numeric>(2));
    for (std::size_t i = 0; i < 2; ++i)
      for (std::size_t j = 0; j < 2; ++j) point.P[i][j] = GiNaC::numeric(central(prior, weights, {i, j}));
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q)
      point.moments[vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q))] =
          GiNaC::numeric(central(prior, weights, vars.higher_moments()[q]));
    const EvaluatedFilter value = evaluate_at(model, eq, point);
    REQUIRE(value.moments_after_update.size() == vars.higher_moments().size());
    // The updated law, point by point.
    const double C0[2] = {0.1, -0.3}, C[2][2] = {{1, 0.5}, {0.2, -1}}, Uv[2][2] = {{0.3, 0}, {0.1, 0.4}};
    const double y[2] = {0.7, -0.2};
    const double root3 = std::sqrt(3.0), z_values[3] = {-root3, 0, root3}, z_weights[3] = {1.0 / 6, 2.0 / 3, 1.0 / 6};
    std::vector<Vec> after;
    Vec after_weights;
    for (std::size_t s = 0; s < prior.size(); ++s)
      for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t b = 0; b < 3; ++b) {
          const double z[2] = {z_values[a], z_values[b]};
          Vec x = prior[s];
          double innovation[2];
          for (std::size_t r = 0; r < 2; ++r)
            innovation[r] = y[r] - C0[r] - C[r][0] * x[0] - C[r][1] * x[1] - Uv[r][0] * z[0] - Uv[r][1] * z[1];
          for (std::size_t i = 0; i < 2; ++i)
            x[i] += value.gain[i][0] * innovation[0] + value.gain[i][1] * innovation[1];
          after.push_back(x);
          after_weights.push_back(weights[s] * z_weights[a] * z_weights[b]);
        }
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
      const double expected = central(after, after_weights, vars.higher_moments()[q]);
      INFO(vars.text_name(vars.first_higher_moment() + static_cast<std::uint32_t>(q)) << ": eval "
                                                                                       << value.moments_after_update[q]
                                                                                       << ", enumeration " << expected);
      CHECK(std::abs(value.moments_after_update[q] - expected) <= 1e-12 + 1e-9 * std::abs(expected));
    }
  }
}
