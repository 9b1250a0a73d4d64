#include "pfgen/kinds/filter_kinds.hpp"

#include <algorithm>
#include <stdexcept>

namespace pfgen {

const std::vector<FilterKindInfo>& filter_kinds() {
  using E = ExpectationRule;
  using D = DiffusionSource;
  const std::vector<ObservationKind> continuous = {ObservationKind::Continuous};
  // The Gaussian-closure and extended kinds read the observation through its module: they are
  // derived for polynomial observations too.
  const std::vector<ObservationKind> rate = {ObservationKind::Continuous, ObservationKind::Polynomial};
  const std::vector<ObservationKind> sampled = {ObservationKind::Sampled};
  const std::vector<ObservationKind> delayed = {ObservationKind::Delayed};
  static const std::vector<FilterKindInfo> kinds = {
      {FilterKind::Optimal, "optimal",
       "Gaussian-closure optimal filter: $E[f]|E[f]$, $E[(x-m)f^T] + E[f(x-m)^T]|E[(x-m)f^{T}] + E[f(x-m)^{T}]$, "
       "$E[g g^T]|E[g\\,g^{T}]$ expanded exactly",
       E::Gaussian, D::Model, rate},
      {FilterKind::Ekf, "ekf", "extended Kalman-Bucy filter (textbook): $f(m)|f(m)$, Jacobian of $f|f$ at $m|m$, "
       "$g(m) g(m)^T|g(m)\\,g(m)^{T}$",
       E::AtMean, D::Model, rate},
      {FilterKind::Additive, "additive",
       "Gaussian-closure filter with the model's additive (state-independent) diffusion in place of $g|g$",
       E::Gaussian, D::Additive, rate},
      {FilterKind::EkfAdditive, "ekf-additive",
       "extended Kalman-Bucy filter with the model's additive (state-independent) diffusion in place of $g|g$",
       E::AtMean, D::Additive, rate},
      {FilterKind::CdOptimal, "cd-optimal",
       "continuous-discrete Gaussian-closure filter: the closed moment ODEs between samples, Kalman update at each",
       E::Gaussian, D::Model, sampled, Prediction::Ode},
      {FilterKind::CdEkf, "cd-ekf",
       "continuous-discrete extended Kalman filter: $f(m)|f(m)$, Jacobian at $m|m$, $g(m) g(m)^T|g(m)\\,g(m)^{T}$ "
       "between samples, Kalman update",
       E::AtMean, D::Model, sampled, Prediction::Ode},
      {FilterKind::CdEuler, "cd-euler",
       "exact Gaussian-closure moments of the Euler-discretised model per sub-step, Kalman update (Allahyani & Date's CDF)",
       E::Gaussian, D::Model, sampled, Prediction::EulerMap},
      {FilterKind::DelayOptimal, "delay-optimal",
       "Gaussian-closure filter for delayed observations: gain $P Phi*^T A^T R^-1|P\\,\\Phi^{*T} A^{T} R^{-1}$ with "
       "$Phi* = diag(x*(t-h)/x*(t))|\\Phi^{*} = \\operatorname{diag}\\bigl(x^{*}(t-h)/x^{*}(t)\\bigr)$ of "
       "the noise-free $x*|x^{*}$, innovation $dy - (A0 + A m(t-h)) dt|dy - (A_0 + A\\,m(t-h))\\,dt$ "
       "(Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004)",
       E::Gaussian, D::Model, delayed, Prediction::Ode, DelayGain::Transition},
      {FilterKind::DelayUncorrected, "delay-uncorrected",
       "Gaussian-closure filter with the undelayed gain $P A^T R^-1|P A^{T} R^{-1}$ and the delayed innovation "
       "$dy - (A0 + A m(t-h)) dt|dy - (A_0 + A\\,m(t-h))\\,dt$",
       E::Gaussian, D::Model, delayed, Prediction::Ode, DelayGain::Undelayed},
      {FilterKind::DelayEkf, "delay-ekf",
       "extended Kalman-Bucy filter (textbook) with the delayed innovation "
       "$dy - (A0 + A m(t-h)) dt|dy - (A_0 + A\\,m(t-h))\\,dt$",
       E::AtMean, D::Model, delayed, Prediction::Ode, DelayGain::Undelayed},
      {FilterKind::RiskSensitive, "risk-sensitive",
       "risk-sensitive filter for the model's risk: criterion $J|J$ (Alcorta-Garcia et al. 2011): "
       "$f(m) - P grad(div f)(m)|f(m) - P\\,\\nabla(\\operatorname{div} f)(m)$, Jacobian at $m|m$, and "
       "$-P (Hess(div f)(m) - (2/eps) M) P|-P\\bigl(\\nabla^{2}(\\operatorname{div} f)(m) - \\tfrac{2}{\\varepsilon} M\\bigr)P$ "
       "in $dP|dP$; LEQG for linear models",
       E::AtMean, D::Model, continuous, Prediction::Ode, DelayGain::Undelayed, Criterion::RiskSensitive},
      {FilterKind::Ukf, "ukf",
       "unscented Kalman-Bucy filter (Sarkka 2007): $E[f]|E[f]$, $E[(x-m)f^T]|E[(x-m)f^{T}]$, $E[g g^T]|E[g\\,g^{T}]$ "
       "as weighted sums over the $2n+1|2n+1$ sigma points $m, m +- sqrt(c) L_j|m, m \\pm \\sqrt{c}\\,L_j$, $L|L$ the "
       "Cholesky factor of $P|P$; opt-in (not among the defaults)",
       E::SigmaPoints, D::Model, rate, Prediction::Ode, DelayGain::Undelayed, Criterion::MeanSquare,
       /*in_defaults=*/false},
      // The moment filters (docs/theory.md §2.10); opt-in like the ukf, so that every default output stays.
      {FilterKind::Closure3, "closure3",
       "moment filter of order 3: $m|m$, $P|P$ and the third central moments $E[(x-m)_i (x-m)_j (x-m)_l]|"
       "E[(x-m)_i (x-m)_j (x-m)_l]$, every cumulant of order > 3 set to zero; opt-in (not among the defaults)",
       E::CumulantNeglect, D::Model, rate, Prediction::Ode, DelayGain::Undelayed, Criterion::MeanSquare,
       /*in_defaults=*/false, /*closure_order=*/3},
      {FilterKind::Closure4, "closure4",
       "moment filter of order 4: $m|m$, $P|P$ and the central moments of orders 3 and 4, every cumulant of "
       "order > 4 set to zero; opt-in (not among the defaults)",
       E::CumulantNeglect, D::Model, rate, Prediction::Ode, DelayGain::Undelayed, Criterion::MeanSquare,
       /*in_defaults=*/false, /*closure_order=*/4},
      // Their sampled form: the same moment equations between samples, and at each sample the moments of the
      // Kalman-updated law x + K (y - c(x) - v), c = C0 + C x or a polynomial (docs/theory.md §2.10).
      {FilterKind::CdClosure3, "cd-closure3",
       "continuous-discrete moment filter of order 3: the closed moment ODEs of m, P and the third central moments "
       "between samples, at each the Kalman update of m and P and the third moments of the updated law; opt-in",
       E::CumulantNeglect, D::Model, sampled, Prediction::Ode, DelayGain::Undelayed, Criterion::MeanSquare,
       /*in_defaults=*/false, /*closure_order=*/3},
      {FilterKind::CdClosure4, "cd-closure4",
       "continuous-discrete moment filter of order 4: as cd-closure3, with the fourth central moments; opt-in",
       E::CumulantNeglect, D::Model, sampled, Prediction::Ode, DelayGain::Undelayed, Criterion::MeanSquare,
       /*in_defaults=*/false, /*closure_order=*/4},
  };
  return kinds;
}

const FilterKindInfo& filter_kind_info(FilterKind kind) {
  for (const auto& info : filter_kinds())
    if (info.kind == kind) return info;
  throw std::logic_error("filter kind missing from the registry");
}

std::optional<FilterKind> parse_filter_kind(const std::string& name) {
  for (const auto& info : filter_kinds())
    if (info.name == name) return info.kind;
  return std::nullopt;
}

std::vector<std::string> filter_kind_names() {
  std::vector<std::string> names;
  for (const auto& info : filter_kinds()) names.push_back(info.name);
  return names;
}

std::optional<std::string> unsupported_reason(const FilterKindInfo& kind, const FilterKindNeeds& model) {
  if (kind.diffusion == DiffusionSource::Additive && !model.has_additive_diffusion)
    return std::string("needs additive_diffusion or additive_diffusion_covariance");
  if (std::find(kind.observations.begin(), kind.observations.end(), model.observation) == kind.observations.end())
    return "is not derived for " + observation_kind_info(model.observation).name + " observations";
  // A moment filter's run stops where P is not positive definite (docs/theory.md §2.10): from a singular P0 it
  // would stop at once, in every run.
  if (kind.expectation == ExpectationRule::CumulantNeglect && !model.prior_positive_definite)
    return std::string("needs a positive definite initial.P0 (a moment filter's run stops where P is not; this P0 is "
                       "singular)");
  if (kind.criterion == Criterion::RiskSensitive) {
    if (!model.has_risk_criterion) return std::string("needs a risk: section (risk: {epsilon: ...})");
    if (!model.state_independent_diffusion)
      return std::string("needs a state-independent diffusion (additive noise, as its construction assumes)");
    if (model.drift_degree > kRiskSensitiveMaxDegree)
      return "is derived for drifts of degree <= " + std::to_string(kRiskSensitiveMaxDegree) + " (drift[" +
             std::to_string(model.drift_degree_row) + "] has degree " + std::to_string(model.drift_degree) + ")";
  }
  return std::nullopt;
}

}  // namespace pfgen
