// quantiles_in_place (runtime statistics): several quantiles of one sample by selecting the order
// statistics they need, which the Monte Carlo summaries and quantile() use. Each must be the plain
// definition's value bit for bit (sort, then interpolate between order statistics: Hyndman-Fan
// type 7), so the summary tables and CSVs do not change, for samples with ties, infinities, sizes
// 1 .. 60 and 2001, and quantiles that share or neighbour order statistics.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "pfgen_runtime/statistics.hpp"

using pfgen_runtime::quantile;
using pfgen_runtime::quantiles_in_place;

namespace {
// The definition, by a full sort.
double sorted_quantile(std::vector<double> sample, double q) {
  std::sort(sample.begin(), sample.end());
  const double position = q * static_cast<double>(sample.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  if (below + 1 >= sample.size()) return sample.back();
  const double fraction = position - static_cast<double>(below);
  return sample[below] + fraction * (sample[below + 1] - sample[below]);
}
}  // namespace

TEST_CASE("quantiles_in_place and quantile() give the sorted definition's values bit for bit", "[unit][runtime]") {
  std::mt19937_64 engine(20261127);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> small(-3, 3);
  const std::vector<std::vector<double>> quantile_sets = {
      {0.05, 0.5, 0.95}, {0.5, 0.95}, {0.0, 1.0}, {0.5, 0.5, 0.5}, {0.1, 0.11, 0.12, 0.9, 1.0}, {1.0}};
  std::vector<std::size_t> sizes;
  for (std::size_t size = 1; size <= 60; ++size) sizes.push_back(size);
  sizes.push_back(2001);
  for (std::size_t size : sizes)
    for (int kind = 0; kind < 3; ++kind) {
      std::vector<double> sample(size);
      for (double& v : sample) v = kind == 0 ? normal(engine) : small(engine);  // kind 1, 2: many ties
      if (kind == 2 && size > 2) {
        sample[0] = std::numeric_limits<double>::infinity();
        sample[size / 2] = -std::numeric_limits<double>::infinity();
      }
      for (const auto& qs : quantile_sets) {
        std::vector<double> reordered = sample, out;
        quantiles_in_place(reordered, qs, out);
        REQUIRE(out.size() == qs.size());
        for (std::size_t k = 0; k < qs.size(); ++k) {
          const double expected = sorted_quantile(sample, qs[k]), single = quantile(sample, qs[k]);
          INFO("size " << size << " kind " << kind << " q " << qs[k]);
          if (std::isnan(expected)) {  // inf - inf between two infinite order statistics
            CHECK(std::isnan(out[k]));
            CHECK(std::isnan(single));
          } else {
            CHECK(out[k] == expected);
            CHECK(single == expected);
          }
        }
      }
    }
}

TEST_CASE("quantiles_in_place refuses what quantile() refuses, and quantiles out of order", "[unit][runtime]") {
  std::vector<double> out, empty, with_nan = {1.0, std::nan(""), 2.0}, sample = {3.0, 1.0, 2.0};
  CHECK_THROWS_AS(quantiles_in_place(empty, {0.5}, out), std::invalid_argument);
  CHECK_THROWS_AS(quantiles_in_place(with_nan, {0.5}, out), std::invalid_argument);
  CHECK_THROWS_AS(quantiles_in_place(sample, {1.5}, out), std::invalid_argument);
  CHECK_THROWS_AS(quantiles_in_place(sample, {0.9, 0.1}, out), std::invalid_argument);
}
