#include "pfgen_runtime/simulation_plugin.hpp"

#include <dlfcn.h>

#include <cmath>
#include <cstdio>

#include "pfgen_runtime/guards.hpp"

namespace pfgen_runtime {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void require(bool condition, const std::string& path, const std::string& what) {
  if (!condition) throw PluginLoadError("simulation plugin " + path + " is inconsistent: " + what);
}

// Everything the runtime relies on, checked once here rather than trusted at every call.
void check_table(const pfgen_plugin& t, const std::string& path) {
  require(t.n >= 1 && t.p >= 1 && t.r >= 1, path, "n, p and r must be at least 1");
  require(t.model_name && t.pfgen_version, path, "the model name or pfgen version is missing");
  require(t.drift && (t.observation_is_sampled ? t.sampled_observation != nullptr : t.observation != nullptr), path,
          "the drift or the observation is missing");
  require((t.q == 0) == (t.diffusion_is_zero != 0), path, "q must be 0 exactly when the diffusion is zero");
  if (!t.diffusion_is_zero) {
    if (t.diffusion_is_covariance)
      require(t.diffusion_covariance && t.q == t.n, path, "a diffusion given as G needs G and q = n");
    else
      require(t.diffusion != nullptr, path, "the diffusion g is missing");
  }
  require(t.filter_count == 0 || t.filters, path, "the filter table is missing");
  if (t.observation_is_sampled) {
    require(t.period > 0 && t.filter_count == 0, path, "a sampled observation needs a period > 0 and sampled filters");
    require(t.sampled_filter_count == 0 || t.sampled_filters, path, "the sampled filter table is missing");
    for (std::size_t k = 0; k < t.sampled_filter_count; ++k) {
      const pfgen_plugin_sampled_filter& f = t.sampled_filters[k];
      require(f.name && f.initial_state && f.predict && f.update && f.predict_at && f.update_at && f.innovation &&
                  f.substeps >= 1,
              path,
              "sampled filter " + std::to_string(k) + " lacks a name, function or sub-steps");
      require(f.n == t.n && f.p == t.p && f.state_size == filter_state_size(t.n), path,
              "filter " + std::string(f.name) + " has other dimensions than the model");
      require(f.extra_state_size == 0 || (f.margin_count > 0 && f.realisability_margins && f.margin_names), path,
              "sampled filter " + std::string(f.name) + " carries extra state without its realisability margins");
    }
  } else {
    require(t.sampled_filter_count == 0, path, "sampled filters need a sampled observation");
  }
  require(std::isfinite(t.delay) && t.delay >= 0 && std::isfinite(t.delay_dt) && t.delay_dt >= 0, path,
          "the observation delay and its grid step must be finite and >= 0");
  if (t.delay > 0) {
    require(!t.observation_is_sampled, path, "a delay needs continuous observations");
    require(t.delay_dt > 0 && t.delay_steps >= 1 &&
                std::abs(t.delay - static_cast<double>(t.delay_steps) * t.delay_dt) <= 1e-9 * t.delay,
            path, "the delay must be delay_steps grid steps delay_dt");
  } else {
    require(t.delay_steps == 0, path, "delay_steps must be 0 without a delay");
  }
  require(!t.observation_rate || t.delay == 0, path, "a nonlinear observation function cannot have a delay");
  require(t.drift_batch && (t.diffusion_batch != nullptr) == (t.diffusion != nullptr) &&
              (t.observation_rate_batch != nullptr) == (t.observation_rate != nullptr),
          path, "a batched function is missing, or present without its one-state function");
  for (std::size_t k = 0; k < t.filter_count; ++k) {
    const pfgen_plugin_filter& f = t.filters[k];
    require(f.name && f.initial_state && f.step, path, "filter " + std::to_string(k) + " lacks a name or function");
    require(f.n == t.n && f.p == t.p && f.state_size == filter_state_size(t.n), path,
            "filter " + std::string(f.name) + " has other dimensions than the model");
    // Extra state on any grid only for a moment filter (its moments above P), which has margins.
    require(std::isfinite(f.fixed_dt) && f.fixed_dt >= 0 &&
                (f.extra_state_size == 0 || f.fixed_dt > 0 || f.realisability_margins != nullptr),
            path, "filter " + std::string(f.name) + " has extra state without a fixed grid step, or a bad one");
    require((f.realisability_margins != nullptr) == (f.margin_count > 0) &&
                (f.margin_count == 0 || f.margin_names != nullptr),
            path, "filter " + std::string(f.name) + " has realisability margins without their count or names");
    for (std::size_t m = 0; m < f.margin_count; ++m)
      require(f.margin_names[m] != nullptr, path, "filter " + std::string(f.name) + " has a margin without a name");
    require((f.step_lanes != nullptr) == (f.lanes > 0) && (f.step_lanes == nullptr || f.extra_state_size == 0) &&
                f.lanes <= 64,
            path, "filter " + std::string(f.name) + " has step_lanes without 1 to 64 lanes, or with extra state");
    require((f.step_at != nullptr) == (f.predicted_observation != nullptr), path,
            "filter " + std::string(f.name) + " has only one of step_at and predicted_observation");
  }
  require(t.parameter_count == 0 || (t.parameter_names && t.parameter_defaults), path,
          "the parameters' names or defaults are missing");
  for (std::size_t k = 0; k < t.parameter_count; ++k)
    require(t.parameter_names[k] != nullptr, path, "parameter " + std::to_string(k) + " has no name");
  require(t.observation_noise == nullptr || !t.observation_is_sampled, path,
          "observation_noise is only for continuous observations");
}

// A moment filter's margins as the runtime checks them (empty for the other filters), keeping `library` loaded;
// a continuous or a sampled filter's table entry.
template <typename Entry>
RealisabilityCheck realisability_check(const Entry& f, const std::shared_ptr<void>& library) {
  RealisabilityCheck check;
  if (!f.realisability_margins) return check;
  check.margins = [library, margins = f.realisability_margins](const double* state, double* out) { margins(state, out); };
  check.names.assign(f.margin_names, f.margin_names + f.margin_count);
  check.n = f.n;
  return check;
}

}  // namespace

SimulationPlugin::SimulationPlugin(const std::string& path) : path_(path) {
  // RTLD_NOW: a missing symbol fails here, not in the middle of a run. RTLD_LOCAL: two plugins
  // (two models, or two versions of one) never resolve symbols against each other.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* error = ::dlerror();
    throw PluginLoadError("cannot load simulation plugin " + path + ": " + (error ? error : "unknown error"));
  }
  library_ = std::shared_ptr<void>(handle, [](void* h) { ::dlclose(h); });
  void* symbol = ::dlsym(handle, PFGEN_PLUGIN_ENTRY_NAME);
  if (!symbol)
    throw PluginLoadError(path + " is not a pfgen simulation plugin: it has no " PFGEN_PLUGIN_ENTRY_NAME "()");
  auto entry = reinterpret_cast<pfgen_plugin_entry_function>(symbol);
  const pfgen_plugin* table = entry();
  if (!table) throw PluginLoadError("simulation plugin " + path + " returned no table");
  // abi_version is the first member in every version: nothing else is read before it matches.
  if (table->abi_version != PFGEN_PLUGIN_ABI_VERSION)
    throw PluginLoadError("simulation plugin " + path + " was built for plugin ABI version " +
                          std::to_string(table->abi_version) + ", this runtime reads version " +
                          std::to_string(PFGEN_PLUGIN_ABI_VERSION) + "; delete it to have it rebuilt");
  check_table(*table, path);
  table_ = table;
}

SdeSystem SimulationPlugin::system() const {
  SdeSystem system;
  system.n = table_->n;
  system.q = table_->q;
  const std::shared_ptr<void> library = library_;
  system.drift = [library, f = table_->drift](double t, const double* x, double* out) { f(t, x, out); };
  if (table_->diffusion)
    system.diffusion = [library, g = table_->diffusion](double t, const double* x, double* out) { g(t, x, out); };
  if (table_->diffusion_jacobian)
    system.diffusion_jacobian = [library, dg = table_->diffusion_jacobian](double t, const double* x, double* out) {
      dg(t, x, out);
    };
  system.drift_batch = [library, f = table_->drift_batch](double t, std::size_t count, const double* x, double* out) {
    f(t, count, x, out);
  };
  if (table_->diffusion_batch)
    system.diffusion_batch = [library, g = table_->diffusion_batch](double t, std::size_t count, const double* x,
                                                                    double* out) { g(t, count, x, out); };
  if (!table_->diffusion_is_zero && table_->diffusion_is_covariance)
    system.diffusion = diffusion_from_covariance(
        table_->n, [library, G = table_->diffusion_covariance](double t, const double* x, double* out) { G(t, x, out); });
  return system;
}

Observation SimulationPlugin::observation() const {
  const std::size_t n = table_->n, p = table_->p, r = table_->r;
  const std::shared_ptr<void> library = library_;
  const bool sampled = table_->observation_is_sampled != 0;
  // The coefficients (A0, A, B, or a sample's C0, C, Uv): row-major in the ABI, column-major in
  // Eigen, copied through row-major buffers.
  auto coefficients = [library, fill = sampled ? table_->sampled_observation : table_->observation,
                       A0_rows = Eigen::VectorXd(p), A_rows = RowMajor(p, n),
                       B_rows = RowMajor(p, r)](double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A,
                                                Eigen::MatrixXd& B) mutable {
    fill(t, A0_rows.data(), A_rows.data(), B_rows.data());
    A0 = A0_rows;
    A = A_rows;
    B = B_rows;
  };
  Eigen::VectorXd A0(p);
  Eigen::MatrixXd A(p, n), B(p, r);
  const bool constant = table_->observation_is_constant != 0;
  if (constant) coefficients(0.0, A0, A, B);
  // The rate: the plugin's function, or A0 + A x.
  std::unique_ptr<ObservationRate> rate;
  if (table_->observation_rate)
    rate = std::make_unique<FunctionRate>(
        p, n, [library, h = table_->observation_rate](double t, const double* x, double* out) { h(t, x, out); },
        [library, h = table_->observation_rate_batch](double t, std::size_t count, const double* x, double* out) {
          h(t, count, x, out);
        });
  else if (constant)
    rate = std::make_unique<AffineRate>(A0, A);
  else
    rate = std::make_unique<AffineRate>(p, n, [coefficients, B](double t, Eigen::VectorXd& a0, Eigen::MatrixXd& a) mutable {
      coefficients(t, a0, a, B);
    });
  // The noise factor, from the same coefficients.
  ObservationNoise noise = constant ? ObservationNoise(B)
                                    : ObservationNoise(p, r, [coefficients, A0, A](double t, Eigen::MatrixXd& b) mutable {
                                        coefficients(t, A0, A, b);
                                      });
  // The timing.
  if (sampled) return Observation::sampled(std::move(rate), std::move(noise), table_->period);
  return Observation::continuous(std::move(rate), std::move(noise), table_->delay);
}

void SimulationPlugin::check_grid_step(double dt) const {
  // The same tolerance as the model's rule for h / dt (simulation_rules.cpp).
  auto differs = [dt](double fixed) { return fixed > 0 && std::abs(dt - fixed) > 1e-9 * fixed; };
  char text[160];
  for (std::size_t k = 0; k < table_->filter_count; ++k)
    if (differs(table_->filters[k].fixed_dt)) {
      std::snprintf(text, sizeof text, " was generated for the grid step dt = %.17g, not %.17g",
                    table_->filters[k].fixed_dt, dt);
      throw PluginLoadError("simulation plugin " + path_ + ": filter '" + table_->filters[k].name + "'" + text +
                            "; generate the plugin for this dt");
    }
  if (table_->delay > 0 && differs(table_->delay_dt)) {
    std::snprintf(text, sizeof text, ": the observation delay h = %.17g was set for dt = %.17g, not %.17g",
                  table_->delay, table_->delay_dt, dt);
    throw PluginLoadError("simulation plugin " + path_ + text + "; generate the plugin for this dt");
  }
}

Eigen::VectorXd SimulationPlugin::truth_initial_state() const {
  if (!table_->truth_initial_state)
    throw PluginLoadError("model " + model_name() + " gives no initial.x0 for the truth");
  Eigen::VectorXd x0(table_->n);
  table_->truth_initial_state(x0.data());
  return x0;
}

std::vector<std::string> SimulationPlugin::parameter_names() const {
  return {table_->parameter_names, table_->parameter_names + table_->parameter_count};
}

std::vector<double> SimulationPlugin::parameter_defaults() const {
  return {table_->parameter_defaults, table_->parameter_defaults + table_->parameter_count};
}

std::vector<RecordFilter> SimulationPlugin::record_filters() const {
  // What every record filter has, continuous or sampled.
  auto record_filter = [&](const char* name, std::size_t n, std::size_t p) {
    RecordFilter filter;
    filter.library = library_;
    filter.name = name;
    filter.n = n;
    filter.p = p;
    filter.r = table_->r;
    return filter;
  };
  std::vector<RecordFilter> out;
  for (std::size_t k = 0; k < table_->filter_count; ++k) {
    const pfgen_plugin_filter& f = table_->filters[k];
    if (!f.step_at || !table_->observation_noise) continue;  // a plugin written without them
    RecordFilter filter = record_filter(f.name, f.n, f.p);
    filter.initial_state = f.initial_state;
    if (f.fixed_dt > 0)
      filter.timing = std::make_shared<RecordFixedIncrements>(f.step_at, f.predicted_observation,
                                                              table_->observation_noise, f.fixed_dt, f.extra_state_size);
    else
      filter.timing = std::make_shared<RecordIncrements>(f.step_at, f.predicted_observation, table_->observation_noise,
                                                         f.extra_state_size);
    filter.realisability = realisability_check(f, library_);
    out.push_back(std::move(filter));
  }
  for (std::size_t k = 0; k < table_->sampled_filter_count; ++k) {
    const pfgen_plugin_sampled_filter& f = table_->sampled_filters[k];
    RecordFilter filter = record_filter(f.name, f.n, f.p);
    filter.initial_state = f.initial_state;
    filter.timing = std::make_shared<RecordSamples>(f.substeps, table_->period, f.predict_at, f.update_at, f.innovation,
                                                    f.extra_state_size);
    filter.realisability = realisability_check(f, library_);
    out.push_back(std::move(filter));
  }
  return out;
}

std::vector<FilterModel> SimulationPlugin::filters() const {
  // Each table entry's timing, built once here: a continuous filter's grid steps (with its lanes
  // form), a delayed one's fixed step, a sampled one's predictions and update. Every function keeps
  // the library loaded.
  std::vector<FilterModel> out;
  const std::shared_ptr<void> library = library_;
  for (std::size_t k = 0; k < table_->filter_count; ++k) {
    const pfgen_plugin_filter& f = table_->filters[k];
    FilterStepFunction step = [library, step = f.step](double* state, double t, double dt, const double* dy) {
      step(state, t, dt, dy);
    };
    std::unique_ptr<FilterTiming> timing;
    if (f.fixed_dt > 0) {
      timing = std::make_unique<FixedSteps>(std::move(step), f.fixed_dt, f.extra_state_size);
    } else {
      FilterStepFunction step_lanes;
      if (f.step_lanes)
        step_lanes = [library, step = f.step_lanes](double* state, double t, double dt, const double* dy) {
          step(state, t, dt, dy);
        };
      timing = std::make_unique<GridSteps>(std::move(step), std::move(step_lanes), f.lanes, f.extra_state_size);
    }
    out.emplace_back(f.name, f.n, f.p, [library, init = f.initial_state](double* state) { init(state); },
                     std::move(timing));
    out.back().realisability = realisability_check(f, library);
  }
  for (std::size_t k = 0; k < table_->sampled_filter_count; ++k) {
    const pfgen_plugin_sampled_filter& f = table_->sampled_filters[k];
    out.emplace_back(
        f.name, f.n, f.p, [library, init = f.initial_state](double* state) { init(state); },
        std::make_unique<SampledSteps>(
            f.substeps, [library, predict = f.predict](double* state, double t, double dt) { predict(state, t, dt); },
            [library, update = f.update](double* state, double t, const double* y) { return update(state, t, y) != 0; },
            f.extra_state_size));
    out.back().realisability = realisability_check(f, library);
  }
  return out;
}

}  // namespace pfgen_runtime
