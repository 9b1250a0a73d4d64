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

#include "pfgen/codegen/cpp_emitter.hpp"
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

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options);

}  // namespace pfgen::codegen
