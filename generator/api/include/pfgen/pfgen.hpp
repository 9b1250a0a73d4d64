#pragma once
// pfgen's C++ API: the one header a program includes to load a polynomial model, derive its
// filters, print them as text, LaTeX or JSON, evaluate them at a point, generate their code,
// simulate them against a truth and run them over a record of observations (estimate, fit). Each call gives what the matching `pfgen` command prints, byte for
// byte, and fails with the same message (docs/guide/cpp-api.md).
//
//   #include <pfgen/pfgen.hpp>
//
//   pfgen::api::Model model = pfgen::api::Model::load("examples/basin2006_quadratic.yaml");
//   pfgen::api::Filter optimal = model.derive("optimal");
//   std::cout << optimal.text();                                   // pfgen derive
//   pfgen::api::Evaluation value = optimal.eval({0, {0.5}, {{1}}});  // pfgen eval
//   pfgen::api::CodegenOptions c;
//   c.language = "c";
//   model.codegen("generated", c);                                 // pfgen codegen --language c
//
// CMake: find_package(pfgen) and target_link_libraries(app PRIVATE pfgen::generator).
//
// Threads: GiNaC, the algebra underneath, is not thread-safe, so pfgen runs one call at a time
// (a call from a second thread waits). The objects below are handles: copies share one model or
// filter, which never changes after it is made.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen_support/error.hpp"

namespace pfgen::api {

// The one exception type pfgen throws for anything wrong with a model, an option, a point or a
// file: what() is the message; report() is the line the command prints after "pfgen: " (a model
// file's problem as "FILE:LINE:COLUMN: error: ...", anything else as "error: ..."); place() gives
// the file, line, column and field where there is one. Other exceptions are not pfgen's
// (std::bad_alloc).
using Error = pfgen_support::Error;

// pfgen's version, "0.1.0".
std::string version();

using Vector = std::vector<double>;
using Matrix = std::vector<std::vector<double>>;  // row by row

// Where Filter::eval evaluates: `pfgen eval --t --m --P --set`. Numbers are read as the decimals
// they print as (0.1 is exactly 1/10), as the command reads its options' text. parameters: the
// model's parameters given other values (the model is checked again with them). The four
// delayed-observation inputs are read by delayed filters only; empty takes the command's default.
// moments: a moment filter's (closure3, closure4) central moments above P by name, `--moment
// M3_112=0.1`; one left out takes its value under N(m, P) (0 at order 3, P_ij P_lq + P_il P_jq +
// P_iq P_jl at order 4). A name the filter does not carry is refused.
struct Point {
  double t = 0;
  Vector m;
  Matrix P;
  std::map<std::string, double> parameters;
  Vector m_delayed, x_star, x_star_delayed, phi;
  std::map<std::string, double> moments;
};

// A filter's values at a Point. json is what `pfgen eval` prints; the fields are its numbers
// (docs/guide/commands.md, "pfgen eval"), empty where the filter's observation has none.
struct Evaluation {
  std::string json;
  Vector m_drift;
  Matrix gain;
  Matrix P_drift;
  Matrix P_dt2;                  // cd-euler only
  Matrix innovation_covariance;  // sampled observations only
  Vector predicted_observation, m_delayed, phi, x_star, x_star_drift;  // delayed observations only
  // Polynomial observations and the moment filters (whatever their h): per observation r, dP's
  // n x n coefficients of dy_r - predicted_observation_r dt.
  std::vector<Matrix> P_gain;
  // The moment filters only: the central moments above P in the state's order (M3_111, M3_112, ...,
  // then M4_...), each one's drift, and its coefficients of dy_r - predicted_observation_r dt (one
  // row of p per moment): eval's "moments", "moment_drift" and "moment_gain".
  std::vector<std::string> moment_names;
  Vector moment_drift;
  Matrix moment_gain;
  // A sampled moment filter's (cd-closure3, cd-closure4) P and higher moments after an update at the point:
  // eval's "P_after_update" and "moments_after_update" (empty for the other filters).
  Matrix P_after_update;
  Vector moments_after_update;
};

// A filter's equations as expressions that Python (and SymPy's sympify, with rational=True) reads:
// the text output's spelling (numbers as its decimals, so read them as exact rationals) with `**`
// for powers. Variables as in the text output: m1..mn, P11, P12, ... (P21 is P12), the time symbol
// and the parameters by their names; a delayed filter's md1, phi1, xs1; a moment filter's central
// moments above P (M3_111, M4_1122). Deterministic, as the text is.
struct Expressions {
  std::vector<std::string> m_drift;                 // n
  std::vector<std::vector<std::string>> gain;       // n x p (n x 0 for a sampled filter)
  std::vector<std::vector<std::string>> P_drift;    // n x n, symmetric
  std::vector<std::string> predicted_observation;   // p (empty for a sampled filter)
  // A polynomial observation's (or a moment filter's) dP = P_drift dt + sum_r P_gain[r] (dy_r -
  // predicted_observation_r dt): per observation, n x n; empty for the other filters.
  std::vector<std::vector<std::vector<std::string>>> P_gain;
  // A moment filter's central moments above P (empty for the other filters), in the state's order:
  // dM_q = moment_drift[q] dt + sum_r moment_gain[q][r] (dy_r - predicted_observation_r dt).
  std::vector<std::string> moment_names;              // q
  std::vector<std::string> moment_drift;              // q
  std::vector<std::vector<std::string>> moment_gain;  // q x p
  // A user filter's `define:` names or the ukf's Cholesky entries, in order: each value may read
  // the names before it, and the expressions above may read them all.
  std::vector<std::pair<std::string, std::string>> definitions;
  std::vector<std::string> m_names;                 // m1..mn
  std::vector<std::vector<std::string>> P_names;    // n x n: "P12" at (0, 1) and (1, 0)
  // Every name the expressions may read: the filter's variables, the parameters, the time
  // symbol and the definitions (anything else in them is a function: sin, exp, ...).
  std::vector<std::string> names;
};

class Model;

// One derived filter of one model.
class Filter {
 public:
  const std::string& name() const;     // "optimal", "ekf-additive", a user filter's name
  std::string text() const;            // pfgen derive --filter NAME
  std::string latex() const;           // pfgen derive --filter NAME --format latex
  std::string json() const;            // pfgen derive --filter NAME --format json
  Evaluation eval(const Point& point) const;  // pfgen eval --filter NAME
  Expressions expressions() const;

 private:
  friend class Model;
  struct Impl;
  explicit Filter(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;
};

// `pfgen codegen`'s options. filters: empty for the model's default filters. language: "cpp" or
// "c" (`--language`). scalar: "template" (C++ only), "float" or "double"; empty for the language's
// default (C++: template, C: double). dt: a delayed filter's grid step (else the model's).
struct CodegenOptions {
  std::vector<std::string> filters;
  std::string language = "cpp";
  std::string scalar;
  std::string name_space = "pfgen_models";
  bool eigen = false;
  std::optional<double> dt;
};

// A generated file: its path relative to the output directory ("<model>/optimal.hpp") and text.
struct CodeFile {
  std::string path;
  std::string contents;
};

// `pfgen simulate`'s settings; unset ones come from the model's `simulation:` section, then from
// pfgen's defaults (docs/guide/simulation.md). reference: the particle reference's N
// (`--reference particles:N`). x0: "prior" or "model". parameters: as Point's. threads: 0 for one
// per core (the results do not depend on it). cache_dir and compiler: empty for the defaults.
struct SimulationOptions {
  std::optional<std::size_t> runs;
  std::optional<double> T, dt;
  std::vector<std::string> filters;
  std::optional<std::uint64_t> seed;
  std::optional<std::size_t> reference;
  std::optional<std::string> scheme, x0;
  // `--stepping`: "refined" (unset: the default) or "generated", each filter's grid step as its
  // generated step() takes it, never split (docs/guide/simulation.md)
  std::optional<std::string> stepping;
  std::optional<std::size_t> record_points, shown_run;
  std::optional<double> bound, risk_epsilon;
  std::vector<double> report_times;
  std::vector<std::pair<double, double>> windows;
  std::map<std::string, double> parameters;
  unsigned threads = 0;
  std::size_t batch = 8;  // runs a thread steps side by side, 1 to 1024 (`--batch`); results do not depend on it
  std::string cache_dir, compiler;
  // The progress line the command draws on a terminal, given as its text: each draw is "\r" and
  // the line ("simulate [###...] 12/50 runs, 3 s elapsed, ~9 s left "), from the first finished
  // run on, at most five a second; the last text clears the line. Called from the simulation's
  // threads, one call at a time, while pfgen's lock is held: it must not call pfgen. Empty: none.
  std::function<void(const std::string& text)> progress;
};

// One filter's (or the particle reference's) statistics over the runs, per state component.
struct FilterSummary {
  std::string name;
  std::size_t completed = 0;   // runs that reached T
  std::size_t diverged = 0;
  std::size_t psd_losses = 0;
  // Among diverged, the runs stopped for a reason of their own, as the report's sections list them: a moment
  // filter's moments left the realisable set; a grid step needed more sub-steps than allowed (too stiff for
  // dt); the filter's equations were not finite at its own state (undefined).
  std::size_t unrealisable = 0;
  std::size_t too_stiff = 0;
  std::size_t undefined = 0;
  Vector rms, rms_se;          // RMS error over [0, T] and its standard error
  Vector peak_median, peak_q95;  // of max_t |x - m| over the completed runs
  // With the particle reference: RMS(m - m_ref) and its standard error (empty without).
  Vector reference_distance, reference_distance_se;
  // The particle reference's own row only (empty in the others): its own Monte Carlo error per
  // state, the table's "m_ref's own error" (NaN where no run had both particle sets reach T).
  Vector own_error;
};

struct SimulationResult {
  std::string report;  // what `pfgen simulate` prints before the paths of its files
  std::string notes;   // what it says on stderr before ("pfgen: note: ..."), line by line
  std::string csv;     // the CSV `pfgen simulate -o FILE` writes
  std::vector<std::string> columns;  // the CSV's header
  std::vector<Vector> series;        // per column, its values down the rows; NaN for an empty cell
  std::vector<FilterSummary> filters;
  std::size_t runs = 0;
  std::size_t steps = 0;
  std::size_t shown_run = 0;            // the run whose truth, estimates and errors the series show
  std::size_t reference_particles = 0;  // the particle reference's N; 0 without one
};

// A record of observations in memory, as a CSV file would hold it (docs/guide/recorded-data.md):
// a header naming each column (the time's among them) and the rows, a value per column, NaN for a
// missing observation. from_arrays builds one from the times and an N x p array of observations,
// the columns named "t" (or time_column) and y1..yp (or names).
struct RecordData {
  std::vector<std::string> columns;
  Matrix rows;
  static RecordData from_arrays(const Vector& times, const Matrix& values, const std::vector<std::string>& names = {},
                                const std::string& time_column = "t");
};

// What `pfgen estimate` and `pfgen fit` read and how (their options of the same names). The record:
// the CSV file data_path, or `data` (then data_path, if not empty, names it in the report and in
// messages; empty: "<data>"). time_column: `--time-column`; columns: `--columns`, the observation
// columns in the model's order (empty: every column but the time's); data_form: "increments" or
// "rates" (continuous observations); substeps: continuous data's filter steps per data interval;
// t0: the prior's time (unset: the first row's); parameters: `--set`; cache_dir, compiler: the
// plugin's, as SimulationOptions'.
struct RecordOptions {
  std::string data_path;
  std::optional<RecordData> data;
  std::string time_column = "t";
  std::vector<std::string> columns;
  std::string data_form = "increments";
  std::size_t substeps = 1;
  std::optional<double> t0;
  std::map<std::string, double> parameters;
  std::string cache_dir, compiler;
};

// `pfgen estimate`: filters empty for the model's defaults; full_covariance: every entry of P in
// the CSV (`--full-covariance`); series: keep the CSV (`-o`'s text) and its columns.
struct EstimateOptions {
  RecordOptions record;
  std::vector<std::string> filters;
  bool full_covariance = false;
  bool series = false;
};

// One filter's scores over a record (docs/guide/recorded-data.md, "The scores"): a row of
// estimate's table. increment_log_density: continuous data only (NaN for samples). Ljung-Box per
// observation entry: its lags, statistic Q and p-value.
struct RecordScores {
  std::string name;
  double log_likelihood = 0;
  double increment_log_density = 0;
  std::size_t count = 0;  // innovations: samples, or steps of continuous data
  double mean_square = 0, band_low = 0, band_high = 0;
  std::vector<std::size_t> ljung_box_lags;
  Vector ljung_box_statistic, ljung_box_p;
  bool consistent = false, white = false;
  std::string verdict;
  // Where and why the filter stopped before the record's end (a moment filter leaving its
  // realisable set: "FILE:LINE: its moments left ..."), its scores then those of the rows up to that
  // one; empty when it ran through.
  std::string stopped;
};

struct EstimateResult {
  std::string report;  // what `pfgen estimate` prints before the paths of its files
  std::vector<RecordScores> filters;
  std::string time_column;                       // as the CSV names it
  std::vector<std::string> observation_columns;  // in the model's order
  // With EstimateOptions::series: the CSV `pfgen estimate -o FILE` writes, its header and, per
  // column, its values down the rows (NaN for an empty cell); else empty.
  std::string csv;
  std::vector<std::string> columns;
  std::vector<Vector> series;
};

// A bound of `pfgen fit --bounds name=low:high`: an infinite end is an open one.
struct Bound {
  std::string name;
  double low = -HUGE_VAL, high = HUGE_VAL;
};

// `pfgen fit`: filter empty for the model's first default filter; estimate: the parameters'
// names; starts, seed, profile: `--starts`, `--seed`, `--profile`.
struct FitOptions {
  RecordOptions record;
  std::string filter;
  std::vector<std::string> estimate;
  std::vector<Bound> bounds;
  std::size_t starts = 1;
  std::uint64_t seed = 1;
  bool profile = false;
};

// One estimated parameter: std_error NaN when the observed information is not positive definite;
// the profile interval's ends NaN unless asked for, or where not found within the bounds.
struct FittedParameter {
  std::string name;
  double estimate = 0, std_error = 0;
  double wald_low = 0, wald_high = 0;
  double profile_low = 0, profile_high = 0;
  bool at_bound = false;
  // A moment filter's likelihood ends where its moments leave the realisable set: the profile
  // interval's end is then the last value where the filter runs (`(the filter fails beyond)`).
  bool profile_low_fails_beyond = false, profile_high_fails_beyond = false;
};

// A fit that did not converge is a result too (converged false, the last point in parameters), as
// the command prints it before exiting with 1.
struct FitResult {
  std::string report;  // what `pfgen fit` prints before the path of its file
  std::string json;    // what `pfgen fit -o FILE.json` writes
  bool converged = false;
  std::string stop_reason;
  std::vector<FittedParameter> parameters;
  double log_likelihood = 0, aic = 0;
  std::size_t evaluations = 0;
  // The estimate lies at the edge of where the filter runs (a neighbour of the differences fails):
  // not a maximum, no standard errors. note: why there are no standard errors, if there are none.
  bool at_edge = false;
  std::string note;
};

// A model: loaded from a model file or YAML text, or built with ModelBuilder. Checked when made.
class Model {
 public:
  static Model load(const std::string& path);
  // `source` names the text in error messages and reports.
  static Model from_yaml(const std::string& text, const std::string& source = "<yaml>");

  const std::string& name() const;
  const std::string& source() const;  // the file's path, or from_yaml's source
  std::vector<std::string> state_names() const;
  std::vector<std::string> parameter_names() const;
  // Every filter the model offers (the built-in kinds it supports, then its own `filters:`), and
  // those the commands use when none is named (all but the opt-in ukf).
  std::vector<std::string> kinds() const;
  std::vector<std::string> default_kinds() const;

  Filter derive(const std::string& kind) const;
  // `pfgen latex`: a whole LaTeX document with these filters (empty: the default ones).
  std::string latex_document(const std::vector<std::string>& filters = {}) const;
  // `pfgen codegen`: the files in memory, or written under `directory` (all or none; a file
  // would never replace the model file) with their paths returned.
  std::vector<CodeFile> codegen(const CodegenOptions& options = {}) const;
  std::vector<std::string> codegen(const std::string& directory, const CodegenOptions& options = {}) const;
  // `pfgen simulate`: compiles the filters with the truth into a cached plugin (the first time a
  // C++ compiler runs, as the command's does) and runs the Monte Carlo.
  SimulationResult simulate(const SimulationOptions& options = {}) const;
  // `pfgen estimate` and `pfgen fit` over a record: the filters compiled into the same cached
  // plugin as simulate's.
  EstimateResult estimate(const EstimateOptions& options) const;
  FitResult fit(const FitOptions& options) const;

 private:
  friend class Filter;
  friend class ModelBuilder;
  struct Impl;
  explicit Model(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;
};

// A model built from GiNaC expressions instead of a file (docs/guide/cpp-api.md). C++ doubles in
// expressions and numbers (0.1) become the exact rationals of their shortest decimals (1/10).
//   pfgen::api::ModelBuilder b("quadratic");
//   GiNaC::symbol x = b.state("x");
//   b.drift({0.1 * GiNaC::pow(x, 2)}).diffusion({{0.1 * GiNaC::pow(x, 2)}}).observation({0}, {{1}}, {{1}});
//   pfgen::api::Model model = b.build();
class ModelBuilder {
 public:
  using Exprs = std::vector<GiNaC::ex>;
  using ExprMatrix = std::vector<std::vector<GiNaC::ex>>;

  explicit ModelBuilder(const std::string& name);
  ~ModelBuilder();
  ModelBuilder(ModelBuilder&&) noexcept;
  ModelBuilder& operator=(ModelBuilder&&) noexcept;

  GiNaC::symbol state(const std::string& name);
  GiNaC::symbol parameter(const std::string& name, double default_value);
  GiNaC::symbol time() const;

  ModelBuilder& drift(const Exprs& f);
  ModelBuilder& diffusion(const ExprMatrix& g);             // g(x, t) dW1
  ModelBuilder& diffusion_covariance(const ExprMatrix& G);  // g g^T given instead of g
  ModelBuilder& additive_diffusion(const ExprMatrix& g);
  ModelBuilder& additive_diffusion_covariance(const ExprMatrix& G);
  // dy = (A0 + A x) dt + B dW2
  ModelBuilder& observation(const Exprs& A0, const ExprMatrix& A, const ExprMatrix& B);
  // dy = (A0 + A x(t - delay)) dt + B dW2
  ModelBuilder& delayed_observation(double delay, const Exprs& A0, const ExprMatrix& A, const ExprMatrix& B);
  // dy = h(x, t) dt + B dW2, each h_r a polynomial in the states
  ModelBuilder& polynomial_observation(const Exprs& h, const ExprMatrix& B);
  // y_k = C0 + C x(k period) + Uv v_k; substeps 0 (the default) as when a model file leaves them
  // out: each filter takes as many prediction sub-steps per period as its rate at the prior needs
  ModelBuilder& sampled_observation(double period, const Exprs& C0, const ExprMatrix& C, const ExprMatrix& Uv,
                                    std::size_t substeps = 0);
  // y_k = c(x(k period)) + Uv v_k, each c_r a polynomial in the states (degree <= 1: as C0 + C x)
  ModelBuilder& sampled_polynomial_observation(double period, const Exprs& c, const ExprMatrix& Uv,
                                               std::size_t substeps = 0);
  // The filters' prior N(m0, P0) and the truth's x0 (empty: drawn from the prior in each run).
  ModelBuilder& initial(const Vector& m0, const Matrix& P0, const Vector& x0 = {});
  // dW read in Stratonovich's sense (the drift is converted to Ito's form).
  ModelBuilder& stratonovich();

  // Checks the model (Error on the first problem) and returns it; the builder stays usable.
  Model build() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pfgen::api
