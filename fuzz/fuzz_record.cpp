// libFuzzer target (docs/development.md, "Fuzzing"): record text -> RecordReader (time column `t`,
// every other column an observation) -> every row through RecordRun, with a one-state Kalman
// filter written here, as sampled samples and as continuous increments. Refused input is expected
// (RecordError, std::invalid_argument for rows a filter cannot take); a finding is a crash, a
// sanitizer report, a run beyond -timeout or memory beyond -rss_limit_mb. scripts/fuzz.sh record
// builds and runs it.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "pfgen_runtime/record_reader.hpp"
#include "pfgen_runtime/record_run.hpp"

namespace {

// dx = -x dt + dW1, observed as y = x + v (sampled) or dy = x dt + dW2 (continuous); the state is
// [m, P], p entries of the row all read the same x.
std::size_t columns = 1;

void initial(double* s) { s[0] = 0, s[1] = 1; }
void predict(double* s, const double*, double, double dt) { s[0] -= s[0] * dt, s[1] += (1 - 2 * s[1]) * dt; }
int update(double* s, const double*, double, const double* y) {
  for (std::size_t i = 0; i < columns; ++i) {
    const double S = s[1] + 1, K = s[1] / S;
    s[0] += K * (y[i] - s[0]);
    s[1] -= K * S * K;
  }
  return 1;
}
void innovation(const double* s, const double*, double, double* yhat, double* S) {
  for (std::size_t i = 0; i < columns; ++i) {
    yhat[i] = s[0];
    for (std::size_t j = 0; j < columns; ++j) S[i * columns + j] = s[1] + (i == j ? 1 : 0);
  }
}
void step(double* s, const double*, double, double dt, const double* dy) {
  const double K = s[1];
  s[0] += -s[0] * dt + K * (dy[0] - s[0] * dt);
  s[1] += (1 - 2 * s[1] - K * K) * dt;
}
void rate(const double* s, const double*, double, double* h) {
  for (std::size_t i = 0; i < columns; ++i) h[i] = s[0];
}
void noise(const double*, double, double* B) {
  for (std::size_t i = 0; i < columns * columns; ++i) B[i] = i % (columns + 1) == 0 ? 1 : 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/dev/shm/pfgen-fuzz-record-" + std::to_string(getpid()) + ".csv";
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  for (const bool sampled : {true, false}) {
    try {
      pfgen_runtime::RecordReader reader(path, "t", {}, 0);
      columns = reader.observation_columns().size();
      if (columns == 0 || columns > 8) return 0;
      pfgen_runtime::RecordFilter filter;
      filter.name = "fuzz";
      filter.n = 1;
      filter.p = filter.r = columns;
      filter.initial_state = &initial;
      if (sampled)
        filter.timing = std::make_shared<pfgen_runtime::RecordSamples>(3, 0.5, &predict, &update, &innovation);
      else
        filter.timing = std::make_shared<pfgen_runtime::RecordIncrements>(&step, &rate, &noise);
      std::vector<double> y(columns);
      double t = 0;
      std::vector<pfgen_runtime::RecordRun> runs;
      while (reader.next(t, y.data())) {
        if (runs.empty()) {
          runs.emplace_back(filter, std::vector<double>{}, t - 1, pfgen_runtime::RecordRunOptions{});
        }
        if (!runs.front().advance(t, y.data())) break;
      }
      if (!runs.empty()) (void)runs.front().scores().summary().verdict();
    } catch (const std::exception&) {
    }
  }
  return 0;
}
