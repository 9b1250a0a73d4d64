// Runs the generated optimal filter of paper 000's example (dx = 0.1 x^2 dt + 0.1 x^2 dW1,
// dy = x dt + dW2) in float over a fixed synthetic observation record, and prints m and P.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "basin2006_quadratic/optimal.hpp"

namespace filter = pfgen_models::basin2006_quadratic::optimal;

namespace {

// A fixed pseudo-random sequence (64-bit LCG), so every run sees the same observations.
class Noise {
 public:
  // Approximately standard normal: the sum of 12 uniforms on [0, 1), minus 6.
  float next() {
    float sum = 0.0f;
    for (int k = 0; k < 12; ++k) {
      state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
      sum += static_cast<float>(state_ >> 40) / 16777216.0f;
    }
    return sum - 6.0f;
  }

 private:
  std::uint64_t state_ = 2006;
};

}  // namespace

int main() {
  const int steps = 400;
  const float dt = 0.01f;
  filter::Params<filter::Scalar> params;
  std::array<filter::Scalar, filter::state_size> state{};
  filter::initial_state(state.data());

  // The truth follows the deterministic part of the model, x' = 0.1 x^2 from x0 = 1.1;
  // the observation increments are dy = x dt + sqrt(dt) w.
  Noise noise;
  float x = 1.1f;
  for (int k = 0; k < steps; ++k) {
    const float t = static_cast<float>(k) * dt;
    x += 0.1f * x * x * dt;
    const std::array<float, filter::p> dy{x * dt + std::sqrt(dt) * noise.next()};
    filter::step(state.data(), t, dt, dy.data(), params);
  }
  std::printf("steps %d t %.2f x %.6g\n", steps, static_cast<double>(static_cast<float>(steps) * dt),
              static_cast<double>(x));
  for (std::size_t i = 0; i < filter::n; ++i) std::printf("m%zu %.9g\n", i + 1, static_cast<double>(state[i]));
  std::size_t k = filter::n;  // then the upper triangle of P, row by row
  for (std::size_t i = 0; i < filter::n; ++i)
    for (std::size_t j = i; j < filter::n; ++j)
      std::printf("P%zu%zu %.9g\n", i + 1, j + 1, static_cast<double>(state[k++]));
  return 0;
}
