#include "pfgen/model/model_filters.hpp"

#include <stdexcept>

#include <Eigen/Dense>

#include "pfgen/algebra/polynomial.hpp"

namespace pfgen {

FilterKindNeeds filter_kind_needs(const Model& model) {
  FilterKindNeeds needs;
  needs.has_additive_diffusion = model.additive_diffusion.has_value();
  needs.observation = model.observation.kind();
  needs.has_risk_criterion = model.risk.has_value();
  if (model.initial && !model.initial->P0.empty()) {
    const std::size_t n = model.initial->P0.size();
    Eigen::MatrixXd P0(n, n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) P0(i, j) = model.initial->P0[i][j].to_double();
    needs.prior_positive_definite = Eigen::LLT<Eigen::MatrixXd>(P0).info() == Eigen::Success;
  }
  // Only the risk-sensitive kind reads the facts below, and only with a risk: section: skip the
  // expansions for every other model.
  if (!needs.has_risk_criterion) return needs;
  needs.state_independent_diffusion = true;
  for (const auto& row : model.diffusion.G)
    for (const auto& entry : row) needs.state_independent_diffusion &= !depends_on_states(model, entry);
  for (std::size_t i = 0; i < model.drift.size(); ++i) {
    // The validator has checked that the drift is polynomial in the states.
    const std::uint32_t degree = Polynomial::from_ex(model.drift[i], model.states).degree();
    if (degree > needs.drift_degree) {
      needs.drift_degree = degree;
      needs.drift_degree_row = static_cast<unsigned>(i + 1);
    }
  }
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

std::vector<std::string> default_filter_names(const Model& model) {
  std::vector<std::string> names;
  for (FilterKind kind : supported_filter_kinds(model))
    if (filter_kind_info(kind).in_defaults) names.push_back(filter_kind_name(kind));
  for (const auto& filter : model.user_filters) names.push_back(filter.name);
  return names;
}

std::optional<std::pair<std::string, std::size_t>> split_substeps(const std::string& name) {
  const std::size_t at = name.find('@');
  if (at == std::string::npos) return std::nullopt;
  const std::string digits = name.substr(at + 1);
  const bool whole = !digits.empty() && digits.size() <= 7 &&
                     digits.find_first_not_of("0123456789") == std::string::npos && digits.front() != '0';
  if (!whole || std::stoul(digits) > 1000000)
    throw std::invalid_argument("filter '" + name + "': the sub-steps after '@' must be a whole number from 1 to 1000000");
  return std::make_pair(name.substr(0, at), static_cast<std::size_t>(std::stoul(digits)));
}

std::optional<std::string> filter_name_problem(const Model& model, const std::string& name) {
  std::optional<std::pair<std::string, std::size_t>> split;
  try {
    split = split_substeps(name);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (split) {
    const auto kind = parse_filter_kind(split->first);
    if (!model.observation.is_sampled() || !kind)
      return "'" + name + "': only the built-in kinds of a model with sampled observations take '@' and a number of "
             "sub-steps";
    return filter_name_problem(model, split->first);
  }
  const std::vector<std::string> available = available_filter_names(model);
  if (auto kind = parse_filter_kind(name))
    if (auto reason = unsupported_reason(model, *kind)) {
      std::string message = "'" + name + "' " + *reason + " in model " + model.name;
      // A delay kind on a model without a delay: `delay: 0` (or none) is the undelayed model.
      const auto& observations = filter_kind_info(*kind).observations;
      const bool delay_kind = observations.size() == 1 && observations.front() == ObservationKind::Delayed;
      if (delay_kind && model.observation.kind() == ObservationKind::Continuous)
        message += " (the delay kinds need observation.delay h > 0; delay: 0, or none, is the undelayed model)";
      std::string known;
      for (const auto& filter : available) known += (known.empty() ? "" : ", ") + filter;
      return message + " (available: " + known + ")";
    }
  std::string known;
  for (const auto& filter : available) {
    if (filter == name) return std::nullopt;
    known += (known.empty() ? "" : ", ") + filter;
  }
  return "unknown filter '" + name + "' (known: " + known + ")";
}

}  // namespace pfgen
