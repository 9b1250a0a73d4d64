#include "pfgen/derivation/filter_equations.hpp"

#include <stdexcept>

#include "pfgen/derivation/derivation_budget.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/derivation/moment_closure.hpp"
#include "pfgen/derivation/observation_derivation.hpp"
#include "pfgen/derivation/risk_sensitive.hpp"
#include "pfgen/derivation/unscented.hpp"
#include "pfgen/notation/rich_text.hpp"

namespace pfgen {
namespace {

using PolyMatrix = std::vector<std::vector<Polynomial>>;

std::vector<Polynomial> state_polynomials(const ExVector& v, const Model& model) {
  std::vector<Polynomial> out;
  for (const auto& e : v) out.push_back(Polynomial::from_ex(e, model.states));
  return out;
}

PolyMatrix jacobian(const std::vector<Polynomial>& f) {
  PolyMatrix J(f.size(), std::vector<Polynomial>(f.size()));
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t k = 0; k < f.size(); ++k) J[i][k] = f[i].derivative(static_cast<std::uint32_t>(k));
  return J;
}

// The three state-dependent quantities a filter kind needs, read in m and P:
// the drift of m, the matrix standing for the Jacobian (E[J_f] or J_f(m)) and
// the diffusion covariance (E[G], G(m) or the additive G), upper triangle.
struct MomentTerms {
  std::vector<Polynomial> drift;
  PolyMatrix jacobian;
  std::vector<Polynomial> diffusion_upper;
  std::optional<ExpectationSources> sources;  // when the three are Gaussian expectations
};

// A diffusion covariance's upper triangle, G_ij for i <= j row by row, as polynomials in the states.
std::vector<Polynomial> upper_polynomials(const ExMatrix& G, const Model& model) {
  std::vector<Polynomial> upper;
  for (std::size_t i = 0; i < G.size(); ++i)
    for (std::size_t j = i; j < G.size(); ++j) upper.push_back(Polynomial::from_ex(G[i][j], model.states));
  return upper;
}

// The model file's field a budget error about that diffusion names.
std::string diffusion_field(const Diffusion& diffusion, bool additive) {
  return std::string(additive ? "additive_" : "") + (diffusion.g ? "diffusion" : "diffusion_covariance");
}

// The budget of a kind built from the model's own f, its Jacobian J and G (not from moment_terms):
// counted as Gaussian expectations when `gaussian`, else as the polynomials read at m.
void check_model_terms_budget(const Model& model, bool gaussian, const std::vector<Polynomial>& f, const PolyMatrix& J) {
  check_derivation_budget(model, DerivationInputs{gaussian, f, J, upper_polynomials(model.diffusion.G, model),
                                                  diffusion_field(model.diffusion, false),
                                                  observation_derivation(model.observation).observed_states(model)});
}

MomentTerms moment_terms(const Model& model, FilterKind kind, const FilterVariables& vars) {
  const std::size_t n = model.n();
  std::vector<Polynomial> f = state_polynomials(model.drift, model);
  PolyMatrix J = jacobian(f);
  const bool additive = uses_additive_diffusion(kind);
  const Diffusion& diffusion = additive ? *model.additive_diffusion : model.diffusion;
  std::vector<Polynomial> G_upper = upper_polynomials(diffusion.G, model);
  check_derivation_budget(model, DerivationInputs{!is_extended_kalman(kind), f, J, G_upper,
                                                  diffusion_field(diffusion, additive),
                                                  observation_derivation(model.observation).observed_states(model)});

  // State x_i and mean m_i share variable index i (FilterVariables), so the
  // extended filter's f(m), J(m), G(m) are the x-polynomials read as they are.
  if (is_extended_kalman(kind)) return MomentTerms{f, J, G_upper, std::nullopt};

  GaussianExpectation E(vars);
  MomentTerms out;
  for (const auto& fi : f) out.drift.push_back(E.of(fi));
  out.jacobian.assign(n, std::vector<Polynomial>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < n; ++k) out.jacobian[i][k] = E.of(J[i][k]);
  for (const auto& g : G_upper) out.diffusion_upper.push_back(E.of(g));
  out.sources = ExpectationSources{std::move(f), std::move(G_upper)};
  return out;
}

// What every filter of the model shares: its variables, its observation kind and what its
// observation module puts in every filter (the predicted observation its innovation subtracts,
// the model's own, for user filters too).
FilterEquations equations_frame(const Model& model) {
  const ObservationDerivation& observation = observation_derivation(model.observation);
  FilterEquations eq;
  eq.observation = model.observation.kind();
  eq.variables = observation.variables(model.n());
  eq.p = model.p();
  observation.frame(model, eq);
  return eq;
}

// The risk-sensitive kind: its parts from paper 002's construction (risk_sensitive.hpp), and the
// Jacobian at m that its transport term is made of, for code generation's shared form.
FilterEquations risk_sensitive_filter(const Model& model, FilterEquations eq) {
  const std::vector<Polynomial> f = state_polynomials(model.drift, model);
  PolyMatrix J = jacobian(f);
  check_model_terms_budget(model, false, f, J);
  RiskSensitiveTerms terms = risk_sensitive_terms(model, eq.variables);
  eq.m_drift = std::move(terms.m_drift);
  eq.gain = std::move(terms.gain);
  eq.jacobian_term = std::move(J);
  eq.P_moment = std::move(terms.P_moment);
  eq.P_diffusion = std::move(terms.P_diffusion);
  eq.P_correction = std::move(terms.P_correction);
  eq.risk = model.risk;
  return eq;
}

// The unscented kind (unscented.hpp): its moment terms from the sigma points, L's entries as the
// equations' definitions, and the observation's gain and correction as the optimal kind's (its
// observation module's terms): with a linear observation the sigma-point cross-covariance of x
// and A x is P A^T exactly. There is no Jacobian term (P_moment is not of the form P J^T + J P for
// a J polynomial in m and P), so code generation takes the expanded form.
FilterEquations unscented_filter(const Model& model, FilterEquations eq) {
  // The Gaussian closure's budget is this derivation's bound too: a monomial's sigma-point sum has
  // no more terms in m than its Gaussian expectation (one per sub-monomial of even co-degree).
  const std::vector<Polynomial> f = state_polynomials(model.drift, model);
  check_model_terms_budget(model, true, f, jacobian(f));
  UnscentedTerms terms = unscented_terms(model, eq.variables);
  eq.definitions = std::move(terms.cholesky);
  eq.m_drift = std::move(terms.m_drift);
  eq.P_moment = std::move(terms.P_moment);
  eq.P_diffusion = std::move(terms.P_diffusion);
  observation_derivation(model.observation).observation_terms(model, FilterKind::Ukf, eq);
  return eq;
}

// A moment filter (moment_closure.hpp): its variables carry the central moments up to the kind's order, and
// the Kushner-Stratonovich equations of each, closed, give every term, a continuous observation's included
// (linear or polynomial alike). With samples (cd-closure3, cd-closure4) the equations have no observation
// term: they are the prediction, and the sampled module gives the update: through C0 + C x its frame's of m and
// P, which code generation and eval extend to the higher moments (sampled_moment_update.hpp); through a
// polynomial c its observation_terms' moment matching under the closed law (closure_sampled_update.hpp).
FilterEquations moment_filter(const Model& model, FilterKind kind, FilterEquations eq) {
  const std::vector<Polynomial> f = state_polynomials(model.drift, model);
  const unsigned order = filter_kind_info(kind).closure_order;
  const ObservationRate& rate = model.observation.rate();
  const bool sampled = model.observation.samples().has_value();
  const std::vector<Polynomial> h = sampled ? std::vector<Polynomial>() : rate.polynomials(model.states);
  // The Gaussian kinds' limits first (the closed law's moments include the Gaussian ones), then the
  // closure's own count of its moments' equations.
  check_model_terms_budget(model, true, f, jacobian(f));
  check_closure_budget(model, ClosureInputs{order, filter_kind_name(kind), f, h, rate.noise(),
                                            diffusion_field(model.diffusion, false),
                                            rate.written_affine() ? "observation.A" : "observation.h"});
  eq.variables = FilterVariables(model.n(), false, order);
  MomentClosureTerms terms = moment_closure_terms(model, eq.variables, h, rate.noise());
  eq.m_drift = std::move(terms.m_drift);
  eq.gain = std::move(terms.gain);
  if (!sampled) eq.predicted_observation = std::move(terms.predicted_observation);  // else the sampled module's
  eq.P_moment = std::move(terms.P_moment);
  eq.P_diffusion = std::move(terms.P_diffusion);
  eq.P_correction = std::move(terms.P_correction);
  eq.P_gain = std::move(terms.P_gain);
  eq.higher_drift = std::move(terms.higher_drift);
  eq.higher_gain = std::move(terms.higher_gain);
  RealisabilityMargins margins = realisability_margins(eq.variables, model.state_names);
  eq.realisability = std::move(margins.margins);
  eq.realisability_meaning = std::move(margins.meaning);
  // The sampled module's own terms: none between samples, and the prediction's sub-steps.
  if (sampled) observation_derivation(model.observation).observation_terms(model, kind, eq);
  return eq;
}

}  // namespace

Polynomial FilterEquations::P_drift(std::size_t i, std::size_t j) const {
  std::size_t u = variables.upper_index(i, j);
  return P_moment[u] + P_diffusion[u] - P_correction[u];
}

FilterEquations derive_filter(const Model& model, FilterKind kind) {
  if (auto reason = unsupported_reason(model, kind))
    throw std::invalid_argument("filter '" + filter_kind_name(kind) + "' " + *reason + " in the model");
  const std::size_t n = model.n();
  // Before the frame, which takes the observation's first expectations.
  check_observation_budget(model, observation_derivation(model.observation).budget_polynomials(model),
                           !is_extended_kalman(kind));
  FilterEquations eq = equations_frame(model);
  eq.name = filter_kind_name(kind);
  eq.description = filter_kind_description(kind);
  eq.kind = kind;
  eq.exactness = assess_exactness(model, kind);
  const FilterVariables& vars = eq.variables;
  auto P = [&](std::size_t i, std::size_t j) { return Monomial::variable(vars.P(i, j)); };
  if (is_risk_sensitive(kind)) return risk_sensitive_filter(model, std::move(eq));
  if (uses_sigma_points(kind)) return unscented_filter(model, std::move(eq));
  if (uses_cumulant_closure(kind)) return moment_filter(model, kind, std::move(eq));

  MomentTerms terms = moment_terms(model, kind, vars);
  eq.expectation_sources = std::move(terms.sources);
  eq.m_drift = std::move(terms.drift);
  eq.P_diffusion = std::move(terms.diffusion_upper);

  // E[(x-m) f^T]_ij = sum_k P_ik E[d_k f_j] (Stein's lemma); the EKF uses J(m).
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      // The products in the order add_times_monomial would add them, summed by one sort.
      std::vector<std::pair<Monomial, GiNaC::ex>> products;
      std::size_t count = 0;
      for (std::size_t k = 0; k < n; ++k) count += terms.jacobian[j][k].terms().size() + terms.jacobian[i][k].terms().size();
      products.reserve(count);
      for (std::size_t k = 0; k < n; ++k) {
        for (const auto& [m, c] : terms.jacobian[j][k].terms()) products.emplace_back(m * P(i, k), c);
        for (const auto& [m, c] : terms.jacobian[i][k].terms()) products.emplace_back(m * P(k, j), c);
      }
      eq.P_moment.push_back(Polynomial::sum_of(std::move(products)));
    }
  eq.jacobian_term = std::move(terms.jacobian);

  observation_derivation(model.observation).observation_terms(model, kind, eq);
  return eq;
}

FilterEquations derive_user_filter(const Model& model, const UserFilter& filter) {
  const std::size_t n = model.n();
  // Its frame takes the observation's expectations as a built-in kind's does.
  check_observation_budget(model, observation_derivation(model.observation).budget_polynomials(model), false);
  FilterEquations eq = equations_frame(model);
  eq.name = filter.name;
  // The model file's words, printed as written (no math spans).
  eq.description = filter.description.empty() ? "user-defined filter given by its equations in the model file"
                                               : rich_text_literal(filter.description);
  eq.exactness.exact = false;
  eq.exactness.condition = "user-defined";
  eq.exactness.explanation = "given by its equations in the model file; not derived by pfgen";
  // The model room names its symbols as FilterVariables does, in the same order
  // (validate_model checked), so symbol k is variable index k.
  auto polynomial = [&](const GiNaC::ex& e) { return Polynomial::from_ex(e, filter.variables); };
  GiNaC::exmap as_filter_symbols;
  for (std::size_t v = 0; v < filter.variables.size(); ++v) as_filter_symbols[filter.variables[v]] = eq.variables.symbols().at(v);
  for (const auto& d : filter.definitions) eq.definitions.push_back(FilterDefinition{d.name, d.value.subs(as_filter_symbols)});
  for (const auto& e : filter.m_drift) eq.m_drift.push_back(polynomial(e));
  eq.gain.assign(n, std::vector<Polynomial>(eq.p));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t r = 0; r < eq.p; ++r) eq.gain[i][r] = polynomial(filter.gain[i][r]);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      eq.P_moment.push_back(polynomial(filter.P_drift[i][j]));
      eq.P_diffusion.emplace_back();
      eq.P_correction.emplace_back();
    }
  return eq;
}

FilterEquations derive_named_filter(const Model& model, const std::string& name) {
  if (auto split = split_substeps(name)) {  // KIND@S: the kind with S sub-steps (model_filters.hpp)
    if (auto problem = filter_name_problem(model, name)) throw std::invalid_argument(*problem);
    FilterEquations eq = derive_named_filter(model, split->first);
    eq.name = name;
    eq.update.substeps = split->second;
    eq.update.substeps_chosen = false;
    return eq;
  }
  for (const auto& filter : model.user_filters)
    if (filter.name == name) return derive_user_filter(model, filter);
  if (auto kind = parse_filter_kind(name)) return derive_filter(model, *kind);
  std::string known;
  for (const auto& n : available_filter_names(model)) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("model " + model.name + " has no filter '" + name + "' (known: " + known + ")");
}

}  // namespace pfgen
