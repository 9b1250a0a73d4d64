#include "pfgen/derivation/filter_kind.hpp"

#include "pfgen/model/model.hpp"

namespace pfgen {

std::string filter_kind_name(FilterKind kind) {
  switch (kind) {
    case FilterKind::Optimal: return "optimal";
    case FilterKind::Ekf: return "ekf";
    case FilterKind::Additive: return "additive";
    case FilterKind::EkfAdditive: return "ekf-additive";
  }
  return "?";
}

std::optional<FilterKind> parse_filter_kind(const std::string& name) {
  for (FilterKind kind : {FilterKind::Optimal, FilterKind::Ekf, FilterKind::Additive, FilterKind::EkfAdditive})
    if (filter_kind_name(kind) == name) return kind;
  return std::nullopt;
}

std::string filter_kind_description(FilterKind kind) {
  switch (kind) {
    case FilterKind::Optimal:
      return "Gaussian-closure optimal filter: E[f], E[(x-m)f^T] + E[f(x-m)^T], E[g g^T] expanded exactly";
    case FilterKind::Ekf:
      return "extended Kalman-Bucy filter (textbook): f(m), Jacobian of f at m, g(m) g(m)^T";
    case FilterKind::Additive:
      return "Gaussian-closure filter with the model's additive (state-independent) diffusion in place of g";
    case FilterKind::EkfAdditive:
      return "extended Kalman-Bucy filter with the model's additive (state-independent) diffusion in place of g";
  }
  return "?";
}

bool uses_additive_diffusion(FilterKind kind) {
  return kind == FilterKind::Additive || kind == FilterKind::EkfAdditive;
}

bool is_extended_kalman(FilterKind kind) { return kind == FilterKind::Ekf || kind == FilterKind::EkfAdditive; }

std::vector<FilterKind> supported_filter_kinds(const Model& model) {
  std::vector<FilterKind> kinds{FilterKind::Optimal, FilterKind::Ekf};
  if (model.additive_diffusion) {
    kinds.push_back(FilterKind::Additive);
    kinds.push_back(FilterKind::EkfAdditive);
  }
  return kinds;
}

}  // namespace pfgen
