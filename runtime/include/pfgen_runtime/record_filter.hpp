#pragma once
// A compiled filter as recorded data meets it: every function takes the model's parameter values
// in the call (the plugin's parameters, in the model's order), so one plugin serves a likelihood
// at any parameters. From SimulationPlugin::record_filters(); it holds the loaded library.
#include <cstddef>
#include <memory>
#include <string>

#include "pfgen_runtime/guards.hpp"
#include "pfgen_runtime/record_timing.hpp"

namespace pfgen_runtime {

struct RecordFilter {
  std::shared_ptr<void> library;  // keeps the plugin loaded while the filter lives
  std::string name;
  std::size_t n = 0;  // states
  std::size_t p = 0;  // observations (rows of A or C)
  std::size_t r = 0;  // observation noise columns (of B, or of Uv)
  void (*initial_state)(double* state) = nullptr;  // from the model's m0, P0
  // What a row holds and how the filter goes to it (record_timing.hpp): RecordSamples,
  // RecordIncrements or a delayed filter's RecordFixedIncrements. Its functions are plain
  // pointers, so copies of the filter share it.
  std::shared_ptr<const RecordTiming> timing;
  // A moment filter's realisability margins (empty for the other filters): a run fails where one is not positive
  // (RecordRun::advance).
  RealisabilityCheck realisability;

  std::size_t state_size() const { return filter_state_size(n); }  // m and P
  std::size_t full_state_size() const { return state_size() + timing->extra_state(); }
};

}  // namespace pfgen_runtime
