// quantiles_in_place (runtime statistics): several quantiles of one sample by selecting the order
// statistics they need, which the Monte Carlo summaries use at every record time. Each must be
// quantile()'s value bit for bit (the summary tables and CSVs do not change), for samples with
// ties, infinities, sizes 1 .. 60 and 2001, and quantiles that share or neighbour order statistics.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "pfgen_runtime/statistics.hpp"

using pfgen_runtime::quantile;
using pfgen_runtime::quantiles_in_place;

TEST_CASE("quantiles_in_place gives quantile()'s values bit for bit", "[unit][runtime]") {
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
          const double expected = quantile(sample, qs[k]);
          INFO("size " << size << " kind " << kind << " q " << qs[k]);
          if (std::isnan(expected))
            CHECK(std::isnan(out[k]));  // inf - inf between two infinite order statistics
          else
            CHECK(out[k] == expected);
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
