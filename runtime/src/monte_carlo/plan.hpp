#pragma once
// The grid points at which a Monte Carlo run needs more than accumulating e^2: record points,
// report times, window ends. Decided once before any run, from the options alone, and then
// shared read-only by all threads, so a worker walks a sorted list of events instead of asking
// at every grid step whether something happens there.
#include <cstddef>
#include <utility>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen_runtime::monte_carlo_detail {

struct Plan {
  enum class Kind { record, report, window_close };
  struct Event {
    std::size_t index;  // grid index
    Kind kind;
    std::size_t slot;  // record, report or window number
  };
  std::size_t n = 0, p = 0;
  TimeGrid grid;
  std::vector<std::size_t> records;                            // grid indices
  std::vector<std::size_t> reports;                            // grid indices, as requested
  std::vector<std::pair<std::size_t, std::size_t>> windows;    // first, last grid index
  std::vector<Event> events;                                   // by grid index
  std::vector<std::pair<std::size_t, std::size_t>> opens;      // (first index, window), by index
};

// Record times [first, last) (indices into Plan::records).
struct RecordRange {
  std::size_t first = 0, last = 0;
  std::size_t size() const { return last - first; }
};

// The record times whose statistics process `process` of `processes` folds when runs are shared
// among processes: contiguous ranges of near-equal size, in process order, covering all records.
RecordRange series_range(std::size_t records, std::size_t process, std::size_t processes);

// The plan for n states and p observations. Report times and window ends are snapped to the
// nearest grid index; std::invalid_argument for a time outside [t0, T] (half a step of slack)
// or a window shorter than a grid step.
Plan make_plan(std::size_t n, std::size_t p, const MonteCarloOptions& options);

}  // namespace pfgen_runtime::monte_carlo_detail
