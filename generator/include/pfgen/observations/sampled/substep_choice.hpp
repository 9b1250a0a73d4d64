#pragma once
// How many sub-steps a sampled filter's prediction takes per period when the model file leaves
// `substeps` out (docs/theory.md, "How many sub-steps"). Heun's method over a period T in one step
// is stable and accurate only when T is short against the prediction's own rates: an epidemic
// observed daily whose covariance grows at 2.5 per day loses its positive definite P within days
// when predicted in one step a day. Two readings of the filter's own prediction ODE (dm, dP) at the
// prior (m0, P0, t = 0, the model file's parameter values) decide:
//   - its rate rho, the spectral radius of its Jacobian: each sub-step's h rho at most 1/4;
//   - its first period from the prior: the count doubled until k and 2k sub-steps agree to 1 %
//     (m and P each, relatively), since the forcing E[g g^T] bends P where the rate does not say.
#include <cstddef>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// The largest h rho the rule allows, the agreement it asks of the first period, and the most
// sub-steps it chooses (beyond, the model must say).
inline constexpr double kSubstepRateProduct = 0.25;
inline constexpr double kSubstepTolerance = 1e-2;
inline constexpr std::size_t kMaxChosenSubsteps = 100000;

struct SubstepAdvice {
  double rate = 0;      // rho, per unit of time, at the prior (infinite where J is not finite)
  double substeps = 1;  // the rule's count, at least 1; beyond kMaxChosenSubsteps where none is enough
};

// The rule above for the prediction in `eq` (m_drift, P_moment + P_diffusion) of a sampled model.
SubstepAdvice advise_substeps(const Model& model, const FilterEquations& eq);

// Sets eq.update's substeps: the model's own when it gives them (with the rule's advice beside,
// for the report), else the rule's count, refused (ModelError at observation.sampled.substeps)
// beyond kMaxChosenSubsteps.
void set_prediction_substeps(const Model& model, FilterEquations& eq);

}  // namespace pfgen
