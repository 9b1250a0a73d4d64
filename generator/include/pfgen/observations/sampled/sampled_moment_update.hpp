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
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/codegen/ir/statements.hpp"
#include "pfgen/derivation/filter_variables.hpp"

namespace pfgen {

using NumericMatrix = std::vector<std::vector<GiNaC::numeric>>;  // n x n, full

// The higher moments after the update (FilterVariables::higher_moments() order), exactly: A = I - K C, P the
// prior covariance, Q = K R K^T, `moments` the prior's higher moments in the same order.
std::vector<GiNaC::numeric> updated_higher_moments(const FilterVariables& vars, const NumericMatrix& A,
                                                   const NumericMatrix& P, const NumericMatrix& Q,
                                                   const std::vector<GiNaC::numeric>& moments);

}  // namespace pfgen

namespace pfgen::codegen {

// The same in a generated update, after joseph_update_statements()'s body has left A and AP = A P (n x n,
// row-major), K (n x p) and the packed R in its local arrays and written P+: each order's moments unpacked from the
// state into a full tensor, A applied to one index at a time (n^(k+1) products per order instead of n^(2k)), then at
// order 4 the noise's terms, and packed back into the state. Empty without higher moments.
ir::Block moment_update_statements(const FilterVariables& vars);

}  // namespace pfgen::codegen
