#pragma once
// Which published condition makes the Gaussian closure exact for a model
// (docs/theory.md §4), or which condition failed, so that a user knows whether
// the derived filter is optimal or a Gaussian assumed-density approximation.
#include <string>
#include <vector>

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

struct ExactnessReport {
  bool exact = false;
  std::string condition;                // short name of the condition that holds, or "none"
  std::string explanation;              // one sentence for the user, rich text (notation/rich_text.hpp)
  std::vector<std::string> failed;      // each failed condition with its reason, rich text
};

ExactnessReport assess_exactness(const Model& model, FilterKind kind);

}  // namespace pfgen
