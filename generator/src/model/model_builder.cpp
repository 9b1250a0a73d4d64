#include "pfgen/model/model_builder.hpp"

#include "pfgen/model/stratonovich.hpp"

#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_validator.hpp"
#include "pfgen/notation/number_format.hpp"
#include "pfgen_support/variable_names.hpp"

namespace pfgen {
namespace {

// Shortest decimal that reads back as the same double, as an exact rational.
GiNaC::numeric exact_from_double(double value) { return *parse_exact_number(shortest_double(value)); }

struct ExactRationals : GiNaC::map_function {
  GiNaC::ex operator()(const GiNaC::ex& e) override {
    if (GiNaC::is_a<GiNaC::numeric>(e)) {
      const auto& number = GiNaC::ex_to<GiNaC::numeric>(e);
      if (number.is_real() && !number.is_rational()) return exact_from_double(number.to_double());
      return e;
    }
    return e.map(*this);
  }
};

ExMatrix exact_matrix(const ExMatrix& m) {
  ExMatrix out = m;
  for (auto& row : out)
    for (auto& entry : row) entry = exact_rationals(entry);
  return out;
}

ExVector exact_vector(const ExVector& v) {
  ExVector out = v;
  for (auto& entry : out) entry = exact_rationals(entry);
  return out;
}

// G is computed (or expanded) only in build(), after validate_model() has checked
// the shapes and degrees: expanding (x+1)^(10^9) first would never finish.
Diffusion from_g(const ExMatrix& g) {
  Diffusion d;
  d.g = exact_matrix(g);
  return d;
}

Diffusion from_G(const ExMatrix& G) {
  Diffusion d;
  d.G = exact_matrix(G);
  return d;
}

void complete(Diffusion& d) {
  if (d.g) {
    d.G = multiply_by_transpose(*d.g);
    return;
  }
  for (auto& row : d.G)
    for (auto& entry : row) entry = entry.expand();
}

}  // namespace

GiNaC::ex exact_rationals(const GiNaC::ex& e) {
  // Rebuilding an expression re-evaluates every sum and product in it: a dense drift entry of
  // thousands of terms whose decimals the parser already made exact is looked at, not rebuilt.
  bool inexact = false;
  for (auto it = e.preorder_begin(); it != e.preorder_end() && !inexact; ++it)
    if (GiNaC::is_a<GiNaC::numeric>(*it)) {  // as ExactRationals tests
      const auto& number = GiNaC::ex_to<GiNaC::numeric>(*it);
      inexact = number.is_real() && !number.is_rational();
    }
  if (!inexact) return e;
  ExactRationals convert;
  return convert(e);
}

ModelBuilder::ModelBuilder(std::string name, std::string source) {
  model_.name = std::move(name);
  model_.source = std::move(source);
  model_.time = GiNaC::symbol("t");
}

GiNaC::symbol ModelBuilder::state(const std::string& name) {
  GiNaC::symbol s(name);
  model_.state_names.push_back(name);
  model_.states.push_back(s);
  return s;
}

GiNaC::symbol ModelBuilder::parameter(const std::string& name, const GiNaC::numeric& value) {
  GiNaC::symbol s(name);
  GiNaC::numeric exact = value;
  if (value.is_real() && !value.is_rational()) exact = exact_from_double(value.to_double());
  model_.parameters.push_back(Parameter{name, s, exact});
  return s;
}

GiNaC::symbol ModelBuilder::time(const std::string& name) {
  model_.time = GiNaC::symbol(name);
  return model_.time;
}

ModelBuilder& ModelBuilder::drift(const ExVector& f) {
  model_.drift = exact_vector(f);
  has_drift_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::diffusion(const ExMatrix& g) {
  model_.diffusion = from_g(g);
  has_diffusion_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::diffusion_covariance(const ExMatrix& G) {
  model_.diffusion = from_G(G);
  has_diffusion_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::additive_diffusion(const ExMatrix& g) {
  model_.additive_diffusion = from_g(g);
  return *this;
}

ModelBuilder& ModelBuilder::additive_diffusion_covariance(const ExMatrix& G) {
  model_.additive_diffusion = from_G(G);
  return *this;
}

ModelBuilder& ModelBuilder::observation(const ExVector& A0, const ExMatrix& A, const ExMatrix& B) {
  model_.observation =
      ObservationModel(ObservationRate::of_affine(exact_vector(A0), exact_matrix(A), exact_matrix(B)), std::nullopt, std::nullopt);
  has_observation_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::delayed_observation(const GiNaC::numeric& delay, const ExVector& A0, const ExMatrix& A,
                                                const ExMatrix& B) {
  model_.observation =
      ObservationModel(ObservationRate::of_affine(exact_vector(A0), exact_matrix(A), exact_matrix(B)), std::nullopt, delay);
  has_observation_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::sampled_observation(const GiNaC::numeric& period, const ExVector& C0, const ExMatrix& C,
                                                const ExMatrix& Uv, std::optional<std::size_t> substeps) {
  model_.observation = ObservationModel(ObservationRate::of_affine(exact_vector(C0), exact_matrix(C), exact_matrix(Uv)),
                                        SampleTimes{period, substeps}, std::nullopt);
  has_observation_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::sampled_polynomial_observation(const GiNaC::numeric& period, const ExVector& c,
                                                          const ExMatrix& Uv, std::optional<std::size_t> substeps) {
  model_.observation = ObservationModel(ObservationRate::of_rows(exact_vector(c), exact_matrix(Uv), model_.states),
                                        SampleTimes{period, substeps}, std::nullopt);
  has_observation_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::polynomial_observation(const ExVector& h, const ExMatrix& B) {
  model_.observation =
      ObservationModel(ObservationRate::of_rows(exact_vector(h), exact_matrix(B), model_.states), std::nullopt, std::nullopt);
  has_observation_ = true;
  return *this;
}

ModelBuilder& ModelBuilder::initial(const InitialConditions& initial) {
  model_.initial = initial;
  return *this;
}

GiNaC::symtab ModelBuilder::symbols() const {
  GiNaC::symtab table;
  for (const auto& s : model_.states) table[s.get_name()] = s;
  for (const auto& p : model_.parameters) table[p.name] = p.symbol;
  table[model_.time.get_name()] = model_.time;
  return table;
}

const std::vector<GiNaC::symbol>& ModelBuilder::filter_variables() {
  // Made once the states are known; a state declared later makes them stale, which
  // build() reports (validate_model checks the names against the states).
  if (filter_variables_.empty())
    for (const auto& name : filter_variable_names(model_.states.size())) filter_variables_.emplace_back(name);
  return filter_variables_;
}

GiNaC::symtab ModelBuilder::filter_symbols() {
  GiNaC::symtab table = symbols();
  const std::vector<GiNaC::symbol>& variables = filter_variables();
  const std::size_t n = model_.states.size();
  for (const auto& v : variables) table[v.get_name()] = v;
  std::size_t index = n;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j, ++index)
      table[pfgen_support::covariance_name(j, i, n)] = variables.at(index);
  return table;
}

ModelBuilder& ModelBuilder::user_filter(const std::string& name, const ExVector& m_drift, const ExMatrix& P_drift,
                                        const ExMatrix& gain, const std::string& description,
                                        const std::vector<FilterDefinition>& definitions) {
  UserFilter filter;
  filter.name = name;
  filter.description = description;
  filter.variables = filter_variables();
  filter.m_drift = exact_vector(m_drift);
  filter.P_drift = exact_matrix(P_drift);
  filter.gain = exact_matrix(gain);
  for (const auto& definition : definitions)
    filter.definitions.push_back(FilterDefinition{definition.name, exact_rationals(definition.value)});
  model_.user_filters.push_back(std::move(filter));
  return *this;
}

ModelBuilder& ModelBuilder::noise(NoiseCalculus calculus) {
  model_.noise = calculus;
  return *this;
}

ModelBuilder& ModelBuilder::risk_criterion(const GiNaC::ex& epsilon, const ExMatrix& weight) {
  model_.risk = RiskCriterion{exact_rationals(epsilon), exact_matrix(weight)};
  return *this;
}

ModelBuilder& ModelBuilder::parameter_bounds(const std::vector<ParameterBound>& bounds) {
  model_.bounds = bounds;
  return *this;
}

ModelBuilder& ModelBuilder::simulation(const SimulationSection& settings) {
  model_.simulation = settings;
  return *this;
}

namespace {

// Rows h (or a sampled c) read against every declared state, now that all are (the rate's affine
// view is found here, once); a sampled c of degree <= 1 is written C0 + C x, so every room sees
// the linear samples, as the model file's C0 and C would give them.
void read_rows_against_states(Model& model) {
  const ObservationModel& observation = model.observation;
  if (observation.rate().written_affine()) return;
  ObservationRate rate = ObservationRate::of_rows(observation.rate().rows(), observation.rate().noise(), model.states);
  if (observation.samples() && rate.affine())
    rate = ObservationRate::of_affine(rate.affine()->A0, rate.affine()->A, rate.noise());
  model.observation = ObservationModel(std::move(rate), observation.samples(), observation.delay_h());
}

}  // namespace

Model ModelBuilder::build() const {
  if (!has_drift_) throw ModelError("drift", "missing required field");
  if (!has_diffusion_)
    throw ModelError("diffusion", "missing required field (give diffusion or diffusion_covariance)");
  if (!has_observation_) throw ModelError("observation", "missing required field");
  validate_model(model_);
  Model model = model_;
  read_rows_against_states(model);
  if (model.noise == NoiseCalculus::Stratonovich) {
    // The model as written is valid (and has g: validate_model checked); the filters and the
    // truth use its Ito form, which is validated again: the kinds it offers follow its drift.
    model.stated_drift = model.drift;
    model.noise_correction = stratonovich_correction(*model.diffusion.g, model.states);
    for (std::size_t i = 0; i < model.n(); ++i) model.drift[i] = (model.drift[i] + model.noise_correction[i]).expand();
    validate_model(model);
  }
  complete(model.diffusion);
  if (model.additive_diffusion) complete(*model.additive_diffusion);
  if (model.risk && model.risk->weight.empty())  // L = |x - m|^2 unless the model says otherwise
    for (std::size_t i = 0; i < model.n(); ++i) {
      model.risk->weight.emplace_back(model.n(), GiNaC::ex(0));
      model.risk->weight[i][i] = 1;
    }
  return model;
}

}  // namespace pfgen
