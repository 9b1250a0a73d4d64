#include "pfgen/derivation/exactness_facts.hpp"

namespace pfgen {

ExactnessFacts::ExactnessFacts(const Model& m, FilterKind kind)
    : model(m), diffusion(uses_additive_diffusion(kind) ? *m.additive_diffusion : m.diffusion) {
  for (const auto& e : m.drift) f.push_back(Polynomial::from_ex(e, m.states));
}

std::string ExactnessFacts::nonaffine_drift() const {
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f[i].degree() > 1) return "drift of " + model.state_names[i] + " has degree " + std::to_string(f[i].degree());
  return {};
}

std::string ExactnessFacts::state_dependent_noise() const {
  for (const auto& row : diffusion.G)
    for (const auto& e : row)
      if (depends_on_states(model, e)) return "the diffusion depends on the state (multiplicative noise)";
  return {};
}

std::string ExactnessFacts::nonaffine_noise() const {
  if (diffusion.g) {
    for (const auto& row : *diffusion.g)
      for (const auto& e : row)
        if (Polynomial::from_ex(e, model.states).degree() > 1) return "$g|g$ is not affine in the state";
    return {};
  }
  for (const auto& row : diffusion.G)
    for (const auto& e : row)
      if (Polynomial::from_ex(e, model.states).degree() > 2)
        return "$G = g g^T|G = g\\,g^{T}$ has degree above 2 ($g|g$ not affine)";
  return {};
}

}  // namespace pfgen
