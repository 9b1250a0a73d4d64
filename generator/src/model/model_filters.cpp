#include "pfgen/model/model_filters.hpp"

namespace pfgen {

FilterKindNeeds filter_kind_needs(const Model& model) {
  FilterKindNeeds needs;
  needs.has_additive_diffusion = model.additive_diffusion.has_value();
  needs.observation = model.observation.kind();
  return needs;
}

std::optional<std::string> unsupported_reason(const Model& model, FilterKind kind) {
  return unsupported_reason(filter_kind_info(kind), filter_kind_needs(model));
}

std::vector<FilterKind> supported_filter_kinds(const Model& model) {
  const FilterKindNeeds needs = filter_kind_needs(model);
  std::vector<FilterKind> kinds;
  for (const auto& info : filter_kinds())
    if (!unsupported_reason(info, needs)) kinds.push_back(info.kind);
  return kinds;
}

std::vector<std::string> available_filter_names(const Model& model) {
  std::vector<std::string> names;
  for (FilterKind kind : supported_filter_kinds(model)) names.push_back(filter_kind_name(kind));
  for (const auto& filter : model.user_filters) names.push_back(filter.name);
  return names;
}

std::optional<std::string> filter_name_problem(const Model& model, const std::string& name) {
  if (auto kind = parse_filter_kind(name))
    if (auto reason = unsupported_reason(model, *kind)) return "'" + name + "' " + *reason + " in model " + model.name;
  const std::vector<std::string> available = available_filter_names(model);
  std::string known;
  for (const auto& filter : available) {
    if (filter == name) return std::nullopt;
    known += (known.empty() ? "" : ", ") + filter;
  }
  return "unknown filter '" + name + "' (known: " + known + ")";
}

}  // namespace pfgen
