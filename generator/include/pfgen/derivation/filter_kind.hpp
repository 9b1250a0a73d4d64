#pragma once
#include <optional>
#include <string>
#include <vector>

namespace pfgen {

struct Model;

// The filters pfgen derives from one model (see README, "Filter kinds").
enum class FilterKind { Optimal, Ekf, Additive, EkfAdditive };

std::string filter_kind_name(FilterKind kind);  // "optimal", "ekf", "additive", "ekf-additive"
std::optional<FilterKind> parse_filter_kind(const std::string& name);
std::string filter_kind_description(FilterKind kind);
bool uses_additive_diffusion(FilterKind kind);
bool is_extended_kalman(FilterKind kind);
// Every kind the model supports, in the canonical order above: the additive
// kinds need the model's additive_diffusion.
std::vector<FilterKind> supported_filter_kinds(const Model& model);

}  // namespace pfgen
