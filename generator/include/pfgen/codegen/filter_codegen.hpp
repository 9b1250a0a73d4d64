#pragma once
// Generates the code of one filter (a built-in kind or a user filter of the model file) in an
// output language: the language-neutral functions (filter_functions.hpp) written by that
// language's backend (backend.hpp, codegen/backends/<language>/) into its templates.
//   C++ (backends/cpp/cpp_backend.hpp): a header-only file per filter, namespace <NS>::<model>::<filter>
//     (the filter's name with '-' written '_'): n, p, state_size; Params<Scalar>; derivatives();
//     gain(); predicted_observation(); initial_state(); step(); with
//     CodegenOptions::eigen_wrapper also <filter>_eigen.hpp.
//   C99 (backends/c/c_backend.hpp): a .h/.c pair per filter, every name prefixed <NS>_<model>_<filter>_.
// Each backend writes the filter's file as its observation module describes it, in no language
// (observation_code.hpp, filter_file.hpp), into that backend's templates. A filter for delayed observations steps on a fixed grid dt and keeps its
// own fixed-size history: CodegenOptions::grid_step must give that dt, and the delay must be a
// whole number of it (model/delay_grid.hpp); otherwise CodegenError.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/codegen/filter_functions.hpp"
#include "pfgen/codegen/scalar_mode.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

// An output language by its name in the registry of backends (backend.hpp): "cpp", "c".
using Language = std::string;

// Code generation holds a graph of every expanded equation beside the structured form it may
// emit instead, about 0.2 kB per equation term with the derivation's own: the dense cubic models'
// optimal filters take 77 MB at n = 12 (0.3 million terms), 250 MB at n = 16 (1.2 million) and
// 670 MB at n = 20 (3.6 million), where derive alone needs 250 MB. A filter with more terms than
// this (about 2 GB) is refused before any of it is built, naming the filter and its count
// (CodegenError). A moment filter's higher-moment terms take about 0.7 kB each (closure4 of the
// dense cubic models: 1.2 GB at n = 7 for 1.6 million terms, 2.8 GB at n = 8 for 4.1 million), so
// each counts as kMomentTermWeight terms against the budget.
inline constexpr double kMaxCodegenTerms = 10000000;
inline constexpr double kMomentTermWeight = 3.5;

struct CodegenOptions {
  Language language = "cpp";
  ScalarMode scalar = ScalarMode::Template;     // C: Float or Double
  std::string name_space = "pfgen_models";      // C: the names' prefix, `::` written `_`
  bool eliminate_common_subexpressions = true;  // false only for the benchmark's baseline
  bool eigen_wrapper = false;                   // C++: also write <kind>_eigen.hpp (the observation module's *_eigen.hpp.tmpl)
  // Delayed observations only: the grid step dt the filter is generated for (`--dt`, else the
  // model's simulation dt). Ignored by the other filters.
  std::optional<double> grid_step;
  // A generated function with more operations (after CSE) than this is written in parts of at most
  // this many, each its own function (StatementEmitter::split_above): g++ -O2 needs minutes and
  // gigabytes for one function of tens of thousands of operations. Every example but ins16 is far
  // below. 0: never split (tests lower it to compare split and unsplit code on a small model).
  std::size_t max_function_ops = 500;
  // The most terms a filter's equations may have (codegen_load: a higher moment's count
  // kMomentTermWeight each); tests lower it.
  double max_equation_terms = kMaxCodegenTerms;
};

struct GeneratedFile {
  std::string relative_path;  // relative to `pfgen codegen -o DIR`: "<model>/<identifier>.hpp"
  std::string contents;
};

struct GeneratedFilter {
  std::string name;  // the filter's name: "ekf-additive", or a user filter's
  // The filter's header first (C++: <identifier>.hpp, then <identifier>_eigen.hpp with the Eigen
  // layer; C: <identifier>.h, then <identifier>.c).
  std::vector<GeneratedFile> files;
  std::vector<FunctionStats> functions;
  OpCounts naive_total() const;
  OpCounts cse_total() const;
};

// Where a filter's files go, relative to `pfgen codegen -o DIR`, in the order of
// GeneratedFilter::files: "<model>/<identifier>.hpp" (and "_eigen.hpp"), or ".h" and ".c";
// identifier = filter_identifier(filter_name): the language's backend's (Backend::filter_paths),
// by which the command line checks the paths it will write before anything is derived.
std::vector<std::string> filter_file_paths(const std::string& model_name, const std::string& filter_name,
                                           const CodegenOptions& options);


// The terms of the polynomials code generation reads from `eq` (drifts, gain, predicted
// observation, the P equations' parts, x*'s drift, a polynomial observation's P_gain, a moment
// filter's higher moments, realisability margins and joint moments at a sample); moment_terms: those of
// the last three.
double codegen_terms(const FilterEquations& eq);
double moment_terms(const FilterEquations& eq);
// What the budget compares with CodegenOptions::max_equation_terms: codegen_terms with each of the
// moment_terms counted kMomentTermWeight times.
double codegen_load(const FilterEquations& eq);

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options);

}  // namespace pfgen::codegen
