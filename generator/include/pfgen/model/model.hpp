#pragma once
// The model of a polynomial stochastic system with linear observations:
//   dx = f(x,t) dt + g(x,t) dW1, observed as its ObservationModel says (observation_model.hpp;
//   today continuously: dy = (A0 + A x) dt + B dW2).
// A Model is plain data; ModelBuilder and the YAML loader create it, and
// validate_model() guarantees every invariant documented here.
#include <ginac/ginac.h>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/model/expression_matrix.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/observation_model.hpp"
#include "pfgen_support/variable_names.hpp"

namespace pfgen {

struct Parameter {
  std::string name;
  GiNaC::symbol symbol;
  GiNaC::numeric default_value;
};

// A diffusion given either as g (n x q) or directly as G = g g^T (n x n, symmetric).
struct Diffusion {
  std::optional<ExMatrix> g;
  ExMatrix G;  // always set: g g^T when g is given
};

// The model file's `bounds:` entry of one parameter: where `pfgen fit` may look for it. An end
// left empty (~) is unbounded.
struct ParameterBound {
  std::string name;
  std::optional<GiNaC::numeric> low, high;
};

struct InitialConditions {
  std::vector<GiNaC::numeric> x0;  // may be empty when the model gives no truth initial state
  // `x0: prior`: each simulated run's truth starts from a draw of N(m0, P0), the filters' prior
  // (then x0 is empty). With a fixed x0 the particle reference is not the conditional mean.
  bool x0_from_prior = false;
  std::vector<GiNaC::numeric> m0;
  std::vector<std::vector<GiNaC::numeric>> P0;
};

// An auxiliary quantity of a user filter (`define:`): `name` stands for `value` wherever it
// appears. The value is any expression of the filter's variables, the parameters, t and the
// names defined before it (for example 1/(P11*P22 - P12^2)), so equations that divide by a
// polynomial of m and P, such as a filter printed in the information matrix Q = -eps P^-1, can
// be written as printed while m_drift, P_drift and gain stay polynomial in m and P.
struct FilterDefinition {
  FilterDefinition(GiNaC::symbol name_, GiNaC::ex value_, std::optional<GiNaC::ex> zero_where_zero_ = std::nullopt)
      : name(std::move(name_)), value(std::move(value_)), zero_where_zero(std::move(zero_where_zero_)) {}
  GiNaC::symbol name;
  GiNaC::ex value;
  // Set: the definition is 0 wherever this expression is 0, and `value` there is not computed.
  // A Cholesky entry below a zero pivot (the ukf with a positive semi-definite P: a state with
  // variance 0 has a zero column) is entry / pivot = 0/0 as written; the column is 0.
  std::optional<GiNaC::ex> zero_where_zero;
};

// A filter the model file gives by its equations (`filters:`), not derived by pfgen:
//   dm = m_drift dt + gain (dy - (A0 + A m) dt),   dP = P_drift dt,
// with the model's own observation for the predicted A0 + A m. Its expressions are
// polynomials in the filter's variables (t, parameters and its definitions may appear in the
// coefficients, states may not).
struct UserFilter {
  std::string name;         // [A-Za-z][A-Za-z0-9_-]*, not a built-in kind; '-' is '_' in C++
  std::string description;  // may be empty
  // m1..mn, then P11, P12, ..., P1n, P22, ... (upper triangle, row by row), named
  // as filter_variable_names(n); P21 in the file is the symbol of P12.
  std::vector<GiNaC::symbol> variables;
  ExVector m_drift;  // n
  ExMatrix P_drift;  // n x n, symmetric
  ExMatrix gain;     // n x p
  std::vector<FilterDefinition> definitions;  // in file order; each value reads only earlier names
};

// Defaults for `pfgen simulate` from the model file's `simulation:` section; every
// field is optional (unset: the command line or pfgen's defaults decide). Plain
// numbers (doubles), not exact rationals. validate_model() checks each field alone
// and against the others given here (dt < T, report times and windows within T,
// shown_run < runs, filters the model offers); the command line checks the
// combination with its own options, naming the field's place through location_of().
struct SimulationSection {
  std::optional<double> T;                       // horizon, > 0 (t0 = 0)
  std::optional<double> dt;                      // step, > 0 and < T
  std::optional<std::size_t> runs;               // >= 1
  std::optional<std::uint64_t> seed;
  std::optional<std::vector<std::string>> filters;  // built-in kinds the model supports or user filter names
  std::optional<std::string> scheme;             // one of simulation_schemes()
  std::vector<double> report_times;               // each in (0, T]; empty when not given
  std::vector<std::pair<double, double>> windows;  // a < b, within [0, T]; empty when not given
  std::optional<std::size_t> record_points;      // >= 2
  std::optional<double> bound;                   // divergence bound, > 0
  std::optional<std::size_t> shown_run;          // < runs

  // Where each given field sits in the model file ("T", "windows", ...); empty from the C++ API.
  std::string source;
  std::map<std::string, SourceLocation> locations;
  // "FILE:LINE:COL" of the field, as ModelError prints it ("FILE" alone when unknown).
  std::string location_of(const std::string& field) const;
};

// The model file's `risk:` section: the exponential criterion
//   J = epsilon log E[exp(epsilon^-1 int_0^T L dt)],   L = (x - m)^T weight (x - m),
// that `pfgen simulate` reports for every filter and the `risk-sensitive` kind is derived for
// (docs/theory.md §2.7). epsilon and weight hold numbers and parameters only (no states, no
// time), so `--set` can change them; weight defaults to the identity.
struct RiskCriterion {
  GiNaC::ex epsilon;
  ExMatrix weight;  // n x n, symmetric
};

// The values `scheme:` accepts: auto, euler-maruyama, milstein, ...
const std::vector<std::string>& simulation_schemes();

// How the model file's dW is read (`noise:`). Ito is the default; with Stratonovich noise
// dx = f dt + g o dW is the Ito equation dx = (f + c) dt + g dW with the correction
// c_i = 1/2 sum_j sum_k g_jk dg_ik/dx_j (docs/theory.md §1.2), polynomial when f and g are.
enum class NoiseCalculus { Ito, Stratonovich };

struct Model {
  std::string name;
  std::string source;  // file the model came from, or "<api>"
  std::vector<std::string> state_names;
  std::vector<GiNaC::symbol> states;
  std::vector<Parameter> parameters;
  GiNaC::symbol time;
  // n entries, polynomial in the states: the Ito drift, which every filter and the truth use.
  // With Stratonovich noise it is the drift as written plus the correction below.
  ExVector drift;
  NoiseCalculus noise = NoiseCalculus::Ito;
  // Stratonovich noise only (empty otherwise): the drift as the model file writes it, and the
  // correction c that drift adds to it (drift = stated_drift + noise_correction).
  ExVector stated_drift;
  ExVector noise_correction;
  Diffusion diffusion;                     // state-dependent (multiplicative) diffusion
  std::optional<Diffusion> additive_diffusion;  // constant diffusion for the `additive` kinds
  ObservationModel observation;           // its kind is chosen when the model file is read
  std::optional<InitialConditions> initial;
  std::vector<UserFilter> user_filters;  // in file order
  SimulationSection simulation;
  std::optional<RiskCriterion> risk;       // the `risk:` section, when given
  std::vector<ParameterBound> bounds;      // the `bounds:` section, in file order (pfgen fit's)

  std::size_t n() const { return states.size(); }
  std::size_t p() const { return observation.p(); }
};

// The text names of the filter's variables for n states, in their order: m1..mn, then the
// upper triangle of P row by row, P11, P12, ...; from n = 10 on the P indices are
// separated (P1_10). The naming rule is the support library's (pfgen_support/variable_names.hpp);
// the derivation's FilterVariables uses the same names.
using pfgen_support::filter_variable_names;

// A filter's name as a C++ identifier, used for generated namespaces and file names:
// '-' becomes '_' ("ekf-additive" -> "ekf_additive", "ekf-printed" -> "ekf_printed").
std::string filter_identifier(const std::string& name);

// The start of a message about the model that has no line to point at: its file and ": " (a
// model built in a program: "<api>: "), or nothing for a model without a source.
std::string source_place(const Model& model);

ExMatrix multiply_by_transpose(const ExMatrix& g);  // g g^T, expanded
ExMatrix inverse_noise_covariance(const ExMatrix& B);  // (B B^T)^-1, each entry a normalised coefficient
bool depends_on_states(const Model& model, const GiNaC::ex& e);

}  // namespace pfgen
