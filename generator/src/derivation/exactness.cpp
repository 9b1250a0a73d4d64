#include "pfgen/derivation/exactness.hpp"

#include "pfgen/derivation/exactness_facts.hpp"
#include "pfgen/derivation/observation_derivation.hpp"

namespace pfgen {
namespace {

// The risk-sensitive filter (docs/theory.md §2.7) is exact, as the risk-sensitive filter, when the
// quadratic form of its information state is: f affine (the LEQG filter). It never estimates the
// conditional mean, and says so.
ExactnessReport risk_sensitive_exactness(const ExactnessFacts& facts) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  if (nonaffine.empty()) {
    report.exact = true;
    report.condition = "LEQG";
    report.explanation = "exact: $f|f$ is affine and the noise additive, so the information state stays Gaussian "
                         "and this is the linear risk-sensitive (LEQG) filter for the criterion $J|J$; $m|m$ is its "
                         "estimate, not the conditional mean";
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation (the construction of Alcorta-Garcia et al. 2011): the equation of the "
                       "risk-sensitive information state's logarithm is expanded about $m|m$ to second order in "
                       "$x - m|x - m$; the terms of order 3 and above, which $f|f$'s degree above 1 brings, are "
                       "dropped";
  report.failed.push_back("LEQG: " + nonaffine);
  return report;
}

// The unscented kind (docs/theory.md §2.8) replaces E[f], E[(x-m) f^T] and E[g g^T] under N(m, P) by
// sigma-point sums; these equal the expectations when f is affine and g constant (Kalman-Bucy), and
// for polynomials of low enough degree along the sigma axes, which the report names as a
// condition only in the Kalman-Bucy case, where it is proven.
ExactnessReport unscented_exactness(const ExactnessFacts& facts) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  if (nonaffine.empty() && multiplicative.empty()) {
    report.exact = true;
    report.condition = "Kalman-Bucy";
    report.explanation = "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so the sigma-point sums are "
                         "the Gaussian expectations and this is the Kalman-Bucy filter";
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation (unscented, Sarkka 2007): $E[f]|E[f]$, $E[(x-m) f^T]|E[(x-m) f^{T}]$ and "
                       "$E[g g^T]|E[g\\,g^{T}]$ under $N(m, P)|N(m, P)$ are replaced by weighted sums over $2n+1|2n+1$ "
                       "sigma points; the sums equal those expectations when $f|f$ has degree $<= 2|\\le 2$ and $G|G$ "
                       "degree $<= 3|\\le 3$, and beyond that only for terms that move along one sigma axis "
                       "(docs/theory.md 2.8), on top of the Gaussian assumed density";
  report.failed.push_back("Kalman-Bucy: " + (!nonaffine.empty() ? nonaffine : multiplicative));
  return report;
}

// The moment filters (docs/theory.md §2.10): with f and h affine and g free of the state, a Gaussian prior
// stays Gaussian, so the cumulants above the order carried stay zero and the closure drops nothing.
ExactnessReport moment_closure_exactness(const ExactnessFacts& facts, FilterKind kind) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  const unsigned h_degree = facts.model.observation.rate().degree(facts.model.states);
  const std::string nonlinear_h =
      h_degree > 1 ? "the observation's h has degree " + std::to_string(h_degree) : std::string();
  const std::string order = std::to_string(filter_kind_info(kind).closure_order);
  // Samples (through C0 + C x) make the exact case the Kalman filter, continuous observations the Kalman-Bucy filter.
  const bool sampled = facts.model.observation.samples().has_value();
  const std::string linear_filter = sampled ? "Kalman" : "Kalman-Bucy";
  if (nonaffine.empty() && multiplicative.empty() && nonlinear_h.empty()) {
    report.exact = true;
    report.condition = linear_filter;
    report.explanation =
        sampled ? "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so from the Gaussian prior the law stays "
                  "Gaussian between and at the samples: the moments of order 3 and above stay those of "
                  "$N(m, P)|N(m, P)$ and $m|m$, $P|P$ are the Kalman filter's (up to the sub-steps' integration error)"
                : "exact: $f|f$ and $h|h$ are affine and $g|g$ does not depend on $x|x$, so from the Gaussian prior the "
                  "conditional law stays Gaussian: the moments of order 3 and above stay those of $N(m, P)|N(m, P)$ "
                  "and $m|m$, $P|P$ are the Kalman-Bucy filter's";
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation: the conditional law's cumulants of order above " + order +
                       " are set to zero (cumulant neglect), so the moments above order " + order +
                       " that the equations read are those of that closed law";
  report.failed.push_back(linear_filter + ": " +
                          (!nonaffine.empty() ? nonaffine : !multiplicative.empty() ? multiplicative : nonlinear_h));
  return report;
}

}  // namespace

ExactnessReport assess_exactness(const Model& model, FilterKind kind) {
  if (is_risk_sensitive(kind)) return risk_sensitive_exactness(ExactnessFacts(model, kind));
  if (uses_sigma_points(kind)) return unscented_exactness(ExactnessFacts(model, kind));
  if (uses_cumulant_closure(kind)) return moment_closure_exactness(ExactnessFacts(model, kind), kind);
  // The Gaussian-closure kinds: exact under conditions that depend on how the states are observed.
  return observation_derivation(model.observation).exactness(model, kind);
}

}  // namespace pfgen
