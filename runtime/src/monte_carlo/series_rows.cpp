#include "series_rows.hpp"

#include <stdexcept>

namespace pfgen_runtime::monte_carlo_detail {

SliceRows rows_of(const std::vector<RunResult>& runs, RecordRange range, std::size_t n, std::size_t filters) {
  const auto rows = [&](const std::vector<double>& values, std::size_t width) -> const char* {
    if (values.empty()) return nullptr;
    if (values.size() < range.last * width)
      throw std::logic_error("monte carlo: a run's record series is shorter than its plan");
    return reinterpret_cast<const char*>(values.data() + range.first * width);
  };
  SliceRows slice;
  slice.filters.reserve(runs.size() * filters);  // the runs point into it: no reallocation
  slice.runs.reserve(runs.size());
  for (const RunResult& run : runs) {
    if (run.filters.size() != filters) throw std::logic_error("monte carlo: a run has another number of filters");
    RunRows& rows_of_run = slice.runs.emplace_back();
    rows_of_run.truth_last = run.truth_last;
    rows_of_run.reference_last = run.reference.last;
    rows_of_run.truth = rows(run.truth_record, n);
    rows_of_run.reference_error = rows(run.reference.error_record, n);
    rows_of_run.filters = slice.filters.data() + slice.filters.size();
    for (const FilterRunResult& filter : run.filters)
      slice.filters.push_back(
          {filter.last, rows(filter.error_record, n), rows(filter.reference_record, n), rows(filter.nees_record, 1)});
  }
  return slice;
}

}  // namespace pfgen_runtime::monte_carlo_detail
