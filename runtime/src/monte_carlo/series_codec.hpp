#pragma once
// The record series of a job whose runs are shared among processes (MonteCarloOptions::share).
// Folding them is most of the statistics' work, so it is shared too: each process folds the
// record times of its series_range. A run's values at those times travel to the process that
// folds them (slices, in one exchange among all processes), and the rows it folded travel to the
// process that writes the result (rows, with its share of the runs). The values of a record time
// reach its process in run order, so its statistics are bit for bit one process's.
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"
#include "plan.hpp"
#include "run_result.hpp"
#include "series_rows.hpp"

namespace pfgen_runtime::monte_carlo_detail {

// Of each run, in run order, at the record times `range`: how far the truth, every filter and the
// reference got, and their values that the series fold (truth_record, every filter's error_record
// and reference_record, the reference's error_record), as the pieces of one block. The values are
// not copied: their pieces point into the runs' record vectors, which must outlive the slice and
// stay unchanged; the rest (the fields, the rows' lengths) is in `heads`, which moving the slice
// keeps where it is.
struct SeriesSlice {
  SeriesSlice() = default;
  SeriesSlice(SeriesSlice&&) = default;
  SeriesSlice& operator=(SeriesSlice&&) = default;
  SeriesSlice(const SeriesSlice&) = delete;
  SeriesSlice& operator=(const SeriesSlice&) = delete;

  std::vector<char> heads;
  PiecedBlock pieces;
};
SeriesSlice series_slice(const std::vector<RunResult>& runs, RecordRange range, std::size_t n);

// A slice's runs' rows, where they are in its bytes (`bytes`, which must outlive the result); their rows
// start at the range's first record (record r at (r - range.first) * n). std::runtime_error for
// bytes that are not such a block. A process's own runs at its own range do not travel: rows_of
// (series_rows.hpp) gives theirs.
SliceRows read_series_slice(const std::vector<char>& bytes, std::size_t filters, RecordRange range, std::size_t n);

// The rows `range` of the series' statistics across runs (what fold_series fills).
std::vector<char> encode_series_rows(const MonteCarloSeries& series, RecordRange range);

// Writes such rows into `series`, whose matrices have the sizes start_series gave them.
// std::runtime_error for bytes that are not such rows.
void decode_series_rows(const std::vector<char>& bytes, RecordRange range, MonteCarloSeries& series);

}  // namespace pfgen_runtime::monte_carlo_detail
