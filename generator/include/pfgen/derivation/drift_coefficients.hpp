#pragma once
// The coefficient form of a model whose drift has degree <= 3 (docs/theory.md §1.1), as the
// risk-sensitive filter of paper 002 writes its systems:
//   f_i(x,t) = A_i + sum_j A1_ij x_j + sum_jk A2_ijk x_j x_k + sum_jkl A3_ijkl x_j x_k x_l,
// with A2 and A3 symmetric in their lower indices (A2_ijk = 1/2 d2f_i/dx_j dx_k and
// A3_ijkl = 1/6 d3f_i/dx_j dx_k dx_l, at x = 0), and the observation's rate
//   h(x,t) = E + E1 x   (dy = h dt + B dW2; for a delayed observation h is of x(t - h)).
// Entries are GiNaC expressions in the parameters and t. A2 and A3 are held sparse: a model
// with many states has few nonzero entries among n^3 and n^4.
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// The highest degree of a drift the coefficient form holds: the risk-sensitive kind's limit
// (kinds/filter_kinds.hpp), so the two cannot drift apart.
inline constexpr std::uint32_t kCoefficientFormDegree = kRiskSensitiveMaxDegree;

// The nonzero entries of a tensor, keyed by 0-based indices (i, j, k[, l]); std::map keeps them in
// lexicographic index order, the order every report lists them in.
using TensorEntries = std::map<std::vector<std::uint32_t>, GiNaC::ex>;

struct DriftCoefficients {
  std::size_t n = 0;
  ExVector A;        // n
  ExMatrix A1;       // n x n
  TensorEntries A2;  // nonzero A2_ijk, every order of (j, k)
  TensorEntries A3;  // nonzero A3_ijkl, every order of (j, k, l)

  // Entries by 0-based index, 0 where the tensor holds none.
  GiNaC::ex A2_at(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
  GiNaC::ex A3_at(std::uint32_t i, std::uint32_t j, std::uint32_t k, std::uint32_t l) const;
};

// The observation's linear terms. A continuous or delayed observation has a rate, E + E1 x; a
// sampled one has none, and its sample equation's C0 and C are given instead (what the reports
// show under those names, not as E and E1).
struct ObservationCoefficients {
  ObservationKind kind = ObservationKind::Continuous;
  ExVector E;   // p: A0 (continuous, delayed) or C0 (sampled)
  ExMatrix E1;  // p x n: A or C
};

// Throws ModelError naming the model's file, field `drift` and the row (1-based) of the first
// drift entry of degree above kCoefficientFormDegree:
//   "drift[2] has degree 4; the coefficient form A..A3 holds degree <= 3".
// The risk-sensitive filter kind calls it before deriving.
void check_coefficient_form_degree(const Model& model);

// A, A1, A2, A3 of the model's drift (check_coefficient_form_degree first).
DriftCoefficients extract_drift_coefficients(const Model& model);
ObservationCoefficients extract_observation_coefficients(const Model& model);

}  // namespace pfgen
