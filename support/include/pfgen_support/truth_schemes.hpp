#pragma once
// The one table of truth scheme names: the runtime implements one scheme per row
// (pfgen_runtime::SchemeKind, in this order), the model file's `simulation.scheme` and
// `pfgen simulate --scheme` accept these names and `auto`, and the help texts and README list
// them; tests/test_kind_registry.cpp fails if any of those lists disagrees.
#include <string>
#include <vector>

namespace pfgen_support {

struct TruthSchemeInfo {
  std::string name;         // as `--scheme` takes it
  std::string description;  // one line
};

// Every scheme the runtime implements, in the order of pfgen_runtime::SchemeKind.
const std::vector<TruthSchemeInfo>& truth_schemes();

// The name `auto` (pfgen chooses a scheme for the model), then every name of truth_schemes().
std::vector<std::string> truth_scheme_choices();

}  // namespace pfgen_support
