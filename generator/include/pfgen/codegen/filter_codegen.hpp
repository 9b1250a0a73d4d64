#pragma once
// Generates the header-only C++ of one filter (a built-in kind or a user filter of the model
// file) from templates/cpp/filter.hpp.tmpl.
// Generated API (namespace <NS>::<model>::<filter>, the filter's name with '-' written '_'):
//   n, p, state_size; Params<Scalar>; derivatives(); gain(); predicted_observation();
//   initial_state(); step()  -- see the template for their contracts.
// A filter for delayed observations (templates/cpp/delayed_filter.hpp.tmpl) steps on a fixed grid
// dt and keeps its own fixed-size history: CodegenOptions::grid_step must give that dt, and the
// delay must be a whole number of it (model/delay_grid.hpp); otherwise CodegenError.
// With CodegenOptions::eigen_wrapper, also <filter>_eigen.hpp: pack()/unpack() between the flat
// state and Eigen m, P, and overloads of the functions above taking them.
#include <optional>
#include <string>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

struct CodegenOptions {
  ScalarMode scalar = ScalarMode::Template;
  std::string name_space = "pfgen_models";
  bool eliminate_common_subexpressions = true;  // false only for the benchmark's baseline
  bool eigen_wrapper = false;                   // also write <kind>_eigen.hpp (templates/cpp/filter_eigen.hpp.tmpl)
  // Delayed observations only: the grid step dt the filter is generated for (`--dt`, else the
  // model's simulation dt). Ignored by the other filters.
  std::optional<double> grid_step;
  // A generated function with more operations (after CSE) than this is written in parts of at most
  // this many, each its own function (CppEmitter::split_above): g++ -O2 needs minutes and gigabytes
  // for one function of tens of thousands of operations. Every header in generated/ is far below.
  // 0: never split (tests lower it to compare split and unsplit code on a small model).
  std::size_t max_function_ops = 500;
};

struct FunctionStats {
  std::string function;  // derivatives, gain, predicted_observation
  OpCounts naive;        // every output evaluated as its own expression tree
  OpCounts cse;          // after common-subexpression elimination
};

// Where a filter's headers go, relative to `pfgen codegen -o DIR`: "<model>/<identifier>.hpp" and
// its Eigen layer "<model>/<identifier>_eigen.hpp", identifier = filter_identifier(filter_name).
// The one place these names are made: the generator names its files by it, and the command line
// checks the paths it will write before anything is derived.
struct FilterHeaderPaths {
  std::string header;
  std::string eigen_header;
};
FilterHeaderPaths filter_header_paths(const std::string& model_name, const std::string& filter_name);

struct GeneratedFilter {
  std::string name;            // the filter's name: "ekf-additive", or a user filter's
  std::string relative_path;   // "<model>/<identifier>.hpp", identifier = filter_identifier(name)
  std::string contents;
  std::string eigen_relative_path;  // "<model>/<identifier>_eigen.hpp", empty unless options.eigen_wrapper
  std::string eigen_contents;       // Eigen wrappers (m, P as Eigen matrices) around contents
  std::vector<FunctionStats> functions;
  OpCounts naive_total() const;
  OpCounts cse_total() const;
};

// Code generation holds a graph of every expanded equation beside the structured form it may
// emit instead, about 1.1 kB per equation term: the dense cubic models' optimal filters took
// 150 MB at n = 10 (0.13 million terms), 670 MB at n = 14 (0.64 million), 1.6 GB at n = 16 (1.2
// million) and ended in bad_alloc at n = 20 (3.6 million), where derive needs 250 MB. A filter with
// more terms than this is refused before any of it is built, naming the filter and its count
// (CodegenError).
inline constexpr double kMaxCodegenTerms = 1500000;

// A sampled filter's update writes its Cholesky solve out for every output, O(r^3) straight-line
// code: 1.2 MB of C++ at r = 64, 4 MB at r = 100 and 27 MB at r = 200, which a compiler takes
// minutes over. Code generation takes at most this many outputs (derive and eval take any).
inline constexpr std::size_t kMaxSampledOutputs = 64;

// The terms of the polynomials code generation reads from `eq` (drifts, gain, predicted
// observation, the P equations' parts, x*'s drift).
double codegen_terms(const FilterEquations& eq);

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options);

}  // namespace pfgen::codegen
