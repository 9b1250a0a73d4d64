#include "pfgen/observations/delayed/delayed_exactness.hpp"

#include "pfgen/derivation/exactness_facts.hpp"
#include "pfgen/observations/continuous/continuous_exactness.hpp"

namespace pfgen {

// Delayed observations (docs/theory.md §2.6). With h = 0 the delay kinds are their undelayed
// counterparts; with h > 0 no finite set of moments of x(t) is exact, and the filter of Basin,
// Rodriguez-Gonzalez & Martinez-Zuniga 2004
// makes two approximations on top of the Gaussian closure, which the report names.
ExactnessReport delayed_exactness(const Model& model, FilterKind kind) {
  const ExactnessFacts facts(model, kind);
  const FilterKind counterpart = is_extended_kalman(kind) ? FilterKind::Ekf : FilterKind::Optimal;
  if (model.observation.delay().is_zero()) {
    ExactnessReport report = continuous_exactness(model, counterpart);
    report.explanation += " ($h = 0|h = 0$: the delayed filter is the '" + filter_kind_name(counterpart) + "' filter)";
    return report;
  }
  ExactnessReport report;
  report.condition = "none";
  const std::string multiplicative = facts.state_dependent_noise();
  const std::string extension =
      multiplicative.empty() ? ""
                             : "; Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004 treat additive state noise "
                               "only, so with state-dependent $g|g$ these equations are a Gaussian-closure extension "
                               "of their filter";
  if (is_extended_kalman(kind))
    report.explanation = "approximation: the extended Kalman-Bucy filter linearises $f|f$ at $m|m$ and compares "
                         "$dy|dy$ with $A m(t - h)|A\\,m(t-h)$ under the undelayed gain";
  else if (uses_transition_gain(kind))
    report.explanation = "approximation (Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004): the innovation uses "
                         "$m(t - h)|m(t-h)$, the estimate made at $t - h|t-h$, for "
                         "$E[x(t - h) \\| Y(t)]|E[x(t-h) \\mid Y(t)]$, which the observations since $t - h|t-h$ also "
                         "inform, and $E[x(t) (x(t - h) - m(t - h))^T]|E\\bigl[x(t)\\,(x(t-h) - m(t-h))^{T}\\bigr]$ is "
                         "taken as $P Phi*^T|P\\,\\Phi^{*T}$, $Phi*|\\Phi^{*}$ from the noise-free solution $x*|x^{*}$ "
                         "started at $m0|m_0$ (Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004, eqs 3 and 5)" +
                         extension;
  else
    report.explanation = "approximation: the undelayed gain $P A^T R^-1|P A^{T} R^{-1}$ with the delayed innovation "
                         "(Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004, eqs 19-20, their comparator)" + extension;
  report.failed.push_back("delay: $h > 0|h > 0$; the conditional law of $x(t)|x(t)$ depends on the path over "
                          "$[t - h, t]|[t-h, t]$, so no filter of $m(t)|m(t)$ and $P(t)|P(t)$ alone is exact");
  return report;
}

}  // namespace pfgen
