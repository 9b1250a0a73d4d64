#include "pfgen/observations/polynomial/ito_stratonovich_correction.hpp"

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

std::vector<Polynomial> ito_stratonovich_correction(const std::vector<std::vector<Polynomial>>& noise,
                                                    const ExMatrix& B, const FilterVariables& vars) {
  const std::size_t count = vars.count();
  const ExMatrix R = multiply_by_transpose(B);
  const std::size_t p = R.size();
  // w = sigma R first (n x p): sigma holds R^-1 (K = P E[J]^T R^-1), so w's coefficients cancel to
  // simple ones, and each product below has one factor free of R. Multiplying by R inside the
  // double sum instead carried rational functions of R's parameters through every product: a
  // 3-state model with a parameter in a 3 x 3 B took a minute.
  std::vector<std::vector<Polynomial>> w(count, std::vector<Polynomial>(p));
  for (std::size_t u = 0; u < count; ++u)
    for (std::size_t r = 0; r < p; ++r)
      for (std::size_t q = 0; q < p; ++q)
        if (!R[q][r].is_zero() && !noise[u][q].is_zero()) w[u][r] += noise[u][q].scaled(R[q][r]);
  std::vector<Polynomial> correction(count);
  for (std::size_t v = 0; v < count; ++v) {
    Polynomial sum;
    for (std::size_t r = 0; r < p; ++r) {
      if (noise[v][r].is_zero()) continue;
      for (std::size_t u = 0; u < count; ++u) {
        if (w[u][r].is_zero()) continue;
        const Polynomial derivative = noise[v][r].derivative(static_cast<std::uint32_t>(u));
        if (!derivative.is_zero()) sum += derivative * w[u][r];
      }
    }
    correction[v] = sum.scaled(GiNaC::numeric(1, 2));
  }
  return correction;
}

}  // namespace pfgen
