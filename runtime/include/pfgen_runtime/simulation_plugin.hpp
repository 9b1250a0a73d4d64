#pragma once
// A compiled simulation plugin (plugin_abi.h) loaded with dlopen: a model's truth, observation
// and filters as the runtime's own types. Every SdeSystem, Observation and FilterModel
// it returns holds a reference to the loaded library, so they stay valid after the
// SimulationPlugin itself is gone; the library is closed with the last of them.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/plugin_abi.h"
#include "pfgen_runtime/record_filter.hpp"
#include "pfgen_runtime/sde_system.hpp"
#include "pfgen_runtime/simulation.hpp"
#include "pfgen_support/error.hpp"

namespace pfgen_runtime {

class PluginLoadError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

class SimulationPlugin {
 public:
  // dlopen(path, RTLD_NOW | RTLD_LOCAL), then pfgen_plugin_entry() and checks of its table.
  // Throws PluginLoadError: the file cannot be loaded, has no entry point, was written for
  // another PFGEN_PLUGIN_ABI_VERSION, or its table is inconsistent.
  explicit SimulationPlugin(const std::string& path);
  // Move-only: a moved-from plugin has no table (only destruction and assignment are valid).
  SimulationPlugin(SimulationPlugin&& other) noexcept
      : path_(std::move(other.path_)), library_(std::move(other.library_)),
        table_(std::exchange(other.table_, nullptr)) {}
  SimulationPlugin& operator=(SimulationPlugin&& other) noexcept {
    path_ = std::move(other.path_);
    library_ = std::move(other.library_);
    table_ = std::exchange(other.table_, nullptr);
    return *this;
  }
  SimulationPlugin(const SimulationPlugin&) = delete;
  SimulationPlugin& operator=(const SimulationPlugin&) = delete;
  ~SimulationPlugin() = default;

  const std::string& path() const { return path_; }
  std::string model_name() const { return table_->model_name; }
  std::string pfgen_version() const { return table_->pfgen_version; }
  std::size_t n() const { return table_->n; }
  std::size_t q() const { return table_->q; }
  std::size_t p() const { return table_->p; }
  std::size_t r() const { return table_->r; }
  // g identically zero: a deterministic truth (q == 0); every truth scheme reduces to the ODE.
  bool diffusion_is_zero() const { return table_->diffusion_is_zero != 0; }
  // The Jacobian of g exists (g given, not only G): Milstein can be used.
  bool has_diffusion_jacobian() const { return table_->diffusion_jacobian != nullptr; }
  bool observation_is_constant() const { return table_->observation_is_constant != 0; }
  bool has_truth_initial_state() const { return table_->truth_initial_state != nullptr; }

  // The truth SDE. A model giving only G = g g^T gets g from diffusion_from_covariance (q = n,
  // no Jacobian).
  SdeSystem system() const;
  // The observation, built from the table's axes: its rate (the plugin's observation_rate, or
  // A0 + A x from its coefficients), its noise factor (B, or a sample's Uv: r() columns) and its
  // timing (samples every period, or continuous increments with the delay h, 0 but for delayed
  // observations). Coefficients that do not depend on t are evaluated once.
  Observation observation() const;
  // PluginLoadError unless every filter accepts the grid step dt: a delayed filter (fixed_dt)
  // runs only on the grid it was generated for, and so does the delay's step count.
  void check_grid_step(double dt) const;
  // The model's initial.x0; PluginLoadError (std::runtime_error) when the model gives none.
  Eigen::VectorXd truth_initial_state() const;
  // The filters in the plugin's order, at the model's default parameters, each with its timing
  // (filter_timing.hpp): GridSteps for a continuous filter (with its lanes form), FixedSteps for a
  // delayed one (its extra state and grid step), SampledSteps for a sampled model's filters.
  std::vector<FilterModel> filters() const;

  // The model's parameters in its order, and the defaults filters() and the truth use.
  std::vector<std::string> parameter_names() const;
  std::vector<double> parameter_defaults() const;
  // The filters that can run over recorded data at any parameter values, in the plugin's order
  // (a delayed one with its extra state and fixed grid step).
  std::vector<RecordFilter> record_filters() const;

  // The raw table, valid while this object (or anything it returned) lives.
  const pfgen_plugin& table() const { return *table_; }

 private:
  std::string path_;
  std::shared_ptr<void> library_;  // the dlopen handle; dlclose when the last user goes
  const pfgen_plugin* table_ = nullptr;
};

}  // namespace pfgen_runtime
