#pragma once
// The model of a polynomial stochastic system with linear continuous observations:
//   dx = f(x,t) dt + g(x,t) dW1,   dy = (A0 + A x) dt + B dW2.
// A Model is plain data; ModelBuilder and the YAML loader create it, and
// validate_model() guarantees every invariant documented here.
#include <ginac/ginac.h>
#include <optional>
#include <string>
#include <vector>

namespace pfgen {

using ExVector = std::vector<GiNaC::ex>;
using ExMatrix = std::vector<std::vector<GiNaC::ex>>;  // row-major, rows of equal length

struct Parameter {
  std::string name;
  GiNaC::symbol symbol;
  GiNaC::numeric default_value;
};

struct Observation {
  ExVector A0;  // p entries, independent of the states
  ExMatrix A;   // p x n
  ExMatrix B;   // p x r, with B B^T positive definite
};

// A diffusion given either as g (n x q) or directly as G = g g^T (n x n, symmetric).
struct Diffusion {
  std::optional<ExMatrix> g;
  ExMatrix G;  // always set: g g^T when g is given
};

struct InitialConditions {
  std::vector<GiNaC::numeric> x0;  // may be empty when the model gives no truth initial state
  std::vector<GiNaC::numeric> m0;
  std::vector<std::vector<GiNaC::numeric>> P0;
};

struct Model {
  std::string name;
  std::string source;  // file the model came from, or "<api>"
  std::vector<std::string> state_names;
  std::vector<GiNaC::symbol> states;
  std::vector<Parameter> parameters;
  GiNaC::symbol time;
  ExVector drift;                          // n entries, polynomial in the states
  Diffusion diffusion;                     // state-dependent (multiplicative) diffusion
  std::optional<Diffusion> additive_diffusion;  // constant diffusion for the `additive` kinds
  Observation observation;
  std::optional<InitialConditions> initial;

  std::size_t n() const { return states.size(); }
  std::size_t p() const { return observation.A.size(); }
};

ExMatrix multiply_by_transpose(const ExMatrix& g);  // g g^T, expanded
bool depends_on_states(const Model& model, const GiNaC::ex& e);

}  // namespace pfgen
