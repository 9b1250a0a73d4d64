#include "pfgen/observations/sampled/sampled_exactness.hpp"

#include "pfgen/derivation/exactness_facts.hpp"

namespace pfgen {

// Sampled observations: the update is the Kalman update, optimal when x given the past samples
// is Gaussian. That holds when f is affine and g does not depend on x (the model sampled is then
// linear Gaussian); cd-euler is then the Kalman filter of the Euler-discretised model.
ExactnessReport sampled_exactness(const Model& model, FilterKind kind, const std::string& nonlinear_samples) {
  const ExactnessFacts facts(model, kind);
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  const std::string failure = !nonaffine.empty() ? nonaffine : !multiplicative.empty() ? multiplicative : nonlinear_samples;
  if (failure.empty()) {
    report.exact = true;
    report.condition = uses_euler_map(kind) ? "Kalman (Euler model)" : "Kalman";
    report.explanation =
        uses_euler_map(kind)
            ? "exact for the Euler-discretised model: $f|f$ is affine and $g|g$ does not depend on $x|x$, so this "
              "is the Kalman filter of $x' = x + f dt + g sqrt(dt) xi|x' = x + f\\,dt + g \\sqrt{dt}\\,\\xi$ "
              "sampled every sub-step"
            : "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so this is the Kalman filter of the "
              "sampled linear system (up to the sub-steps' integration error)";
    return report;
  }
  report.condition = "none";
  if (!nonlinear_samples.empty() && nonaffine.empty() && multiplicative.empty())
    report.explanation = "approximation: the samples' $c|c$ is nonlinear, so the update is the Gaussian "
                         "(moment-matching) one with " +
                         std::string(is_extended_kalman(kind) ? "$c|c$ linearised at $m|m$" : "the exact moments of $c|c$") +
                         ", not the optimal one";
  else if (uses_euler_map(kind) && nonaffine.empty())
    report.explanation = "linear minimum-variance filter (Allahyani & Date): with affine $f|f$ the predicted $m|m$ "
                         "and $P|P$ are the exact moments of the Euler-discretised model, but $x|x$ is not Gaussian, "
                         "so the update is the best linear one, not the optimal one";
  else if (is_extended_kalman(kind))
    report.explanation = "approximation: the extended Kalman filter linearises $f|f$ at $m|m$; it is exact only "
                         "in the linear Gaussian case";
  else
    report.explanation = "approximation: Gaussian assumed density between samples and a Kalman update at each";
  report.failed.push_back("Kalman: " + failure);
  return report;
}

}  // namespace pfgen
