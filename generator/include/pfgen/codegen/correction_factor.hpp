#pragma once
// The observation's correction term in factored form, for code generation.
//
// The derivation hands code generation the correction P Aᵀ R⁻¹ A P of the mean-square continuous
// kinds expanded, as Σ_kl M_kl P_ik P_lj with M = Aᵀ R⁻¹ A folded into the coefficients: about
// n⁴/2 monomials over the upper triangle. Graph sharing cannot refactor a sum by distributivity,
// so it cannot recover the factor P Aᵀ. The same term is K H with K = P Aᵀ R⁻¹ (the filter's gain,
// n × p) and H = A P (p × n), which costs O(n² p) operations. correction_factor() reads A off the
// predicted observation A0 + A m, builds H, and returns it only when Σ_r K_ir H_rj equals every
// P_correction entry exactly (polynomial arithmetic): the factored form is used where it is the
// same polynomial, never assumed. Delayed kinds (A reads md, and Φ* sits between), the
// risk-sensitive kind (its correction has more terms) and user filters get nothing.
#include <optional>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

// A (p × n) of a predicted observation A0 + A m, when every entry is affine in m.
std::optional<std::vector<std::vector<GiNaC::ex>>> observation_matrix(const FilterEquations& eq);
// G^T (p × n) with gain_ir = Σ_k P_ik G_kr for every i (G = Aᵀ R⁻¹ for the mean-square kinds), when
// the gain is exactly that product.
std::optional<std::vector<std::vector<GiNaC::ex>>> gain_factor(const FilterEquations& eq);
// M (p × p) with G^T = M A exactly (M = R⁻¹ for the mean-square kinds), so that K^T = M (A P):
// p² n operations from H = A P instead of p n² from P. Nothing when A's rank is below p or no
// such M exists.
std::optional<std::vector<std::vector<GiNaC::ex>>> gain_weight(const std::vector<std::vector<GiNaC::ex>>& Gt,
                                                               const std::vector<std::vector<GiNaC::ex>>& A);
// H = A P (p × n), H[r][j] = Σ_k A_rk P_kj, when P_correction == gain · H entry by entry.
std::optional<std::vector<std::vector<Polynomial>>> correction_factor(const FilterEquations& eq);

}  // namespace pfgen::codegen
