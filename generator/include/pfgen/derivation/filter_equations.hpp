#pragma once
// The closed equations of one filter kind for one model:
//   dm = m_drift dt + gain (dy - (A0 + A m) dt)
//   dP = (P_moment + P_diffusion - P_correction) dt
// with P_moment = E[(x-m)f^T] + E[f(x-m)^T] (or its EKF form), P_diffusion =
// E[g g^T] (or g(m)g(m)^T, or the additive G), P_correction = P A^T R^-1 A P.
// P entries are stored as the upper triangle, row by row (FilterVariables).
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/exactness.hpp"
#include "pfgen/derivation/filter_kind.hpp"
#include "pfgen/derivation/filter_variables.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

struct FilterEquations {
  FilterKind kind;
  FilterVariables variables;
  std::size_t p = 0;
  std::vector<Polynomial> m_drift;              // n
  std::vector<std::vector<Polynomial>> gain;    // n x p
  // The matrix standing for the Jacobian: E[d_k f_j] (optimal, additive) or
  // d_k f_j at m (EKF kinds), entry [j][k]; P_moment_ij = sum_k P_ik J_jk + J_ik P_kj.
  // Kept so that code generation can compute P_moment from it, sharing its entries.
  std::vector<std::vector<Polynomial>> jacobian_term;  // n x n
  std::vector<Polynomial> P_moment;             // n(n+1)/2, upper triangle
  std::vector<Polynomial> P_diffusion;          // n(n+1)/2
  std::vector<Polynomial> P_correction;         // n(n+1)/2, subtracted
  ExactnessReport exactness;

  std::size_t n() const { return variables.n(); }
  // The dt-coefficient of dP_ij, all parts combined (i, j in either order).
  Polynomial P_drift(std::size_t i, std::size_t j) const;
};

// The predicted observation rate A0 + A m, one polynomial per observation row.
std::vector<Polynomial> predicted_observation(const Model& model, const FilterVariables& vars);

// Derives the filter; throws std::invalid_argument if the model lacks what the
// kind needs (an additive kind without additive_diffusion).
FilterEquations derive_filter(const Model& model, FilterKind kind);

}  // namespace pfgen
