// bench_record: the time of one log-likelihood evaluation over a record, what `pfgen fit` repeats
// for every point it tries: the model's filter loaded from the cached plugin, then the whole record
// run through it at the model's parameter values, the median of `--repeats` timings, each over at
// least `--min-time-ms` of repetitions.
//   bench_record MODEL DATA [--time-column C] [--filter F] [--t0 T] [--repeats R] [--min-time-ms M]
// Prints the log-likelihood (to check it against another program's) and the median time.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "record_job.hpp"

int main(int argc, char** argv) {
  using namespace pfgen::cli;
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_record MODEL DATA [--time-column C] [--filter F] [--t0 T] [--repeats R] "
                         "[--min-time-ms M]\n");
    return 2;
  }
  RecordJobOptions options;
  options.model_path = argv[1];
  options.data_path = argv[2];
  options.quiet = true;
  int repeats = 11;
  double min_time = 0.1;
  for (int k = 3; k + 1 < argc; k += 2) {
    const std::string option = argv[k], value = argv[k + 1];
    if (option == "--time-column") options.time_column = value;
    else if (option == "--filter") options.filters = {value};
    else if (option == "--t0") options.t0 = std::atof(value.c_str());
    else if (option == "--repeats") repeats = std::atoi(value.c_str());
    else if (option == "--min-time-ms") min_time = std::atof(value.c_str()) / 1000;
    else {
      std::fprintf(stderr, "bench_record: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  try {
    const RecordJob job = prepare_record_job(options);
    const Record record = read_record(options, job);
    const double t0 = prior_time(options, record.times.front(), options.data_path);
    const pfgen_runtime::RecordFilter& filter = job.filters.front();
    auto evaluate = [&] {
      pfgen_runtime::RecordRun run(filter, job.values, t0, job.run_options);
      for (std::size_t row = 0; row < record.times.size(); ++row)
        run.advance(record.times[row], record.values.data() + row * record.p);
      return run.log_likelihood();
    };
    const double value = evaluate();
    std::vector<double> seconds;
    using Clock = std::chrono::steady_clock;
    for (int r = 0; r < repeats; ++r) {
      std::size_t count = 0;
      const auto start = Clock::now();
      double elapsed = 0;
      double sink = 0;
      do {
        sink += evaluate();
        ++count;
        elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      } while (elapsed < min_time);
      if (sink == 0.12345) std::puts("");  // keeps the evaluations
      seconds.push_back(elapsed / static_cast<double>(count));
    }
    std::nth_element(seconds.begin(), seconds.begin() + repeats / 2, seconds.end());
    std::printf("filter %s, %zu rows: log-likelihood %.9f, one evaluation %.3g s (median of %d)\n",
                filter.name.c_str(), record.times.size(), value, seconds[static_cast<std::size_t>(repeats / 2)], repeats);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_record: %s\n", e.what());
    return 1;
  }
  return 0;
}
