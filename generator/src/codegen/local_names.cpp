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

}  // namespace

LocalNames::LocalNames(std::set<std::string> inputs) : taken_(std::move(inputs)), temporary_prefix_("tmp") {
  auto clashes = [&] {
    return std::any_of(taken_.begin(), taken_.end(),
                       [&](const std::string& name) { return has_form(name, temporary_prefix_); });
  };
  while (clashes()) temporary_prefix_ += "_";
}

bool LocalNames::is_temporary(const std::string& name) const { return has_form(name, temporary_prefix_); }

std::string LocalNames::take(const std::string& preferred) {
  std::string name = preferred;
  while (taken_.count(name) || is_temporary(name)) name += "_";
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
