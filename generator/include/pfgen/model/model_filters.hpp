#pragma once
// The filters a model offers, by name: the built-in kinds of the registry
// (kinds/filter_kinds.hpp) that it supports, then its own filters (`filters:`) in file order.
// The validator, the derivation and the command line all ask here, so they agree.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// What the registry's rules need to know of the model.
FilterKindNeeds filter_kind_needs(const Model& model);

// Why `kind` cannot be derived for this model, or nothing.
std::optional<std::string> unsupported_reason(const Model& model, FilterKind kind);

// Every kind the model supports, in the registry's order.
std::vector<FilterKind> supported_filter_kinds(const Model& model);

// The names of supported_filter_kinds(), then the model's user filters in file order.
std::vector<std::string> available_filter_names(const Model& model);

// What derive/latex/codegen/simulate use when no filter is named: available_filter_names()
// without the kinds the registry keeps out of the defaults (FilterKindInfo::in_defaults, the ukf),
// which a user names to get.
std::vector<std::string> default_filter_names(const Model& model);

// Why `name` is not a filter of the model, in the words every command and the validator use
// ("unknown filter 'kalman' (known: optimal, ekf)", "'additive' needs additive_diffusion or
// additive_diffusion_covariance in model m"), or nothing when it is one.
// A sampled model's filter may also be named KIND@S, S a whole number from 1 to 1000000: the
// kind with S prediction sub-steps per period instead of the model's `substeps`
// ("cd-euler@1" is paper 003's discrete-discrete filter), so that one simulation can compare
// sub-step counts on the same truths.
std::optional<std::string> filter_name_problem(const Model& model, const std::string& name);

// NAME@S split into NAME and S; nothing when the name has no '@'. std::invalid_argument (with a
// message naming the filter) when what follows '@' is not a whole number from 1 to 1000000.
std::optional<std::pair<std::string, std::size_t>> split_substeps(const std::string& name);

}  // namespace pfgen
