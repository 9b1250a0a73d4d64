#include "pfgen/model/stratonovich.hpp"

namespace pfgen {

ExVector stratonovich_correction(const ExMatrix& g, const std::vector<GiNaC::symbol>& states) {
  const std::size_t n = states.size();
  ExVector c(n, GiNaC::ex(0));
  for (std::size_t i = 0; i < n; ++i) {
    GiNaC::ex sum = 0;
    for (std::size_t k = 0; k < g.at(i).size(); ++k)
      for (std::size_t j = 0; j < n; ++j) sum += g.at(j).at(k) * g.at(i).at(k).diff(states[j]);
    c[i] = (sum / 2).expand();
  }
  return c;
}

}  // namespace pfgen
