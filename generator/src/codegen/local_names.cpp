#include "pfgen/codegen/local_names.hpp"

#include <algorithm>
#include <cctype>

namespace pfgen::codegen {
namespace {

bool all_digits(const std::string& text) {
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

// prefix followed by digits only: the spelling of a temporary with that prefix.
bool has_form(const std::string& name, const std::string& prefix) {
  return name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
         all_digits(name.substr(prefix.size()));
}

std::set<std::string> parameters_and_time(const Model& model) {
  std::set<std::string> names;
  for (const auto& p : model.parameters) names.insert(p.name);
  names.insert(model.time.get_name());
  return names;
}

// The k-th spelling tried for `preferred` (k = 0, 1, ...): itself, then with '_', then with '_2',
// '_3', ...: a name never gets a second '_' in a row, since C++ reserves every name holding '__'
// (model names `shared` and `shared_` made the local `shared__`).
std::string candidate(const std::string& preferred, std::size_t k) {
  if (k == 0) return preferred;
  return preferred + "_" + (k == 1 ? "" : std::to_string(k));
}

}  // namespace

LocalNames::LocalNames(std::set<std::string> inputs) : taken_(std::move(inputs)) {
  auto clashes = [&] {
    return std::any_of(taken_.begin(), taken_.end(),
                       [&](const std::string& name) { return has_form(name, temporary_prefix_); });
  };
  // tmp, tmp_, tmp_2_, ...: a temporary is the prefix and digits, so a prefix after the first
  // ends in '_' to keep its number apart.
  for (std::size_t k = 0; k == 0 || clashes(); ++k) temporary_prefix_ = candidate("tmp", k) + (k < 2 ? "" : "_");
}

bool LocalNames::is_temporary(const std::string& name) const { return has_form(name, temporary_prefix_); }

std::string LocalNames::take(const std::string& preferred) {
  std::string name = preferred;
  for (std::size_t k = 1; taken_.count(name) || is_temporary(name); ++k) name = candidate(preferred, k);
  taken_.insert(name);
  return name;
}

std::set<std::string> filter_input_names(const Model& model) {
  std::set<std::string> names = parameters_and_time(model);
  for (const auto& name : filter_variable_names(model.n())) names.insert(name);
  return names;
}

std::set<std::string> truth_input_names(const Model& model) {
  std::set<std::string> names = parameters_and_time(model);
  names.insert(model.state_names.begin(), model.state_names.end());
  return names;
}

}  // namespace pfgen::codegen
