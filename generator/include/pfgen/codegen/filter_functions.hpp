#pragma once
// The functions a filter's code consists of, built from its equations in no language's syntax
// and written by a backend's emitter: derivatives() (with its structured Stein form) and any other
// function of the filter variables. Each is one ExpressionGraph of all its outputs (common
// subexpressions shared), its operation counts, and its body as the emitter writes it. Which
// functions a filter has is its observation module's (observations/<kind>/<kind>_code.hpp: a
// continuous or delayed filter's derivatives(), gain() and predicted_observation(); a sampled
// filter's derivatives(), euler_square() (cd-euler), innovation_terms(), observation_matrices()
// and predicted_observation()); the backends (codegen/backends/<language>/) put their bodies into
// their templates.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/codegen/ir/statement_emitter.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

struct CodegenOptions;

struct FunctionStats {
  std::string function;  // derivatives, gain, predicted_observation
  OpCounts naive;        // every output evaluated as its own expression tree
  OpCounts cse;          // after common-subexpression elimination
  // false for a function that computes what others of the filter do (rates()): the file's totals
  // count each quantity once.
  bool in_totals = true;
};

// "N (a add, m mul, d div, c call)" and "Ops: ... without CSE, ... with CSE."
std::string counts_text(const OpCounts& counts);
std::string ops_comment(const FunctionStats& stats);

// The arguments of the generated functions and their temporaries, named clear of the model's
// names (local_names.hpp). The time argument has the model's name.
struct FunctionNames {
  // L and c: a polynomial observation's covariance gain and Ito-Stratonovich correction.
  std::string time, state, delayed, params, out, K, h, shared, L, c, temporary_prefix;
  // The loops of P's drift (p_drift_loops.hpp): the work array, local blocks and loop indices.
  std::string work, full_P, JP, gain_T, H, sum, i, j, u, JP_T;
};
FunctionNames function_names(const Model& model);

// One generated function: its statistics and its body.
struct FunctionCode {
  FunctionStats stats;
  FunctionBody body;
};

// The function `function` writing `outputs` to its array argument `target`, with the filter's
// definitions computed first.
FunctionCode function_code(const std::string& function, const std::vector<Polynomial>& outputs,
                           const std::string& target, const Model& model, const FilterEquations& eq,
                           const CodegenOptions& options, const FunctionNames& names, const StatementEmitter& emitter);
// The forms derivatives() may be written in: the expanded polynomials; the derivation's structure
// (P E[J]^T + E[J] P, each E[J] entry once; the correction as K (A P)), its expectations as the
// derivation's polynomials or over shared Gaussian moments (moment_form.hpp), each also with the
// products of P and E[J]'s constant entries collected with E[g g^T] into one expanded polynomial
// (Collected...); and the first two with P's drift in loops over dense blocks (p_drift_loops.hpp).
enum class DerivativesForm { Expanded, Structured, Moments, Loops, MomentLoops, CollectedStructured, CollectedMoments };

// derivatives(): m's drift, P's drift (upper triangle) and x*'s drift when the filter has one, to
// `out`; in the form that needs the fewest operations after sharing (the earlier on a tie), or in
// loops where E[J] is dense or they need no more (from n = kMinLoopDimensionAlone). `rates_form`
// receives the form rates() takes: the same, but in loops from n = kMinLoopDimension, where they
// pay with the gain shared.
FunctionCode derivatives_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                              const FunctionNames& names, const StatementEmitter& emitter,
                              DerivativesForm* rates_form = nullptr);
// rates(): derivatives' outputs, then the gain (n x p, row-major) and the predicted observation,
// to `out`, in one body in `form` (derivatives_code's rates_form): what derivatives() and gain()
// have in common (K, and with it P's correction) is computed once. `naive`: the three functions' naive count.
FunctionCode rates_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                        const FunctionNames& names, const StatementEmitter& emitter, DerivativesForm form,
                        const OpCounts& naive);

// The filter state at t = 0: m0 and P0's upper triangle (zeros without an initial section); with
// `x_star`, x*(0) = m0 after them (a delayed filter's noise-free solution).
std::vector<GiNaC::numeric> initial_values(const Model& model, const FilterVariables& vars, bool x_star = false);
// initial_state()'s body: state[v] = values[v] for each.
ir::Block initial_state_statements(const std::vector<GiNaC::numeric>& values);

}  // namespace pfgen::codegen
