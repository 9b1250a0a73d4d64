#include "run_codec.hpp"

#include <cstdint>
#include <type_traits>
#include <utility>

#include "byte_codec.hpp"

namespace pfgen_runtime::monte_carlo_detail {

namespace {

// A new field of RunResult or FilterRunResult must be written and read below, or processes'
// runs would lose it on the way: the sizes are checked where they are known, to make that loud.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(RunResult) == 224, "RunResult changed: encode the new field in run_codec.cpp");
static_assert(sizeof(FilterRunResult) == 328, "FilterRunResult changed: encode the new field in run_codec.cpp");
#endif

constexpr char kMagic[8] = {'p', 'f', 'g', 'e', 'n', 'r', 'u', '3'};

// One function per type for both directions, so that what is written is what is read: Run is
// const when encoding.
template <class IO, class Run>
void filter_fields(IO& io, Run& f) {
  io.put_or_get(f.last);
  io.put_or_get(f.diverged);
  io.put_or_get(f.psd_lost);
  io.put_or_get(f.too_stiff);
  io.put_or_get(f.undefined);
  io.put_or_get(f.unrealisable);
  io.put_or_get(f.divergence_t);
  io.put_or_get(f.psd_t);
  io.put_or_get(f.mean_square);
  io.put_or_get(f.report_error);
  io.put_or_get(f.peak);
  io.put_or_get(f.refined_steps);
  io.put_or_get(f.error_record);
  io.put_or_get(f.m_record);
  io.put_or_get(f.P_record);
  io.put_or_get(f.sample_sums);
  io.put_or_get(f.samples);
  io.put_or_get(f.update_failed);
  io.put_or_get(f.integral);
  io.put_or_get(f.reference_square);
  io.put_or_get(f.reference_record);
  io.put_or_get(f.nees_record);
  io.put_or_get(f.nees);
}

template <class IO, class Run>
void run_fields(IO& io, Run& r) {
  io.put_or_get(r.truth_last);
  io.put_or_get(r.truth_diverged);
  io.put_or_get(r.truth_covariance_indefinite);
  io.put_or_get(r.truth_divergence_t);
  io.put_or_get(r.truth_record);
  io.put_or_get(r.truth_report);
  std::uint64_t filters = r.filters.size();
  io.put_or_get(filters);
  if constexpr (!std::is_const_v<Run>) {
    if (filters != io.filters) ByteReader::fail();  // before allocating a corrupt count
    r.filters.resize(static_cast<std::size_t>(filters));
  }
  for (auto& f : r.filters) filter_fields(io, f);
  io.put_or_get(r.reference.last);
  io.put_or_get(r.reference.stopped);
  io.put_or_get(r.reference.stop_t);
  io.put_or_get(r.reference.resamplings);
  io.put_or_get(r.reference.mean_square);
  io.put_or_get(r.reference.error_record);
  io.put_or_get(r.reference.m_record);
  io.put_or_get(r.reference.spread_square);
}

struct Encode {
  template <class T>
  void put_or_get(const T& value) {
    writer.put(value);
  }
  ByteWriter writer;
};

struct Decode {
  template <class T>
  void put_or_get(T& value) {
    reader.get(value);
  }
  ByteReader reader;
  std::uint64_t filters = 0;  // every run's, as the folding process expects
};

}  // namespace

std::vector<char> encode_share(const std::vector<RunResult>& runs, const MonteCarloTiming& timing,
                               const std::vector<char>& series_rows) {
  Encode io;
  io.writer.put_magic(kMagic);
  io.put_or_get(timing.threads);
  io.put_or_get(timing.truth_seconds);
  io.put_or_get(timing.truth_cpu_seconds);
  io.put_or_get(timing.truth_steps);
  io.put_or_get(timing.filter_seconds);
  io.put_or_get(timing.filter_cpu_seconds);
  io.put_or_get(timing.filter_steps);
  io.put_or_get(timing.filter_samples);
  io.put_or_get(timing.reference_seconds);
  io.put_or_get(timing.reference_cpu_seconds);
  io.put_or_get(timing.reference_steps);
  io.put_or_get(static_cast<std::uint64_t>(runs.size()));
  for (const RunResult& run : runs) run_fields(io, run);
  io.put_or_get(series_rows);
  return std::move(io.writer.out);
}

std::vector<char> decode_share(const std::vector<char>& bytes, std::size_t filters, std::vector<RunResult>& runs,
                               MonteCarloTiming& timing) {
  Decode io{ByteReader(bytes), filters};
  io.reader.check_magic(kMagic);
  MonteCarloTiming block;
  io.put_or_get(block.threads);
  io.put_or_get(block.truth_seconds);
  io.put_or_get(block.truth_cpu_seconds);
  io.put_or_get(block.truth_steps);
  io.put_or_get(block.filter_seconds);
  io.put_or_get(block.filter_cpu_seconds);
  io.put_or_get(block.filter_steps);
  io.put_or_get(block.filter_samples);
  io.put_or_get(block.reference_seconds);
  io.put_or_get(block.reference_cpu_seconds);
  io.put_or_get(block.reference_steps);
  if (block.filter_seconds.size() != filters || block.filter_cpu_seconds.size() != filters ||
      block.filter_steps.size() != filters || (block.filter_samples.size() != filters && !block.filter_samples.empty()))
    ByteReader::fail();
  std::uint64_t count = 0;
  io.put_or_get(count);
  for (std::uint64_t k = 0; k < count; ++k) {
    RunResult run;
    run_fields(io, run);  // refuses a run of another number of filters
    runs.push_back(std::move(run));
  }
  std::vector<char> series_rows;
  io.put_or_get(series_rows);
  if (!io.reader.done()) ByteReader::fail();

  timing.threads += block.threads;
  timing.truth_seconds += block.truth_seconds;
  timing.truth_cpu_seconds += block.truth_cpu_seconds;
  timing.truth_steps += block.truth_steps;
  timing.reference_seconds += block.reference_seconds;
  timing.reference_cpu_seconds += block.reference_cpu_seconds;
  timing.reference_steps += block.reference_steps;
  for (std::size_t f = 0; f < filters; ++f) {
    timing.filter_seconds[f] += block.filter_seconds[f];
    timing.filter_cpu_seconds[f] += block.filter_cpu_seconds[f];
    timing.filter_steps[f] += block.filter_steps[f];
    if (!block.filter_samples.empty() && f < timing.filter_samples.size())
      timing.filter_samples[f] += block.filter_samples[f];
  }
  return series_rows;
}

}  // namespace pfgen_runtime::monte_carlo_detail
