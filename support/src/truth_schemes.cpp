#include "pfgen_support/truth_schemes.hpp"

namespace pfgen_support {

const std::vector<TruthSchemeInfo>& truth_schemes() {
  static const std::vector<TruthSchemeInfo> schemes = {
      {"euler-maruyama", "x + f dt + g dW: strong order 0.5 (1 for additive noise)"},
      {"milstein", "Euler-Maruyama plus the Ito correction from the diffusion's Jacobian: strong order 1, commutative noise"},
      {"derivative-free-milstein", "Platen's explicit order-1 scheme: Milstein without the diffusion's Jacobian"},
      {"tamed-euler", "Euler-Maruyama with the increment tamed to at most 1/dt: no overflow for superlinear f and g"},
      {"adaptive-euler", "Euler-Maruyama on Brownian-bridge substeps sized to the local coefficients"},
      {"rk4", "classical Runge-Kutta 4 for deterministic truths (g = 0)"},
  };
  return schemes;
}

std::vector<std::string> truth_scheme_choices() {
  std::vector<std::string> names{"auto"};
  for (const auto& scheme : truth_schemes()) names.push_back(scheme.name);
  return names;
}

}  // namespace pfgen_support
