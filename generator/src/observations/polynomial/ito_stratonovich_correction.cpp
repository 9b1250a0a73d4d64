#include "pfgen/observations/polynomial/ito_stratonovich_correction.hpp"

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

std::vector<Polynomial> ito_stratonovich_correction(const std::vector<std::vector<Polynomial>>& noise,
                                                    const ExMatrix& B, const FilterVariables& vars) {
  const std::size_t count = vars.count();
  const ExMatrix R = multiply_by_transpose(B);
  const std::size_t p = R.size();
  std::vector<Polynomial> correction(count);
  for (std::size_t v = 0; v < count; ++v)
    for (std::size_t r = 0; r < p; ++r) {
      if (noise[v][r].is_zero()) continue;
      for (std::size_t u = 0; u < count; ++u) {
        const Polynomial derivative = noise[v][r].derivative(static_cast<std::uint32_t>(u));
        if (derivative.is_zero()) continue;
        for (std::size_t q = 0; q < p; ++q)
          if (!R[r][q].is_zero() && !noise[u][q].is_zero())
            correction[v] += (derivative * noise[u][q]).scaled(normalize_coefficient(R[r][q] / 2));
      }
    }
  return correction;
}

}  // namespace pfgen
