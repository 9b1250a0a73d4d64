#pragma once
// A moment filter's update at a sample through C0 + C x (cd-closure3, cd-closure4; docs/theory.md §2.10): the
// moments of the Kalman-updated law x+ = x + K (y - C0 - C x - v), v ~ N(0, R) independent of x. With
// A = I - K C, e = x - m, u = A e and w = -K v (Gaussian, covariance Q = K R K^T, independent of u):
//   m+ = m + K (y - C0 - C m),   P+ = A P A^T + Q (the Joseph form, joseph_update),
//   M3+_ijl  = sum_abc A_ia A_jb A_lc M3_abc                       (w's odd moments vanish),
//   M4+_ijlq = sum_abcd A_ia A_jb A_lc A_qd M4_abcd
//              + U_ij Q_lq + U_il Q_jq + U_iq Q_jl + U_jl Q_iq + U_jq Q_il + U_lq Q_ij   (U = A P A^T)
//              + Q_ij Q_lq + Q_il Q_jq + Q_iq Q_jl.
// They are the moments of an actual law whenever (m, P, M3, M4) are, so the update keeps a realisable state
// realisable; for a Gaussian prior they are N(m+, P+)'s. The samples do not enter them: only m+ reads y.
#include <functional>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/codegen/ir/statements.hpp"
#include "pfgen/observations/sampled/joseph_update.hpp"
#include "pfgen/derivation/filter_variables.hpp"

namespace pfgen {

using NumericMatrix = std::vector<std::vector<GiNaC::numeric>>;  // rows of entries, full

// The central moment of z with these indices (ascending, 0-based over A's columns), of order 2 up to the filter's.
using JointMoment = std::function<GiNaC::numeric(const std::vector<std::size_t>&)>;

struct MomentsAfterUpdate {
  NumericMatrix P;                    // n x n
  std::vector<GiNaC::numeric> higher; // FilterVariables::higher_moments() order
};

// The moments of x+ - m+ = A z + w, w ~ N(0, Q) independent of z, exactly: A (n x N) and z's moments `z`, N = n and
// z = x - m for samples through C0 + C x, z = (x - m, d) and A = Abar for a polynomial c (closure_sampled_update.hpp).
MomentsAfterUpdate updated_moments(const FilterVariables& vars, const NumericMatrix& A, const JointMoment& z,
                                   const NumericMatrix& Q);

}  // namespace pfgen

namespace pfgen::codegen {

// The same in a generated update, after joseph_update_statements()'s body has left A and AP = A P (n x n,
// row-major), K (n x p) and the packed R in its local arrays and written P+: each order's moments unpacked from the
// state into a full tensor, A applied to one index at a time (n^(k+1) products per order instead of n^(2k)), then at
// order 4 the noise's terms, and packed back into the state. Empty without higher moments.
ir::Block moment_update_statements(const FilterVariables& vars);

// A moment filter's update at a sample through a polynomial c (closure_sampled_update.hpp): the Joseph update's
// arrays, views and solve, the joint moments z (`joint`, SampledUpdate::joint's order) taken by the file's
// joint_moments() before m moves, then m += K (y - h), A = I - K C, Abar = [A, -K], and P and each higher order
// as Abar's contraction of z's moments (read from the state where all indices are e's) plus the noise's terms.
JosephUpdate joint_moment_update_statements(const FilterVariables& vars, std::size_t r,
                                            const std::vector<std::vector<std::size_t>>& joint);

}  // namespace pfgen::codegen
