#pragma once
// The pieces the truth's functions are written with (truth_codegen.hpp), shared with the
// observation modules' plugin parts.
#include <string>
#include <utility>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/local_names.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

// The truth functions' arguments, their local `params` and their temporaries, named clear of the
// model's states, parameters and time (local_names.hpp); the time argument has the model's name.
struct TruthNames {
  explicit TruthNames(const Model& model);
  // An output argument: `preferred` unless the model or an earlier argument took it.
  std::string take(const std::string& preferred) { return local.take(preferred); }

  LocalNames local;  // first: the names below are taken from it
  const std::string time, x, params, temporary_prefix;
};

// The entries of `rows`, row by row, as polynomials in the model's states.
std::vector<Polynomial> in_states(const Model& model, const ExMatrix& rows);

// One function of (t, x) at the default parameters, all outputs in one graph so that
// subexpressions shared between entries (the powers of x in f and in g, sin(t)) are computed
// once; output k is written to destinations[k]. The body first names each input it reads
// (states, then parameters, as in the model), and casts the arguments it does not read to void
// so that the plugin compiles without warnings whatever the model leaves out.
std::string truth_function(const Model& model, TruthNames& names, const std::string& signature, bool reads_x,
                           const std::vector<Polynomial>& outputs, const std::vector<std::string>& destinations);

// A function of (t, x), `function_name`(t, x, target), writing output k to target[k]; the target
// is named `preferred_target` unless the model or an earlier argument took it.
std::string state_function(const Model& model, TruthNames& names, const std::string& function_name,
                           const std::string& preferred_target, const std::vector<Polynomial>& outputs);

// Matrices in one function of t, `function_name`(t, M1, M2, ...): entry k of each part, in turn,
// to its own argument, named as the part unless the model took that name.
std::string matrices_function(const Model& model, TruthNames& names, const std::string& function_name,
                              const std::vector<std::pair<std::string, ExMatrix>>& parts);

// The same at parameter values given in the call, `function_name`(values, t, M1, M2, ...): values
// holds the model's parameters in its order (read by the truth's Params(values) constructor).
std::string parameterised_matrices_function(const Model& model, TruthNames& names, const std::string& function_name,
                                            const std::vector<std::pair<std::string, ExMatrix>>& parts);

// Whether an entry of `m` reads the model's time.
bool depends_on_time(const Model& model, const ExMatrix& m);

}  // namespace pfgen::codegen
