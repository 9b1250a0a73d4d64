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

// A run's rows of the range, or none; none only where the fold never reads them (`read`: the run
// reached a record time, so fold_series reads the vector there).
void get_rows(ByteReader& reader, std::vector<double>& values, RecordRange range, std::size_t n, bool read) {
  reader.get(values);
  if (values.empty() ? read && range.size() > 0 : values.size() != range.size() * n) ByteReader::fail();
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

void decode_series_slice(const std::vector<char>& bytes, std::size_t filters, RecordRange range, std::size_t n,
                         std::vector<RunResult>& runs) {
  ByteReader reader(bytes);
  reader.check_magic(kSliceMagic);
  std::uint64_t count = 0;
  reader.get(count);
  for (std::uint64_t k = 0; k < count; ++k) {
    RunResult& run = runs.emplace_back();
    reader.get(run.truth_last);
    std::uint64_t run_filters = 0;
    reader.get(run_filters);
    if (run_filters != filters) ByteReader::fail();
    run.filters.resize(filters);
    for (FilterRunResult& filter : run.filters) reader.get(filter.last);
    reader.get(run.reference.last);
    get_rows(reader, run.truth_record, range, n, run.truth_last >= 0);
    for (FilterRunResult& filter : run.filters) {
      get_rows(reader, filter.error_record, range, n, filter.last >= 0);
      get_rows(reader, filter.reference_record, range, n, filter.last >= 0 && run.reference.last >= 0);
    }
    get_rows(reader, run.reference.error_record, range, n, run.reference.last >= 0);
  }
  if (!reader.done()) ByteReader::fail();
}

void append_series_slice(const std::vector<RunResult>& runs, RecordRange range, std::size_t n,
                         std::vector<RunResult>& slice) {
  // put_rows' rows, or nothing for an empty vector.
  const auto rows = [&](const std::vector<double>& values, std::vector<double>& to) {
    if (values.empty()) return;
    if (values.size() < range.last * n) throw std::logic_error("monte carlo: a run's record series is shorter than its plan");
    const auto from = values.begin() + static_cast<std::ptrdiff_t>(range.first * n);
    to.assign(from, from + static_cast<std::ptrdiff_t>(range.size() * n));
  };
  for (const RunResult& run : runs) {
    RunResult& copy = slice.emplace_back();
    copy.truth_last = run.truth_last;
    copy.filters.resize(run.filters.size());
    for (std::size_t f = 0; f < run.filters.size(); ++f) {
      copy.filters[f].last = run.filters[f].last;
      rows(run.filters[f].error_record, copy.filters[f].error_record);
      rows(run.filters[f].reference_record, copy.filters[f].reference_record);
    }
    copy.reference.last = run.reference.last;
    rows(run.truth_record, copy.truth_record);
    rows(run.reference.error_record, copy.reference.error_record);
  }
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
