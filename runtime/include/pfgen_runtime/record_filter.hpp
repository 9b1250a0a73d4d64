#pragma once
// A compiled filter as recorded data meets it: every function takes the model's parameter values
// in the call (the plugin's parameters, in the model's order), so one plugin serves a likelihood
// at any parameters. From SimulationPlugin::record_filters(); it holds the loaded library.
#include <cstddef>
#include <memory>
#include <string>

#include "pfgen_runtime/guards.hpp"

namespace pfgen_runtime {

struct RecordFilter {
  std::shared_ptr<void> library;  // keeps the plugin loaded while the filter lives
  std::string name;
  std::size_t n = 0;  // states
  std::size_t p = 0;  // observations (rows of A or C)
  std::size_t r = 0;  // observation noise columns (of B, or of Uv)
  // Sampled filters: prediction sub-steps per model period, and the period; 0 for continuous.
  std::size_t substeps = 0;
  double period = 0;
  // A delayed filter: the entries after m and P (x* and the history of its last h / fixed_dt grid
  // values), and the only step it takes, on its own grid tau_k = k fixed_dt from the prior; 0 for
  // others. step and predicted_observation then read the whole state and a time of that grid.
  std::size_t extra_state_size = 0;
  double fixed_dt = 0;
  void (*initial_state)(double* state) = nullptr;  // from the model's m0, P0
  // Continuous observations dy = h dt + B dW2: one step over [t, t + dt] with the increment dy,
  // the predicted rate h of a state, and B at t (p x r, row-major).
  void (*step)(double* state, const double* values, double t, double dt, const double* dy) = nullptr;
  void (*predicted_observation)(const double* state, const double* values, double t, double* h) = nullptr;
  void (*observation_noise)(const double* values, double t, double* B) = nullptr;
  // Sampled observations: one prediction sub-step, the update with a sample y at t (0 when S is
  // not positive definite), and the predicted sample yhat with its covariance S (p x p) at t.
  void (*predict)(double* state, const double* values, double t, double dt) = nullptr;
  int (*update)(double* state, const double* values, double t, const double* y) = nullptr;
  void (*innovation)(const double* state, const double* values, double t, double* yhat, double* S) = nullptr;

  bool sampled() const { return substeps > 0; }
  std::size_t state_size() const { return filter_state_size(n); }  // m and P
  std::size_t full_state_size() const { return state_size() + extra_state_size; }
};

}  // namespace pfgen_runtime
