#include "cli_options.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/model.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/model_validator.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace pfgen::cli {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t k = 0; k < parts.size(); ++k) out += (k ? separator : "") + parts[k];
  return out;
}

GiNaC::numeric parse_number(const std::string& option, const std::string& text) {
  auto value = parse_exact_number(text);
  if (!value) throw CliValueError(option + ": " + pfgen_support::quoted(text) + " " + unread_number_problem(text));
  // --phi 1e400 was accepted and reported later as "gain[1][1] is not finite", naming no option.
  if (auto problem = double_range_problem(*value))
    throw CliValueError(option + ": " + pfgen_support::quoted(text) + " " + *problem);
  return *value;
}

std::vector<GiNaC::numeric> parse_number_list(const std::string& option, const std::string& text) {
  std::vector<GiNaC::numeric> out;
  for (const auto& part : split(text, ',')) out.push_back(parse_number(option, part));
  if (out.empty()) throw CliValueError(option + ": no values given");
  return out;
}

std::vector<std::vector<GiNaC::numeric>> parse_number_matrix(const std::string& option, const std::string& text) {
  std::vector<std::vector<GiNaC::numeric>> out;
  for (const auto& row : split(text, ';')) out.push_back(parse_number_list(option, row));
  if (out.empty()) throw CliValueError(option + ": no values given");
  return out;
}

std::pair<std::string, GiNaC::numeric> parse_assignment(const std::string& option, const std::string& text) {
  std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw CliValueError(option + ": expected name=value, got " + pfgen_support::quoted(text));
  return {text.substr(0, eq), parse_number(option, text.substr(eq + 1))};
}

void apply_parameter_assignments(Model& model, const std::vector<std::string>& assignments) {
  std::set<std::string> given;
  for (const std::string& text : assignments) {
    const auto [name, value] = parse_assignment("--set", text);
    auto parameter = std::find_if(model.parameters.begin(), model.parameters.end(),
                                  [&name = name](const Parameter& p) { return p.name == name; });
    if (parameter == model.parameters.end())
      throw CliValueError("--set: model " + model.name + " has no parameter " + pfgen_support::quoted(name));
    if (!given.insert(name).second)
      throw CliValueError("--set: parameter " + pfgen_support::quoted(name) + " is given twice");
    parameter->default_value = value;
  }
  if (assignments.empty()) return;
  try {
    validate_model(model);
  } catch (const ModelError& e) {
    std::string where = "field '" + e.field() + "'";
    if (e.row()) where += ", row " + std::to_string(*e.row());
    if (e.column()) where += ", column " + std::to_string(*e.column());
    throw CliValueError("--set: with these values " + model.source + " is not valid: " + where + ": " + e.message());
  }
}

std::vector<std::string> parse_filter_list(const std::string& option, const std::string& text, const Model& model) {
  if (text.empty()) return default_filter_names(model);
  std::vector<std::string> out;
  for (const auto& name : split(text, ',')) {
    if (auto problem = filter_name_problem(model, name)) throw CliValueError(option + ": " + *problem);
    out.push_back(name);
  }
  return out;
}

}  // namespace pfgen::cli
