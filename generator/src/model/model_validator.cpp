#include "pfgen/model/model_validator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "pfgen/algebra/numeric_value.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/expansion_bound.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/polynomial_shape.hpp"
#include "pfgen/model/reserved_names.hpp"
#include "pfgen/model/simulation_rules.hpp"
#include "pfgen/model/text_characters.hpp"
#include "pfgen_support/shortest_double.hpp"
#include "pfgen/notation/number_format.hpp"
#include "pfgen/notation/text_printer.hpp"

namespace pfgen {
namespace {

// An eigenvalue in a message: std::to_string's six decimals, as the messages have always shown,
// unless that would print hundreds of digits (1e200).
std::string eigenvalue_text(double value) { return pfgen_support::fixed_unless_huge(value); }

// In the canonical order of pfgen's printer: GiNaC's own varies from run to run.
std::string to_text(const GiNaC::ex& e) { return TextPrinter().print(e); }

// Row and column are reported 1-based, as a user counts them in the file.
std::optional<int> one_based(std::size_t index) { return static_cast<int>(index + 1); }

// The closure's moments grow with the degree: x^(10^10) must be refused, not exhaust memory.
constexpr int kMaxDegree = 1000;

// The powers in e whose exponent is a number beyond the degree limit, found in one walk of e
// (not one per state: a dense model's drift entry has thousands of terms).
std::vector<GiNaC::ex> huge_powers(const GiNaC::ex& e) {
  std::vector<GiNaC::ex> found;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::power>(*it) && GiNaC::is_a<GiNaC::numeric>(it->op(1)) &&
        GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(it->op(1))) > GiNaC::numeric(kMaxDegree))
      found.push_back(*it);
  return found;
}

void require_bounded_degree(const GiNaC::ex& e, const std::vector<GiNaC::ex>& huge, const GiNaC::symbol& variable,
                            const std::string& what, const std::string& field, std::optional<int> row,
                            std::optional<int> column) {
  int degree = kMaxDegree + 1;
  // GiNaC's degree() wraps an exponent beyond int's range (x^(83^10) gave a negative degree, which
  // passed, and the expectation's recursion then overflowed the stack): compare exponents exactly.
  bool huge_exponent = false;
  for (const GiNaC::ex& power : huge)
    if (power.op(0).has(variable)) huge_exponent = true;
  try {
    if (!huge_exponent) degree = e.degree(variable);
  } catch (const std::exception&) {
    // The exponent does not even fit an int.
  }
  if (degree > kMaxDegree)
    throw ModelError(field,
                     "'" + to_text(e) + "' has a degree in " + what + " above the limit of " +
                         std::to_string(kMaxDegree),
                     row, column);
}

// Before anything expands it (the symmetry check, G = g g^T, the derivation).
void require_bounded_expansion(const GiNaC::ex& e, const std::string& field, std::optional<int> row,
                               std::optional<int> column, const std::string& what = "") {
  const double terms = expanded_terms_bound(e);
  if (terms > kMaxExpandedTerms)
    throw ModelError(field,
                     (what.empty() ? "'" + to_text(e) + "'" : what) + " would expand to " +
                         "up to " + count_text(terms) + " terms, above the limit of " + count_text(kMaxExpandedTerms),
                     row, column);
}

// The degree check of one variable, on a shape already found (polynomial_shape).
void require_degree_within_limit(const GiNaC::ex& e, std::int64_t degree, const std::string& what,
                                 const std::string& field, std::optional<int> row, std::optional<int> column) {
  if (degree > kMaxDegree)
    throw ModelError(field,
                     "'" + to_text(e) + "' has a degree in " + what + " above the limit of " +
                         std::to_string(kMaxDegree),
                     row, column);
}

void require_polynomial(const Model& model, const GiNaC::ex& e, const std::string& field,
                        std::optional<int> row, std::optional<int> column) {
  const PolynomialShape shape = polynomial_shape(e, model.states, kMaxDegree);
  if (!shape.polynomial)
    throw ModelError(field,
                     "'" + to_text(e) + "' is not polynomial in the states (only non-negative "
                     "integer powers of states are allowed; sin(x), 1/x, x^0.5 are not)",
                     row, column);
  for (std::size_t k = 0; k < model.states.size(); ++k)
    require_degree_within_limit(e, shape.degrees[k], "state '" + model.state_names[k] + "'", field, row, column);
  require_bounded_expansion(e, field, row, column);
}

void require_state_free(const Model& model, const GiNaC::ex& e, const std::string& field,
                        std::optional<int> row, std::optional<int> column) {
  if (depends_on_states(model, e))
    throw ModelError(field, "'" + to_text(e) + "' must not depend on the states", row, column);
  require_bounded_expansion(e, field, row, column);
}

void require_shape(const ExMatrix& m, std::size_t rows, std::optional<std::size_t> columns,
                   const std::string& field, const std::string& what) {
  if (m.size() != rows)
    throw ModelError(field, "expected " + std::to_string(rows) + " rows (" + what + "), found " +
                                std::to_string(m.size()));
  std::size_t width = columns ? *columns : (m.empty() ? 0 : m[0].size());
  if (width == 0) throw ModelError(field, "rows must not be empty", 1);
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m[i].size() != width)
      throw ModelError(field,
                       "expected " + std::to_string(width) + " columns" + (columns ? " (" + what + ")" : "") +
                           ", found " + std::to_string(m[i].size()),
                       one_based(i));
  }
}

// Numeric value at the parameters' defaults and t = 0.
GiNaC::ex at_defaults(const Model& model, const GiNaC::ex& e) {
  GiNaC::exmap values;
  for (const auto& p : model.parameters) values[p.symbol] = p.default_value;
  values[model.time] = 0;
  return numeric_value(e, values).evalf();
}

void validate_names(const Model& model) {
  if (auto problem = identifier_problem(model.name)) throw ModelError("name", *problem);
  if (auto problem = namespace_name_problem(model.name)) throw ModelError("name", *problem);
  if (auto problem = name_part_problem(model.name)) throw ModelError("name", *problem);
  if (model.states.empty()) throw ModelError("states", "at least one state is required");
  std::set<std::string> seen;
  const std::string time = model.time.get_name();
  auto check = [&](const std::string& name, const std::string& field, std::optional<int> index) {
    if (auto problem = identifier_problem(name)) throw ModelError(field, *problem, index);
    // Time is named first, so a state or parameter named like it is the one to rename (the
    // message named field 'time', which a user who kept the default t never wrote).
    if (field != "time" && name == time)
      throw ModelError(field, "'" + name + "' is the name of time (" +
                                  (time == "t" ? "t unless the field `time:` names it otherwise" : "field `time:`") +
                                  "); give this one another name",
                       index);
    if (auto problem = symbol_name_problem(name)) throw ModelError(field, *problem, index);
    if (!seen.insert(name).second)
      throw ModelError(field, "name '" + name + "' is used twice", index);
  };
  check(time, "time", std::nullopt);
  for (std::size_t i = 0; i < model.state_names.size(); ++i)
    check(model.state_names[i], "states", one_based(i));
  for (const auto& p : model.parameters) check(p.name, "parameters." + p.name, std::nullopt);
}

// A number a double holds, as every number in an expression must be (expression_parser): 1e-310
// would be 0 in eval, the generated code and simulate, 1e400 infinite.
void require_double_range(const GiNaC::numeric& value, const std::string& field, std::optional<int> row = {},
                          std::optional<int> column = {}) {
  if (auto problem = double_range_problem(value))
    throw ModelError(field, "the value, about " + approximate_text(value) + ", " + *problem, row, column);
}

void validate_numbers(const Model& model) {
  for (const auto& p : model.parameters) require_double_range(p.default_value, "parameters." + p.name);
  if (!model.initial) return;
  const InitialConditions& init = *model.initial;
  for (std::size_t i = 0; i < init.x0.size(); ++i) require_double_range(init.x0[i], "initial.x0", one_based(i));
  for (std::size_t i = 0; i < init.m0.size(); ++i) require_double_range(init.m0[i], "initial.m0", one_based(i));
  for (std::size_t i = 0; i < init.P0.size(); ++i)
    for (std::size_t j = 0; j < init.P0[i].size(); ++j)
      require_double_range(init.P0[i][j], "initial.P0", one_based(i), one_based(j));
}

void validate_diffusion(const Model& model, const Diffusion& d, const std::string& g_field,
                        const std::string& G_field, bool must_be_state_free) {
  std::size_t n = model.n();
  if (d.g) {
    require_shape(*d.g, n, std::nullopt, g_field, "one per state");
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < (*d.g)[i].size(); ++j) {
        require_polynomial(model, (*d.g)[i][j], g_field, one_based(i), one_based(j));
        if (must_be_state_free)
          require_state_free(model, (*d.g)[i][j], g_field, one_based(i), one_based(j));
      }
    // The model's G = g g^T is expanded entry by entry.
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) {
        GiNaC::ex entry = 0;
        for (std::size_t k = 0; k < (*d.g)[i].size(); ++k) entry += (*d.g)[i][k] * (*d.g)[j][k];
        require_bounded_expansion(entry, g_field, one_based(i), std::nullopt,
                                  "entry (" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") of g g^T");
      }
    return;
  }
  require_shape(d.G, n, n, G_field, "G = g g^T must be square, n x n with n = number of states");
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      require_polynomial(model, d.G[i][j], G_field, one_based(i), one_based(j));
      if (must_be_state_free)
        require_state_free(model, d.G[i][j], G_field, one_based(i), one_based(j));
    }
  // Symmetry only once every entry is known to be a polynomial of bounded degree.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!(d.G[i][j] - d.G[j][i]).expand().is_zero())
        throw ModelError(G_field,
                         "not symmetric: entry (" + std::to_string(i + 1) + "," +
                             std::to_string(j + 1) + ") is '" + to_text(d.G[i][j]) +
                             "' but entry (" + std::to_string(j + 1) + "," +
                             std::to_string(i + 1) + ") is '" + to_text(d.G[j][i]) + "'",
                         one_based(i), one_based(j));
    }
  // A covariance that depends on neither the states nor t must be positive semi-definite: a
  // negative one was accepted and the truth then ran with zero noise in its place.
  bool constant = true;
  for (const auto& row : d.G)
    for (const auto& e : row) constant = constant && !depends_on_states(model, e) && !e.has(model.time);
  if (!constant) return;
  Eigen::MatrixXd G(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const GiNaC::ex value = at_defaults(model, d.G[i][j]);
      if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real()) return;
      G(i, j) = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
    }
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(G).eigenvalues().minCoeff();
  if (smallest < -1e-12 * std::max(1.0, G.cwiseAbs().maxCoeff()))
    throw ModelError(G_field, "not positive semi-definite at the parameter defaults (smallest eigenvalue " +
                                  eigenvalue_text(smallest) + "): a covariance cannot be negative");
}

// N N^T must be positive definite: numerically, at the parameters' defaults and t = 0. `name` is
// the matrix's name in messages (B, Uv), `field` its place in the model file.
void require_positive_definite_noise(const Model& model, const ExMatrix& N, const std::string& field,
                                     const std::string& name) {
  const std::size_t p = N.size();
  const std::string NNt = name + " " + name + "^T";
  Eigen::MatrixXd R(p, p);
  ExMatrix Rsym = multiply_by_transpose(N);
  std::vector<bool> exact_zero_diagonal(p, false);
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t j = 0; j < p; ++j) {
      GiNaC::ex value = at_defaults(model, Rsym[i][j]);
      if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
        throw ModelError(field, NNt + " entry (" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                                    ") is not a real number at the parameter defaults");
      R(i, j) = GiNaC::ex_to<GiNaC::numeric>(value).to_double();
      if (i == j) exact_zero_diagonal[i] = value.is_zero();
    }
  if (!R.allFinite())
    throw ModelError(field, NNt + " overflows double at the parameter values (an entry is beyond about 1.8e308): "
                            "the noise is too large for the filters to compute with");
  for (std::size_t i = 0; i < p; ++i)
    if (R(i, i) <= 0)
      // A row of tiny entries (1e-300) is not zero, but its squared norm is 0 in double.
      throw ModelError(field,
                       std::string(exact_zero_diagonal[i] ? "row is zero"
                                                          : "row is too small: its squared norm is 0 in double") +
                           " at the parameter defaults and t = 0, so observation " + std::to_string(i + 1) +
                           " has no noise and " + NNt + " is not positive definite",
                       one_based(i));
  Eigen::LLT<Eigen::MatrixXd> cholesky(R);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(R);
  if (cholesky.info() != Eigen::Success || eigen.eigenvalues().minCoeff() <= 1e-12 * std::max(1.0, R.stableNorm()))
    throw ModelError(field,
                     NNt + " is not positive definite (smallest eigenvalue " +
                         eigenvalue_text(eigen.eigenvalues().minCoeff()) +
                         " at the parameter defaults and t = 0); every observation needs its own noise");
}

// The model file's names of the rate's fields, which depend on the timing: dy's A0, A, h and B,
// or the samples' C0, C, c and Uv (and `p x n` or `r x n` in the shape's words).
struct RateFields {
  std::string constant, linear, rows, noise, noise_name, count;
};

RateFields rate_fields(bool sampled) {
  if (sampled)
    return {"observation.sampled.C0", "observation.sampled.C", "observation.sampled.c", "observation.sampled.Uv", "Uv", "r"};
  return {"observation.A0", "observation.A", "observation.h", "observation.B", "B", "p"};
}

// The last name of a field: "C" of "observation.sampled.C".
std::string short_name(const std::string& field) { return field.substr(field.rfind('.') + 1); }

void require_state_free_noise(const Model& model, const ExMatrix& noise, const RateFields& fields, std::size_t i) {
  for (std::size_t j = 0; j < noise[i].size(); ++j)
    require_state_free(model, noise[i][j], fields.noise, one_based(i), one_based(j));
}

// A rate written as rows h_r(x, t) (a sample's c): polynomials in the states.
void validate_rate_rows(const Model& model, const ObservationRate& rate, const RateFields& fields, bool sampled) {
  const std::size_t p = rate.p();
  if (!sampled && p == 0) throw ModelError(fields.rows, "at least one observation is required");
  for (std::size_t i = 0; i < p; ++i) require_polynomial(model, rate.rows()[i], fields.rows, one_based(i), std::nullopt);
  if (p == 0) throw ModelError(fields.linear, "at least one observation row is required");
  require_shape(rate.noise(), p, std::nullopt, fields.noise, "one per observation, as in " + short_name(fields.rows));
  for (std::size_t i = 0; i < rate.noise().size(); ++i) require_state_free_noise(model, rate.noise(), fields, i);
}

// A rate written A0 + A x (a sample's C0 + C x): coefficients free of the states.
void validate_rate_affine(const Model& model, const ObservationRate& rate, const RateFields& fields) {
  const AffineRate& affine = *rate.affine();
  const std::size_t p = affine.A.size();
  const std::string linear = short_name(fields.linear);
  if (p == 0) throw ModelError(fields.linear, "at least one observation row is required");
  require_shape(affine.A, p, model.n(), fields.linear, fields.count + " x n with n = number of states");
  if (affine.A0.size() != p)
    throw ModelError(fields.constant, "expected " + std::to_string(p) + " entries (one per row of " + linear +
                                          "), found " + std::to_string(affine.A0.size()));
  require_shape(rate.noise(), p, std::nullopt, fields.noise, "one per observation, as in " + linear);
  for (std::size_t i = 0; i < p; ++i) {
    require_state_free(model, affine.A0[i], fields.constant, one_based(i), std::nullopt);
    for (std::size_t j = 0; j < affine.A[i].size(); ++j)
      require_state_free(model, affine.A[i][j], fields.linear, one_based(i), one_based(j));
    require_state_free_noise(model, rate.noise(), fields, i);
  }
}

void validate_sample_times(const SampleTimes& samples) {
  const std::string field = "observation.sampled";
  if (!(samples.period > 0)) throw ModelError(field + ".period", "must be positive, found " + to_text(samples.period));
  if (samples.substeps && *samples.substeps < 1)
    throw ModelError(field + ".substeps", "must be at least 1 (1 sub-step: predict over the whole period)");
}

// Each axis checked once: the timing's period, the delay, then the rate in the timing's names.
void validate_observation(const Model& model) {
  const ObservationModel& observation = model.observation;
  if (observation.samples()) validate_sample_times(*observation.samples());
  if (observation.delay() < 0)
    throw ModelError("observation.delay", "must be 0 or more (the delay h of dy = (A0 + A x(t - h)) dt + B dW2), found " +
                                              to_text(observation.delay()));
  const RateFields fields = rate_fields(observation.samples().has_value());
  if (observation.rate().written_affine())
    validate_rate_affine(model, observation.rate(), fields);
  else
    validate_rate_rows(model, observation.rate(), fields, observation.samples().has_value());
  require_positive_definite_noise(model, observation.rate().noise(), fields.noise, fields.noise_name);
}

// A symmetric matrix of numbers (P0, the risk weight) with no eigenvalue below -1e-12 of its scale.
void require_positive_semidefinite(const Eigen::MatrixXd& m, const std::string& field) {
  const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(m).eigenvalues().minCoeff();
  if (smallest < -1e-12 * std::max(1.0, m.norm()))
    throw ModelError(field, "not positive semi-definite (smallest eigenvalue " + eigenvalue_text(smallest) + ")");
}

void validate_initial(const Model& model) {
  if (!model.initial) return;
  const InitialConditions& init = *model.initial;
  std::size_t n = model.n();
  if (!init.x0.empty() && init.x0.size() != n)
    throw ModelError("initial.x0", "expected " + std::to_string(n) + " entries, found " +
                                       std::to_string(init.x0.size()));
  if (init.m0.size() != n)
    throw ModelError("initial.m0", "expected " + std::to_string(n) + " entries, found " +
                                       std::to_string(init.m0.size()));
  if (init.P0.size() != n)
    throw ModelError("initial.P0", "expected " + std::to_string(n) + " rows, found " +
                                       std::to_string(init.P0.size()));
  Eigen::MatrixXd P(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    if (init.P0[i].size() != n)
      throw ModelError("initial.P0", "expected " + std::to_string(n) + " columns, found " +
                                         std::to_string(init.P0[i].size()),
                       one_based(i));
    for (std::size_t j = 0; j < n; ++j) P(i, j) = init.P0[i][j].to_double();
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (init.P0[i][j] != init.P0[j][i])
        throw ModelError("initial.P0", "not symmetric", one_based(i), one_based(j));
  // Positive semi-definite, not definite: paper 001 starts from a singular P0.
  require_positive_semidefinite(P, "initial.P0");
}

// The risk criterion's epsilon and weight are numbers or expressions of the parameters: simulate
// evaluates them with the parameters' values. At the defaults epsilon must be positive and the
// weight symmetric positive semi-definite (simulate checks the values it is given by --set).
void validate_risk(const Model& model) {
  if (!model.risk) return;
  const RiskCriterion& risk = *model.risk;
  auto value_of = [&](const GiNaC::ex& e, const std::string& field, std::optional<int> row,
                         std::optional<int> column) {
    require_state_free(model, e, field, row, column);
    if (e.has(model.time))
      throw ModelError(field, "'" + to_text(e) + "' must not depend on the time", row, column);
    GiNaC::ex value = at_defaults(model, e);
    if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_real())
      throw ModelError(field, "'" + to_text(e) + "' is not a real number at the parameters' values", row, column);
    return GiNaC::ex_to<GiNaC::numeric>(value).to_double();
  };
  const double epsilon = value_of(risk.epsilon, "risk.epsilon", std::nullopt, std::nullopt);
  if (!(epsilon > 0)) {
    if (GiNaC::is_a<GiNaC::numeric>(risk.epsilon))
      throw ModelError("risk.epsilon", "must be a number greater than 0, found " + to_text(risk.epsilon));
    throw ModelError("risk.epsilon", "'" + to_text(risk.epsilon) + "' is " + to_text(at_defaults(model, risk.epsilon)) +
                                         " at the parameters' values; it must be greater than 0");
  }
  if (risk.weight.empty()) return;
  const std::size_t n = model.n();
  require_shape(risk.weight, n, n, "risk.weight", "n x n, one per state");
  Eigen::MatrixXd M(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      M(i, j) = value_of(risk.weight[i][j], "risk.weight", one_based(i), one_based(j));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (!(risk.weight[i][j] - risk.weight[j][i]).expand().is_zero())
        throw ModelError("risk.weight", "not symmetric", one_based(i), one_based(j));
  require_positive_semidefinite(M, "risk.weight");
}

// A double as the user wrote it, near enough: shortest round-trip is not needed in messages.
void require_polynomial_in(const std::vector<GiNaC::symbol>& variables, const GiNaC::ex& e, const std::string& field,
                           std::optional<int> row, std::optional<int> column) {
  const PolynomialShape shape = polynomial_shape(e, variables, kMaxDegree);
  if (!shape.polynomial)
    throw ModelError(field,
                     "'" + to_text(e) + "' is not polynomial in the filter's m and P entries (only non-negative "
                     "integer powers of m1, P11, ... are allowed; name a quotient such as 1/P11 under `define:` "
                     "and use the name)",
                     row, column);
  for (std::size_t k = 0; k < variables.size(); ++k)
    require_degree_within_limit(e, shape.degrees[k], "'" + variables[k].get_name() + "'", field, row, column);
  require_bounded_expansion(e, field, row, column);
}

void validate_user_filter_entry(const Model& model, const UserFilter& filter, const GiNaC::ex& e,
                                const std::string& field, std::optional<int> row, std::optional<int> column) {
  if (depends_on_states(model, e))
    throw ModelError(field,
                     "'" + to_text(e) + "' depends on the states; a filter is written in its own variables "
                     "(m1, P11, ...), t and the parameters",
                     row, column);
  if (!filter.definitions.empty()) {
    // A definition may stand for anything of m and P, so its powers are bounded as a variable's.
    const std::vector<GiNaC::ex> huge = huge_powers(e);
    for (const auto& d : filter.definitions)
      require_bounded_degree(e, huge, d.name, "'" + d.name.get_name() + "'", field, row, column);
  }
  require_polynomial_in(filter.variables, e, field, row, column);
}

// A user filter's `define:` (FilterDefinition): each name clear of the model's names, of the
// names the printed equations use and of the earlier definitions; each value free of the states
// and reading only the filter's variables, the parameters, t and the names defined before it
// (so the values can be computed in file order, once per evaluation).
void validate_filter_definitions(const Model& model, const UserFilter& filter, const std::string& field) {
  std::set<std::string> taken(model.state_names.begin(), model.state_names.end());
  taken.insert(model.time.get_name());
  std::set<GiNaC::ex, GiNaC::ex_is_less> readable(filter.variables.begin(), filter.variables.end());
  readable.insert(model.time);
  for (const auto& p : model.parameters) {
    taken.insert(p.name);
    readable.insert(p.symbol);
  }
  for (const auto& d : filter.definitions) {
    const std::string name = d.name.get_name();
    const std::string entry = field + ".define." + name;
    if (auto problem = identifier_problem(name)) throw ModelError(entry, *problem);
    if (auto problem = symbol_name_problem(name)) throw ModelError(entry, *problem);
    if (!taken.insert(name).second)
      throw ModelError(entry, "'" + name + "' is already a name of the model or an earlier definition of this filter");
    if (depends_on_states(model, d.value))
      throw ModelError(entry, "'" + to_text(d.value) + "' depends on the states; a definition is written in the "
                              "filter's variables (m1, P11, ...), t, the parameters and earlier definitions");
    for (auto it = d.value.preorder_begin(); it != d.value.preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it) && !readable.count(*it))
        throw ModelError(entry, "reads '" + to_text(*it) + "', which is not defined before it");
    if (!huge_powers(d.value).empty())
      throw ModelError(entry, "'" + to_text(d.value) + "' has a power beyond " + std::to_string(kMaxDegree));
    require_bounded_expansion(d.value, entry, std::nullopt, std::nullopt);
    readable.insert(d.name);
  }
}

void validate_user_filters(const Model& model) {
  const std::size_t n = model.n();
  const std::vector<std::string> names = filter_variable_names(n);
  const std::regex filter_name("^[A-Za-z][A-Za-z0-9_-]*$");
  // Every C++ identifier taken so far, with the filter that took it (file names
  // <identifier>.hpp and <identifier>_eigen.hpp derive from it too).
  std::map<std::string, std::string> identifiers;
  for (const auto& builtin : filter_kinds()) identifiers[filter_identifier(builtin.name)] = builtin.name;
  if (model.observation.is_sampled() && !model.user_filters.empty())
    throw ModelError("filters." + model.user_filters.front().name,
                     "a filter given by its equations is a continuous-observation filter (dm = ... + gain (dy - ...)); "
                     "this model's observation is sampled");
  if (!model.observation.rate().written_affine() && !model.user_filters.empty())
    throw ModelError("filters." + model.user_filters.front().name,
                     "a filter given by its equations has no dy term in dP, which a polynomial observation's "
                     "filters have; write the observation as A0 + A x, or drop filters:");
  for (const UserFilter& filter : model.user_filters) {
    const std::string field = "filters." + filter.name;
    if (!std::regex_match(filter.name, filter_name))
      throw ModelError(field, "'" + filter.name +
                                  "' is not a filter name (a letter, then letters, digits, '_' or '-')");
    if (parse_filter_kind(filter.name))
        throw ModelError(field, "'" + filter.name + "' is a built-in filter kind; give the model's filter another name");
    const std::string identifier = filter_identifier(filter.name);
    if (auto problem = namespace_name_problem(identifier)) throw ModelError(field, *problem);
    if (auto problem = name_part_problem(identifier)) throw ModelError(field, *problem);
    for (const auto& [taken, owner] : identifiers) {
      if (taken == identifier)
        throw ModelError(field, "its C++ identifier '" + identifier + "' is also that of filter '" + owner + "'");
      if (identifier == taken + "_eigen" || taken == identifier + "_eigen")
        throw ModelError(field, "its C++ identifier '" + identifier + "' would clash with filter '" + owner +
                                    "' in the file names of `pfgen codegen --eigen` (<name>_eigen.hpp)");
    }
    identifiers[identifier] = filter.name;
    for (char c : filter.description)
      if (static_cast<unsigned char>(c) < 0x20)
        throw ModelError(field + ".description", "must be one line of text (no line breaks or control characters)");

    std::vector<std::string> given;
    for (const auto& v : filter.variables) given.push_back(v.get_name());
    if (given != names)
      throw ModelError(field, "the filter's variables must be m1..m" + std::to_string(n) +
                                  " and the upper triangle of P (" + names.back() + " last), " +
                                  std::to_string(names.size()) + " symbols, found " + std::to_string(given.size()));
    validate_filter_definitions(model, filter, field);
    const std::string m_field = field + ".m_drift";
    if (filter.m_drift.size() != n)
      throw ModelError(m_field, "expected " + std::to_string(n) + " entries (one per state), found " +
                                    std::to_string(filter.m_drift.size()));
    for (std::size_t i = 0; i < n; ++i)
      validate_user_filter_entry(model, filter, filter.m_drift[i], m_field, one_based(i), std::nullopt);
    const std::string P_field = field + ".P_drift";
    require_shape(filter.P_drift, n, n, P_field, "P_drift is n x n with n = number of states");
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        validate_user_filter_entry(model, filter, filter.P_drift[i][j], P_field, one_based(i), one_based(j));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (!(filter.P_drift[i][j] - filter.P_drift[j][i]).expand().is_zero())
          throw ModelError(P_field,
                           "not symmetric: entry (" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
                               ") is '" + to_text(filter.P_drift[i][j]) + "' but entry (" + std::to_string(j + 1) +
                               "," + std::to_string(i + 1) + ") is '" + to_text(filter.P_drift[j][i]) + "'",
                           one_based(i), one_based(j));
    const std::string K_field = field + ".gain";
    require_shape(filter.gain, n, model.p(), K_field, "gain is n x p: one row per state, one column per observation");
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t r = 0; r < model.p(); ++r)
        validate_user_filter_entry(model, filter, filter.gain[i][r], K_field, one_based(i), one_based(r));
  }
}

// The rules live in simulation_rules.cpp, shared with the command line.
void validate_simulation(const Model& model) {
  if (auto breach = check_simulation_settings(model, model.simulation))
    throw ModelError("simulation." + breach->field, breach->message,
                     breach->entry ? one_based(*breach->entry) : std::nullopt);
}

}  // namespace

bool is_valid_identifier(const std::string& name) {
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

std::optional<std::string> identifier_problem(const std::string& name) {
  if (is_valid_identifier(name)) return std::nullopt;
  const std::string rule = "ASCII letters, digits and _, not starting with a digit";
  if (auto character = first_non_ascii(name))
    return "'" + name + "' is not an identifier: it contains " + *character + " (" + rule + ")";
  return "'" + name + "' is not an identifier (" + rule + ")";
}

// bounds: each entry a parameter, once, with low < high and its default inside.
void validate_bounds(const Model& model) {
  std::set<std::string> seen;
  for (const ParameterBound& bound : model.bounds) {
    const std::string field = "bounds." + bound.name;
    const auto parameter = std::find_if(model.parameters.begin(), model.parameters.end(),
                                        [&](const Parameter& p) { return p.name == bound.name; });
    if (parameter == model.parameters.end()) throw ModelError(field, "'" + bound.name + "' is not a parameter");
    if (!seen.insert(bound.name).second) throw ModelError(field, "given twice");
    if (bound.low && bound.high && !(*bound.low < *bound.high))
      throw ModelError(field, "the low end is not below the high end");
    const GiNaC::numeric& value = parameter->default_value;
    if ((bound.low && value < *bound.low) || (bound.high && value > *bound.high))
      throw ModelError(field, "the bounds exclude the parameter's value " + pfgen_support::shortest_chars(value.to_double()));
  }
}

void validate_model(const Model& model) {
  validate_names(model);
  validate_numbers(model);
  std::size_t n = model.n();
  if (model.drift.size() != n)
    throw ModelError("drift", "expected " + std::to_string(n) + " entries (one per state), found " +
                                  std::to_string(model.drift.size()));
  for (std::size_t i = 0; i < n; ++i) require_polynomial(model, model.drift[i], "drift", one_based(i), std::nullopt);
  validate_diffusion(model, model.diffusion, "diffusion", "diffusion_covariance", false);
  if (model.noise == NoiseCalculus::Stratonovich && !model.diffusion.g)
    throw ModelError("noise", "stratonovich needs the diffusion as g (field `diffusion:`): the Ito correction "
                              "1/2 sum g_jk dg_ik/dx_j reads g itself, which diffusion_covariance G = g g^T does not "
                              "determine");
  if (model.additive_diffusion)
    validate_diffusion(model, *model.additive_diffusion, "additive_diffusion",
                       "additive_diffusion_covariance", true);
  validate_observation(model);
  validate_initial(model);
  validate_risk(model);
  validate_user_filters(model);
  validate_simulation(model);
  validate_bounds(model);
}

}  // namespace pfgen
