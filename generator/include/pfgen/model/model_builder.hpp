#pragma once
// The C++ API for building a Model from GiNaC expressions, for users who
// generate models in code. The YAML loader uses it too, so both paths share
// one validation (validate_model).
//
//   pfgen::ModelBuilder b("basin2006_quadratic");
//   GiNaC::symbol x = b.state("x");
//   b.drift({GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)});
//   b.diffusion({{GiNaC::numeric(1, 10) * GiNaC::pow(x, 2)}});
//   b.observation({0}, {{1}}, {{1}});
//   pfgen::Model model = b.build();
//
// Floating-point numbers in the expressions (0.1 written as a C++ double) are
// replaced by the exact rational of their shortest round-trip decimal (1/10).
#include <string>

#include "pfgen/model/model.hpp"

namespace pfgen {

class ModelBuilder {
 public:
  explicit ModelBuilder(std::string name, std::string source = "<api>");

  GiNaC::symbol state(const std::string& name);
  GiNaC::symbol parameter(const std::string& name, const GiNaC::numeric& default_value);
  // Renames the time symbol (default "t"); call before using time() in expressions.
  GiNaC::symbol time(const std::string& name);
  GiNaC::symbol time() const { return model_.time; }

  ModelBuilder& drift(const ExVector& f);
  ModelBuilder& diffusion(const ExMatrix& g);
  ModelBuilder& diffusion_covariance(const ExMatrix& G);
  ModelBuilder& additive_diffusion(const ExMatrix& g);
  ModelBuilder& additive_diffusion_covariance(const ExMatrix& G);
  ModelBuilder& observation(const ExVector& A0, const ExMatrix& A, const ExMatrix& B);
  // dy = (A0 + A x(t - delay)) dt + B dW2; delay >= 0 (the validator refuses a negative one).
  ModelBuilder& delayed_observation(const GiNaC::numeric& delay, const ExVector& A0, const ExMatrix& A,
                                    const ExMatrix& B);
  // Samples y_k = C0 + C x(k T) + Uv v_k; C0 may be zeros. Without substeps
  // each filter chooses its own (observations/sampled/substep_choice.hpp).
  ModelBuilder& sampled_observation(const GiNaC::numeric& period, const ExVector& C0, const ExMatrix& C,
                                    const ExMatrix& Uv, std::optional<std::size_t> substeps = std::nullopt);
  // dy = h(x, t) dt + B dW2, each h_r a polynomial in the states.
  ModelBuilder& polynomial_observation(const ExVector& h, const ExMatrix& B);
  // Samples y_k = c(x(t_k)) + Uv v_k, c polynomial in the states; a c of degree <= 1 is written
  // C0 + C x by build(), so its filters are those of sampled_observation().
  ModelBuilder& sampled_polynomial_observation(const GiNaC::numeric& period, const ExVector& c, const ExMatrix& Uv,
                                               std::optional<std::size_t> substeps);
  ModelBuilder& initial(const InitialConditions& initial);

  // The filter's own variables for user filters, once every state is declared: m1..mn,
  // then P11, P12, ..., P1n, P22, ... (upper triangle; see filter_variable_names). The
  // same symbols on every call, so all user filters share them.
  const std::vector<GiNaC::symbol>& filter_variables();
  // Adds a filter given by its equations (see UserFilter), written in filter_variables(),
  // the time symbol and the parameters; checked by build() like the model's expressions.
  //   auto v = b.filter_variables();   // n = 1: m1, P11
  //   b.user_filter("ekf-printed", {0.1 * pow(v[0], 2)}, {{0.4 * v[1] + 0.01 - pow(v[1], 2)}}, {{v[1]}});
  // `definitions` (FilterDefinition) are the filter's auxiliary names, in the order they are
  // defined; their symbols may appear in the equations' coefficients.
  ModelBuilder& user_filter(const std::string& name, const ExVector& m_drift, const ExMatrix& P_drift,
                            const ExMatrix& gain, const std::string& description = "",
                            const std::vector<FilterDefinition>& definitions = {});
  // How dW is read (`noise:`, NoiseCalculus): with Stratonovich, build() converts the drift to
  // its Ito form (stratonovich.hpp) and keeps the drift as given in Model::stated_drift.
  ModelBuilder& noise(NoiseCalculus calculus);
  // The model file's `risk:` section (RiskCriterion); an empty weight means the identity.
  ModelBuilder& risk_criterion(const GiNaC::ex& epsilon, const ExMatrix& weight = {});
  // The model file's `bounds:` (ParameterBound; checked by build(): parameters, low < high, the
  // default inside).
  ModelBuilder& parameter_bounds(const std::vector<ParameterBound>& bounds);
  // The model file's `simulation:` defaults (checked by build()).
  ModelBuilder& simulation(const SimulationSection& settings);

  // Every name an expression of this model may use: states, parameters, time.
  GiNaC::symtab symbols() const;
  // What a user filter's expressions may use: symbols() and filter_variables(), with P21
  // (P2_1 from n = 10 on) naming the same symbol as P12 (P1_2).
  GiNaC::symtab filter_symbols();

  // Validates and returns the model; throws ModelError on the first problem.
  Model build() const;

 private:
  Model model_;
  bool has_drift_ = false;
  bool has_diffusion_ = false;
  bool has_observation_ = false;
  std::vector<GiNaC::symbol> filter_variables_;
};

// Replaces floating-point numerics by exact rationals (see ModelBuilder).
GiNaC::ex exact_rationals(const GiNaC::ex& e);

}  // namespace pfgen
