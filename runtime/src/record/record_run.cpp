#include "pfgen_runtime/record_run.hpp"

#include <sstream>
#include <stdexcept>

namespace pfgen_runtime {

RecordRun::RecordRun(const RecordFilter& filter, std::vector<double> values, double t0, const RecordRunOptions& options,
                     const std::vector<double>& initial)
    : filter_(filter),
      progress_(filter.n, filter.p, filter.r, filter.full_state_size(), std::move(values), t0, options) {
  if (options.substeps == 0) throw std::invalid_argument("substeps must be at least 1");
  std::vector<double>& state = progress_.state;
  if (initial.empty())
    filter.initial_state(state.data());
  else if (filter.timing->keeps_history())
    throw std::invalid_argument("the filter '" + filter.name + "' keeps a history and starts from the model's m0 and P0");
  else if (initial.size() == state.size())
    state = initial;
  else
    throw std::invalid_argument("the initial state has " + std::to_string(initial.size()) + " entries, the filter " +
                                std::to_string(state.size()));
}

bool RecordRun::advance(double t, const double* observation) {
  if (failed()) return false;
  const bool first = !begun_;
  begun_ = true;
  if (!filter_.timing->absorb(progress_, t, observation, first)) return false;
  return realisable();
}

// A moment filter's state must stay in the realisable set: a margin not positive (NaN included) fails the run
// there, as it stops a simulated one.
bool RecordRun::realisable() {
  const auto event = check_realisability(filter_.realisability, progress_.t, progress_.state.data(), margins_);
  if (!event) return true;
  std::ostringstream why;
  why.precision(10);
  why << "its moments left the realisable set at t = " << event->t << " (" << event->what << " is " << event->value << ")"
      << filter_.timing->step_hint(progress_);
  return progress_.fail(why.str());
}

}  // namespace pfgen_runtime
