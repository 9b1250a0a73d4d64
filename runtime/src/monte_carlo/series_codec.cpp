#include "series_codec.hpp"

#include <cstdint>
#include <stdexcept>
#include <utility>

#include "byte_codec.hpp"

namespace pfgen_runtime::monte_carlo_detail {

namespace {

constexpr char kSliceMagic[8] = {'p', 'f', 'g', 'e', 'n', 's', 'l', '2'};
constexpr char kRowsMagic[8] = {'p', 'f', 'g', 'e', 'n', 's', 'r', '2'};

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
    visit(filter.error_rms);
    visit(filter.nees);
  }
  visit(series.reference_error_rms);
}

template <class Series, class Visit>
void alive_counts(Series& series, Visit visit) {
  visit(series.truth_alive);
  for (auto& filter : series.filters) {
    visit(filter.alive);
    visit(filter.nees_runs);
  }
}

}  // namespace

SeriesSlice series_slice(const std::vector<RunResult>& runs, RecordRange range, std::size_t n) {
  // The fixed fields and every rows' length go into `heads`; rows, where a run has them, follow
  // the head bytes up to `head_end` as a piece of their own.
  struct Rows {
    std::size_t head_end = 0;
    const double* values = nullptr;
    std::size_t count = 0;
  };
  ByteWriter heads;
  std::vector<Rows> rows;
  const std::size_t filters = runs.empty() ? 0 : runs.front().filters.size();
  // A run's fields: truth_last, the filter count, each filter's last, the reference's last; then a
  // length for the truth's rows, each filter's three and the reference's.
  heads.out.reserve(sizeof(kSliceMagic) + sizeof(std::uint64_t) +
                    runs.size() * (5 + 4 * filters) * sizeof(std::uint64_t));
  rows.reserve(runs.size() * (2 + 3 * filters));
  // Rows `range` of a record vector (records x width, row-major), or nothing when the run has none.
  const auto put_rows = [&](const std::vector<double>& values, std::size_t width) {
    if (values.empty()) {
      heads.put(std::uint64_t{0});
      return;
    }
    if (values.size() < range.last * width)
      throw std::logic_error("monte carlo: a run's record series is shorter than its plan");
    heads.put(static_cast<std::uint64_t>(range.size() * width));
    rows.push_back({heads.out.size(), values.data() + range.first * width, range.size() * width});
  };
  heads.put_magic(kSliceMagic);
  heads.put(static_cast<std::uint64_t>(runs.size()));
  for (const RunResult& run : runs) {
    heads.put(run.truth_last);
    heads.put(static_cast<std::uint64_t>(run.filters.size()));
    for (const FilterRunResult& filter : run.filters) heads.put(filter.last);
    heads.put(run.reference.last);
    put_rows(run.truth_record, n);
    for (const FilterRunResult& filter : run.filters) {
      put_rows(filter.error_record, n);
      put_rows(filter.reference_record, n);
      put_rows(filter.nees_record, 1);
    }
    put_rows(run.reference.error_record, n);
  }
  SeriesSlice slice;
  slice.heads = std::move(heads.out);  // from here on its bytes stay where they are
  std::size_t from = 0;
  for (const Rows& part : rows) {
    slice.pieces.push_back({slice.heads.data() + from, part.head_end - from});
    if (part.count > 0) slice.pieces.push_back({reinterpret_cast<const char*>(part.values), part.count * sizeof(double)});
    from = part.head_end;
  }
  if (from < slice.heads.size()) slice.pieces.push_back({slice.heads.data() + from, slice.heads.size() - from});
  return slice;
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
      filter.nees = rows_in_place(reader, range, 1, filter.last >= 0);
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
