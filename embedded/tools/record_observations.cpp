// Writes embedded/observations.hpp: a fixed, recorded observation sequence for the
// embedded proof (embedded/main.cpp), so that the firmware under QEMU and the host's
// double-precision run filter bit-identical inputs.
//
// For each of the two example models it simulates the true system with Euler-Maruyama
// on a fine grid (100 substeps per observation interval) from the model file's x0, and
// records the observation increments dy_k = y(t_{k+1}) - y(t_k) of
//   dy = x1 dt + dW2            (both models observe the first state, A = [1 0...], B = 1)
// over `steps` intervals of length dt. The dynamics are those of
//   examples/basin2006_quadratic.yaml   dx = 0.1 x^2 dt + 0.1 x^2 dW1
//   examples/basin_skliar_partial.yaml  dx1 = 0.1 (x1^2 + x2) dt, dx2 = 0.1 x2 dt
// written out below (this tool does not read the model files).
//
// Randomness: SplitMix64 seeded with a fixed seed per model, Marsaglia's polar method for
// normal deviates. Only IEEE double arithmetic, std::sqrt and std::log are involved, so
// the output is reproducible; scripts/embedded-check.sh regenerates the header and fails
// if it differs from the committed one.
//
// Each dy is rounded to float and printed with 9 significant digits (exact float
// round-trip), so the float firmware and the double host read the very same numbers.
//
// Samples for the sampled filter (cd-optimal) of examples/allahyani_date_example1_gamma1.yaml,
// paper 003's Example 1 with gamma = 1:
//   dx = -0.5 x dt + 6 dW + 0.1 x dS, x(0) = 1;  y_k = 10 x(k T) + v_k, T = 1, k = 1..200,
// the truth by Euler-Maruyama with 1000 substeps per period, v_k standard normal, each y_k
// rounded to float like the dy above.
//
// Increments for the delayed filter (delay-optimal) of examples/delay_linear.yaml:
//   dx = -0.5 x dt + 0.3 dW1, x(0) = 1;  dy = x(t - 0.5) dt + 0.2 dW2, x(s) = x(0) for s < 0,
// on the same grid (500 steps of dt, 100 Euler-Maruyama substeps each), appended after the samples.
//
// Build and run (from the repository root):
//   c++ -std=c++17 -O2 -o /tmp/record_observations embedded/tools/record_observations.cpp
//   /tmp/record_observations > embedded/observations.hpp
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace {

constexpr int kSteps = 500;
constexpr int kSubsteps = 100;
// The observation interval as both runs see it: the float nearest 0.01.
constexpr float kDtFloat = 0.01f;

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform on (-1, 1), 53 random bits.
  double symmetric_uniform() { return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-52 - 1.0; }
  // Standard normal deviate (Marsaglia's polar method; the second deviate is kept).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = symmetric_uniform();
      v = symmetric_uniform();
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double factor = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * factor;
    has_spare_ = true;
    return u * factor;
  }

 private:
  std::uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

struct Record {
  std::vector<float> dy;
  std::vector<double> x_final;
};

// state x (n entries); drift/diffusion advance one Euler-Maruyama substep of length h.
template <class Advance>
Record simulate(std::vector<double> x, std::uint64_t seed, Advance advance) {
  SplitMix64 rng(seed);
  const double dt = static_cast<double>(kDtFloat);
  const double h = dt / kSubsteps;
  const double sqrt_h = std::sqrt(h);
  Record record;
  for (int k = 0; k < kSteps; ++k) {
    double dy = 0.0;
    for (int s = 0; s < kSubsteps; ++s) {
      const double dw2 = sqrt_h * rng.normal();
      dy += x[0] * h + dw2;  // dy = x1 dt + dW2, with x at the start of the substep
      advance(x, h, sqrt_h, rng);
    }
    record.dy.push_back(static_cast<float>(dy));
  }
  record.x_final = x;
  return record;
}

std::string float_literal(float value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(value));
  std::string text = buffer;
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text + "f";
}

// Paper 003's Example 1 (gamma = 1) sampled every kPeriod: kSamples samples y_1..y_kSamples.
constexpr int kSamples = 200;
constexpr double kPeriod = 1.0;
constexpr int kSampleSubsteps = 1000;

Record simulate_sampled(double x, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const double h = kPeriod / kSampleSubsteps;
  const double sqrt_h = std::sqrt(h);
  Record record;
  for (int k = 1; k <= kSamples; ++k) {
    for (int s = 0; s < kSampleSubsteps; ++s) {
      const double dw = sqrt_h * rng.normal();
      const double ds = sqrt_h * rng.normal();
      x += -0.5 * x * h + 6.0 * dw + 0.1 * x * ds;
    }
    record.dy.push_back(static_cast<float>(10.0 * x + rng.normal()));
  }
  record.x_final = {x};
  return record;
}

// examples/delay_linear.yaml's truth and its delayed observation increments.
constexpr double kDelay = 0.5;

Record simulate_delayed(double x0, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const double dt = static_cast<double>(kDtFloat);
  const double h = dt / kSubsteps;
  const double sqrt_h = std::sqrt(h);
  const auto lag = static_cast<std::size_t>(std::lround(kDelay / h));  // substeps in the delay
  std::vector<double> path = {x0};                                       // x at every substep
  Record record;
  for (int k = 0; k < kSteps; ++k) {
    double dy = 0.0;
    for (int s = 0; s < kSubsteps; ++s) {
      const std::size_t now = path.size() - 1;
      const double delayed = now >= lag ? path[now - lag] : x0;  // x(t - h), x(0) before 0
      dy += delayed * h + 0.2 * sqrt_h * rng.normal();
      path.push_back(path.back() - 0.5 * path.back() * h + 0.3 * sqrt_h * rng.normal());
    }
    record.dy.push_back(static_cast<float>(dy));
  }
  record.x_final = {path.back()};
  return record;
}

void print_array(const char* name, const Record& record, const char* description, std::uint64_t seed,
                 const char* size = "steps", const char* at = "t = 500 dt") {
  std::printf("\n// %s\n// seed %llu; true state at %s:", description, static_cast<unsigned long long>(seed), at);
  for (double v : record.x_final) std::printf(" %.6g", v);
  std::printf("\ninline constexpr float %s[%s] = {", name, size);
  for (std::size_t i = 0; i < record.dy.size(); ++i) {
    std::printf("%s%s", i % 6 == 0 ? "\n    " : " ", float_literal(record.dy[i]).c_str());
    if (i + 1 < record.dy.size()) std::printf(",");
  }
  std::printf("};\n");
}

}  // namespace

int main() {
  const std::uint64_t quadratic_seed = 2006;
  const Record quadratic = simulate({1.1}, quadratic_seed, [](std::vector<double>& x, double h, double sqrt_h, SplitMix64& rng) {
    const double dw1 = sqrt_h * rng.normal();
    const double x2 = x[0] * x[0];
    x[0] += 0.1 * x2 * h + 0.1 * x2 * dw1;
  });
  const std::uint64_t partial_seed = 2009;
  const Record partial = simulate({1.1, 1.1}, partial_seed, [](std::vector<double>& x, double h, double, SplitMix64&) {
    const double x1 = x[0], x2 = x[1];
    x[0] += 0.1 * (x1 * x1 + x2) * h;
    x[1] += 0.1 * x2 * h;
  });

  std::printf(
      "// Recorded observation increments dy_k = y((k+1) dt) - y(k dt) for embedded/main.cpp, and the\n"
      "// samples y_k of its sampled filter run.\n"
      "// Generated by embedded/tools/record_observations.cpp; do not edit (see that file).\n"
      "#pragma once\n\n"
      "namespace pfgen_embedded::observations {\n\n"
      "inline constexpr int steps = %d;\n"
      "// The observation interval of both runs (float and double): the float nearest 0.01.\n"
      "inline constexpr float dt = %s;\n",
      kSteps, float_literal(kDtFloat).c_str());
  print_array("basin2006_quadratic_dy", quadratic,
              "basin2006_quadratic: dx = 0.1 x^2 dt + 0.1 x^2 dW1, x(0) = 1.1; dy = x dt + dW2", quadratic_seed);
  print_array("basin_skliar_partial_dy", partial,
              "basin_skliar_partial: dx1 = 0.1 (x1^2 + x2) dt, dx2 = 0.1 x2 dt, x(0) = (1.1, 1.1); dy = x1 dt + dW2",
              partial_seed);
  const std::uint64_t sampled_seed = 2003;
  const Record sampled = simulate_sampled(1.0, sampled_seed);
  std::printf(
      "\n// Samples y_k, k = 1..samples, of the sampled filter run (cd-optimal), taken every period.\n"
      "inline constexpr int samples = %d;\n"
      "inline constexpr float period = %s;\n",
      kSamples, float_literal(static_cast<float>(kPeriod)).c_str());
  print_array("allahyani_date_example1_gamma1_y", sampled,
              "allahyani_date_example1_gamma1: dx = -0.5 x dt + 6 dW + 0.1 x dS, x(0) = 1; y_k = 10 x(k) + v_k",
              sampled_seed, "samples", "t = 200");
  const std::uint64_t delayed_seed = 2004;
  print_array("delay_linear_dy", simulate_delayed(1.0, delayed_seed),
              "delay_linear: dx = -0.5 x dt + 0.3 dW1, x(0) = 1; dy = x(t - 0.5) dt + 0.2 dW2 (x(s) = x(0), s < 0)",
              delayed_seed);
  std::printf("\n}  // namespace pfgen_embedded::observations\n");
  return 0;
}
