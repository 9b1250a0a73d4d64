#include "series_codec.hpp"

#include <cstdint>
#include <stdexcept>
#include <utility>

#include "byte_codec.hpp"

namespace pfgen_runtime::monte_carlo_detail {

namespace {

constexpr char kSliceMagic[8] = {'p', 'f', 'g', 'e', 'n', 's', 'l', '1'};
constexpr char kRowsMagic[8] = {'p', 'f', 'g', 'e', 'n', 's', 'r', '1'};

// Rows `range` of a record vector (records x n, row-major), or nothing when the run has none.
void put_rows(ByteWriter& writer, const std::vector<double>& values, RecordRange range, std::size_t n) {
  if (values.empty()) {
    writer.put_range(values.data(), 0);
    return;
  }
  if (values.size() < range.last * n) throw std::logic_error("monte carlo: a run's record series is shorter than its plan");
  writer.put_range(values.data() + range.first * n, range.size() * n);
}

// A run's rows of the range where they are in the bytes, or none (nullptr); none only where the
// fold never reads them (`read`: the run reached a record time, so fold_series reads its rows there).
const char* rows_in_place(ByteReader& reader, RecordRange range, std::size_t n, bool read) {
  std::size_t size = 0;
  const char* rows = reader.get_in_place<double>(size);
  if (size == 0 ? read && range.size() > 0 : size != range.size() * n) ByteReader::fail();
  return rows;
}

// Every matrix of the series' statistics across runs, in one order for both directions.
template <class Series, class Visit>
void statistics_matrices(Series& series, Visit visit) {
  const auto statistics = [&visit](auto& s) {
    visit(s.mean);
    visit(s.q05);
    visit(s.q50);
    visit(s.q95);
  };
  statistics(series.truth_statistics);
  for (auto& filter : series.filters) {
    statistics(filter.error);
    visit(filter.reference_distance_rms);
  }
  visit(series.reference_error_rms);
}

template <class Series, class Visit>
void alive_counts(Series& series, Visit visit) {
  visit(series.truth_alive);
  for (auto& filter : series.filters) visit(filter.alive);
}

}  // namespace

std::vector<char> encode_series_slice(const std::vector<RunResult>& runs, RecordRange range, std::size_t n) {
  ByteWriter writer;
  // The exact size first: the slices of a large job are tens of megabytes, which growing by
  // doubling would copy again and again.
  const auto rows_bytes = [&](const std::vector<double>& values) {
    return sizeof(std::uint64_t) + (values.empty() ? 0 : range.size() * n * sizeof(double));
  };
  std::size_t size = sizeof(kSliceMagic) + sizeof(std::uint64_t);
  for (const RunResult& run : runs) {
    size += sizeof(run.truth_last) + sizeof(std::uint64_t) + run.filters.size() * sizeof(std::ptrdiff_t) +
            sizeof(run.reference.last) + rows_bytes(run.truth_record) + rows_bytes(run.reference.error_record);
    for (const FilterRunResult& filter : run.filters)
      size += rows_bytes(filter.error_record) + rows_bytes(filter.reference_record);
  }
  writer.out.reserve(size);
  writer.put_magic(kSliceMagic);
  writer.put(static_cast<std::uint64_t>(runs.size()));
  for (const RunResult& run : runs) {
    writer.put(run.truth_last);
    writer.put(static_cast<std::uint64_t>(run.filters.size()));
    for (const FilterRunResult& filter : run.filters) writer.put(filter.last);
    writer.put(run.reference.last);
    put_rows(writer, run.truth_record, range, n);
    for (const FilterRunResult& filter : run.filters) {
      put_rows(writer, filter.error_record, range, n);
      put_rows(writer, filter.reference_record, range, n);
    }
    put_rows(writer, run.reference.error_record, range, n);
  }
  return std::move(writer.out);
}

SliceRows read_series_slice(const std::vector<char>& bytes, std::size_t filters, RecordRange range, std::size_t n) {
  ByteReader reader(bytes);
  reader.check_magic(kSliceMagic);
  std::uint64_t count = 0;
  reader.get(count);
  // At least a run's fixed fields per run, before reserving for a corrupt count.
  if (count > bytes.size() / (4 * sizeof(std::uint64_t))) ByteReader::fail();
  SliceRows slice;
  slice.runs.reserve(static_cast<std::size_t>(count));
  slice.filters.reserve(static_cast<std::size_t>(count) * filters);  // the runs point into it
  for (std::uint64_t k = 0; k < count; ++k) {
    RunRows& run = slice.runs.emplace_back();
    reader.get(run.truth_last);
    std::uint64_t run_filters = 0;
    reader.get(run_filters);
    if (run_filters != filters) ByteReader::fail();
    run.filters = slice.filters.data() + slice.filters.size();
    slice.filters.resize(slice.filters.size() + filters);
    FilterRows* run_filter = slice.filters.data() + (slice.filters.size() - filters);
    for (std::size_t f = 0; f < filters; ++f) reader.get(run_filter[f].last);
    reader.get(run.reference_last);
    run.truth = rows_in_place(reader, range, n, run.truth_last >= 0);
    for (std::size_t f = 0; f < filters; ++f) {
      FilterRows& filter = run_filter[f];
      filter.error = rows_in_place(reader, range, n, filter.last >= 0);
      filter.reference = rows_in_place(reader, range, n, filter.last >= 0 && run.reference_last >= 0);
    }
    run.reference_error = rows_in_place(reader, range, n, run.reference_last >= 0);
  }
  if (!reader.done()) ByteReader::fail();
  return slice;
}

std::vector<char> encode_series_rows(const MonteCarloSeries& series, RecordRange range) {
  ByteWriter writer;
  writer.put_magic(kRowsMagic);
  writer.put(static_cast<std::uint64_t>(series.filters.size()));
  statistics_matrices(series, [&](const Eigen::MatrixXd& matrix) {
    if (matrix.size() == 0) return;  // the reference's, without a reference
    for (std::size_t r = range.first; r < range.last; ++r)
      for (Eigen::Index i = 0; i < matrix.cols(); ++i) writer.put(matrix(static_cast<Eigen::Index>(r), i));
  });
  alive_counts(series, [&](const std::vector<std::size_t>& alive) {
    for (std::size_t r = range.first; r < range.last; ++r) writer.put(static_cast<std::uint64_t>(alive[r]));
  });
  return std::move(writer.out);
}

void decode_series_rows(const std::vector<char>& bytes, RecordRange range, MonteCarloSeries& series) {
  ByteReader reader(bytes);
  reader.check_magic(kRowsMagic);
  std::uint64_t filters = 0;
  reader.get(filters);
  if (filters != series.filters.size()) ByteReader::fail();
  statistics_matrices(series, [&](Eigen::MatrixXd& matrix) {
    if (matrix.size() == 0) return;
    if (static_cast<std::size_t>(matrix.rows()) < range.last) ByteReader::fail();
    for (std::size_t r = range.first; r < range.last; ++r)
      for (Eigen::Index i = 0; i < matrix.cols(); ++i) reader.get(matrix(static_cast<Eigen::Index>(r), i));
  });
  alive_counts(series, [&](std::vector<std::size_t>& alive) {
    if (alive.size() < range.last) ByteReader::fail();
    for (std::size_t r = range.first; r < range.last; ++r) {
      std::uint64_t count = 0;
      reader.get(count);
      alive[r] = static_cast<std::size_t>(count);
    }
  });
  if (!reader.done()) ByteReader::fail();
}

}  // namespace pfgen_runtime::monte_carlo_detail
