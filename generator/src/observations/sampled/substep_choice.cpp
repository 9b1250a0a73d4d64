#include "pfgen/observations/sampled/substep_choice.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>

#include "pfgen/algebra/numeric_value.hpp"
#include "pfgen/derivation/closed_expectation.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/notation/number_format.hpp"

namespace pfgen {
namespace {

// The prediction field z' = F(z), z = (m, upper triangle of P, a moment filter's higher moments) in
// FilterVariables' order (m_i is variable i, P_ij variable n + upper_index(i, j)), with its coefficients' values at t = 0 and the
// model file's parameters taken once, in double precision. Sums run over the terms in their stored
// order, so every value is the same in every process.
class NumericField {
 public:
  NumericField(const std::vector<const Polynomial*>& rows, const GiNaC::exmap& values) {
    for (const Polynomial* row : rows) {
      std::vector<Term> terms;
      for (const auto& [monomial, coefficient] : row->terms()) {
        const GiNaC::ex value = numeric_value(coefficient, values);
        // Coefficients hold parameters and t only; one that stays symbolic leaves F unknown.
        const double c = GiNaC::is_a<GiNaC::numeric>(value) ? GiNaC::ex_to<GiNaC::numeric>(value).to_double()
                                                             : std::numeric_limits<double>::quiet_NaN();
        terms.push_back(Term{c, &monomial.factors()});
      }
      rows_.push_back(std::move(terms));
    }
  }

  std::size_t size() const { return rows_.size(); }

  Eigen::VectorXd value(const Eigen::VectorXd& z) const {
    Eigen::VectorXd out(static_cast<Eigen::Index>(rows_.size()));
    for (std::size_t row = 0; row < rows_.size(); ++row) {
      double sum = 0;
      for (const Term& term : rows_[row]) {
        double product = term.c;
        for (const auto& [variable, exponent] : *term.factors) product *= power(z, variable, exponent);
        sum += product;
      }
      out(static_cast<Eigen::Index>(row)) = sum;
    }
    return out;
  }

  // Each term's partial derivatives from the term itself: c a_v z_v^(a_v - 1) times the others.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& z) const {
    const auto d = static_cast<Eigen::Index>(rows_.size());
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(d, d);
    for (std::size_t row = 0; row < rows_.size(); ++row)
      for (const Term& term : rows_[row]) {
        const FactorList& factors = *term.factors;
        for (std::size_t k = 0; k < factors.size(); ++k) {
          double partial = term.c * factors[k].second * power(z, factors[k].first, factors[k].second - 1);
          for (std::size_t l = 0; l < factors.size(); ++l)
            if (l != k) partial *= power(z, factors[l].first, factors[l].second);
          J(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(factors[k].first)) += partial;
        }
      }
    return J;
  }

  // One period T in `substeps` Heun sub-steps from z, as the generated predict() takes them.
  Eigen::VectorXd heun(Eigen::VectorXd z, double T, std::size_t substeps) const {
    const double h = T / static_cast<double>(substeps);
    for (std::size_t s = 0; s < substeps && z.allFinite(); ++s) {
      const Eigen::VectorXd first = value(z);
      const Eigen::VectorXd second = value(z + h * first);
      z += h / 2 * (first + second);
    }
    return z;
  }

 private:
  struct Term {
    double c;
    const FactorList* factors;  // into the FilterEquations' polynomials, which outlive the field
  };
  static double power(const Eigen::VectorXd& z, std::uint32_t variable, std::uint32_t exponent) {
    return exponent == 1 ? z(variable) : std::pow(z(variable), static_cast<double>(exponent));
  }
  std::vector<std::vector<Term>> rows_;
};

// The relative difference of two solutions, block by block (m, then P: their scales differ).
double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b, Eigen::Index n) {
  double worst = 0;
  for (auto [start, length] : {std::pair<Eigen::Index, Eigen::Index>{0, n}, {n, b.size() - n}}) {
    const double scale = b.segment(start, length).norm(), difference = (a - b).segment(start, length).norm();
    worst = std::max(worst, scale > 0 ? difference / scale : difference);
  }
  return std::isfinite(worst) ? worst : std::numeric_limits<double>::infinity();
}

}  // namespace

SubstepAdvice advise_substeps(const Model& model, const FilterEquations& eq) {
  const FilterVariables& vars = eq.variables;
  const std::size_t n = vars.n();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(vars.count()));
  if (model.initial) {
    for (std::size_t i = 0; i < n && i < model.initial->m0.size(); ++i) z(vars.m(i)) = model.initial->m0[i].to_double();
    for (std::size_t i = 0; i < n && i < model.initial->P0.size(); ++i)
      for (std::size_t j = i; j < n && j < model.initial->P0[i].size(); ++j)
        z(vars.P(i, j)) = model.initial->P0[i][j].to_double();
    // A moment filter's higher moments start at the Gaussian prior's.
    if (model.initial->P0.size() == n)
      for (std::size_t q = 0; q < vars.higher_moments().size(); ++q)
        z(vars.first_higher_moment() + q) = gaussian_central_moment(vars.higher_moments()[q], model.initial->P0).to_double();
  }
  GiNaC::exmap values;
  for (const Parameter& p : model.parameters) values[p.symbol] = p.default_value;
  values[model.time] = GiNaC::numeric(0);
  std::vector<Polynomial> P_drift;
  P_drift.reserve(eq.P_moment.size());
  for (std::size_t u = 0; u < eq.P_moment.size(); ++u) P_drift.push_back(eq.P_moment[u] + eq.P_diffusion[u]);
  std::vector<const Polynomial*> rows;
  for (const Polynomial& p : eq.m_drift) rows.push_back(&p);
  for (const Polynomial& p : P_drift) rows.push_back(&p);
  for (const Polynomial& p : eq.higher_drift) rows.push_back(&p);  // a moment filter's
  const NumericField field(rows, values);

  SubstepAdvice advice;
  advice.rate = std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd J = field.jacobian(z);
  if (J.allFinite()) {
    advice.rate = 0;
    const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(J, false).eigenvalues();
    for (Eigen::Index k = 0; k < lambda.size(); ++k) advice.rate = std::max(advice.rate, std::abs(lambda[k]));
  }
  const double period = model.observation.samples()->period.to_double();
  advice.substeps = std::max(1.0, std::ceil(period * advice.rate / kSubstepRateProduct));
  // Then the first period itself, from the prior: doubled until k sub-steps and 2k agree to
  // kSubstepTolerance (the forcing, E[g g^T], can bend the solution where the rate does not say).
  while (advice.substeps <= static_cast<double>(kMaxChosenSubsteps)) {
    const auto k = static_cast<std::size_t>(advice.substeps);
    const double difference =
        relative_difference(field.heun(z, period, k), field.heun(z, period, 2 * k), static_cast<Eigen::Index>(n));
    if (difference <= kSubstepTolerance) break;
    advice.substeps *= 2;
  }
  return advice;
}

void set_prediction_substeps(const Model& model, FilterEquations& eq) {
  const SampleTimes& sampled = *model.observation.samples();
  const SubstepAdvice advice = advise_substeps(model, eq);
  eq.update.prior_rate = advice.rate;
  eq.update.advised_substeps = advice.substeps;
  if (sampled.substeps) {
    eq.update.substeps = *sampled.substeps;
    return;
  }
  if (!(advice.substeps <= static_cast<double>(kMaxChosenSubsteps))) {
    ModelError error("observation.sampled",
                     "substeps not given, and filter '" + eq.name + "''s prediction from the prior (rate " +
                         three_digits(advice.rate) + " per unit of time) needs more than " +
                         std::to_string(kMaxChosenSubsteps) + " sub-steps of the period T = " +
                         three_digits(sampled.period.to_double()) + ": give substeps, or a shorter period");
    error.set_file(model.source);
    throw error;
  }
  eq.update.substeps = static_cast<std::size_t>(advice.substeps);
  eq.update.substeps_chosen = true;
}

}  // namespace pfgen
