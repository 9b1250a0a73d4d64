#pragma once
// What the series fold reads (fold_series): of every run, in run order, at the record times of a
// range, how far its truth, filters and reference got and where their rows start. The rows stay
// where they are, in a run's own record vectors or in the bytes another process sent them in
// (series_codec), and are read with memcpy, so bytes need not be aligned for double. (A shared
// job's processes used to copy every run's rows into new record vectors before folding: 2000
// satellite runs on 2 processes, 38 ms and 20 MB of new memory on each, the largest share of what
// the exchange cost.)
#include <cstddef>
#include <cstring>
#include <vector>

#include "plan.hpp"
#include "run_result.hpp"

namespace pfgen_runtime::monte_carlo_detail {

struct FilterRows {
  std::ptrdiff_t last = -1;
  const char* error = nullptr;      // error_record's rows; nullptr: the run has none
  const char* reference = nullptr;  // reference_record's rows; nullptr: none
  const char* nees = nullptr;       // nees_record's rows (one value a record); nullptr: none
};

struct RunRows {
  std::ptrdiff_t truth_last = -1, reference_last = -1;
  const char* truth = nullptr;            // truth_record's rows; nullptr: none
  const char* reference_error = nullptr;  // the reference's error_record rows; nullptr: none
  const FilterRows* filters = nullptr;    // the run's filters, held by its SliceRows
};

// One block of runs' rows: a process's own runs, or the runs another process sent. The runs'
// filters point into `filters`, which moving a SliceRows keeps where it is (not copying it).
struct SliceRows {
  SliceRows() = default;
  SliceRows(SliceRows&&) = default;
  SliceRows& operator=(SliceRows&&) = default;
  SliceRows(const SliceRows&) = delete;
  SliceRows& operator=(const SliceRows&) = delete;

  std::vector<RunRows> runs;
  std::vector<FilterRows> filters;  // runs.size() x the job's filters
};

// Entry `at` (record r, state i at (r - range.first) * n + i) of rows.
inline double row_value(const char* rows, std::size_t at) {
  double value;
  std::memcpy(&value, rows + at * sizeof(double), sizeof value);
  return value;
}

// The rows `range` of runs' record vectors, where they are (the runs must outlive the result).
// std::logic_error for a record vector shorter than the plan.
SliceRows rows_of(const std::vector<RunResult>& runs, RecordRange range, std::size_t n, std::size_t filters);

}  // namespace pfgen_runtime::monte_carlo_detail
