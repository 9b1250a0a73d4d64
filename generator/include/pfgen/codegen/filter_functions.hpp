#pragma once
// The functions a filter's code consists of, built from its equations in no language's syntax
// and written by a backend's emitter: derivatives(), gain() and predicted_observation() of a
// continuous or delayed filter; a sampled filter's derivatives(), euler_square() (cd-euler),
// innovation_terms(), observation_matrices() and predicted_observation(). Each is one
// ExpressionGraph of all its outputs (common subexpressions shared), its operation counts, and
// its body as the emitter writes it. The backends (codegen/backends/<language>/) put these
// bodies into their templates.
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

struct CodegenOptions;

struct FunctionStats {
  std::string function;  // derivatives, gain, predicted_observation
  OpCounts naive;        // every output evaluated as its own expression tree
  OpCounts cse;          // after common-subexpression elimination
};

// "N (a add, m mul, d div, c call)" and "Ops: ... without CSE, ... with CSE."
std::string counts_text(const OpCounts& counts);
std::string ops_comment(const FunctionStats& stats);

// The arguments of the generated functions and their temporaries, named clear of the model's
// names (local_names.hpp). The time argument has the model's name.
struct FunctionNames {
  std::string time, state, delayed, params, out, K, h, shared, temporary_prefix;
};
FunctionNames function_names(const Model& model);

// One generated function: its statistics and its body.
struct FunctionCode {
  FunctionStats stats;
  FunctionBody body;
};

// The three functions of a filter with continuous (or delayed) observations.
struct ContinuousFunctions {
  FunctionCode derivatives, gain, observation;
};
ContinuousFunctions continuous_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                         const FunctionNames& names, const CFamilyEmitter& emitter);

// The functions of a filter for sampled observations; euler_square only for cd-euler.
struct SampledFunctions {
  FunctionCode derivatives;
  std::optional<FunctionCode> euler_square;
  FunctionCode innovation, matrices, observation;
};
SampledFunctions sampled_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                   const FunctionNames& names, const CFamilyEmitter& emitter);

// The filter state at t = 0: m0 and P0's upper triangle (zeros without an initial section); with
// `x_star`, x*(0) = m0 after them (a delayed filter's noise-free solution).
std::vector<GiNaC::numeric> initial_values(const Model& model, const FilterVariables& vars, bool x_star = false);

}  // namespace pfgen::codegen
