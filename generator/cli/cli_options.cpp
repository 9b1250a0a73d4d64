#include "cli_options.hpp"

#include <sstream>

#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::cli {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.push_back("");
  return parts;
}

GiNaC::numeric parse_number(const std::string& option, const std::string& text) {
  auto value = parse_exact_number(text);
  if (!value) throw CliValueError(option + ": '" + text + "' is not a number");
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
    throw CliValueError(option + ": expected name=value, got '" + text + "'");
  return {text.substr(0, eq), parse_number(option, text.substr(eq + 1))};
}

std::vector<std::string> parse_filter_list(const std::string& option, const std::string& text, const Model& model) {
  std::vector<std::string> available = available_filter_names(model);
  if (text.empty()) return available;
  std::vector<std::string> out;
  for (const auto& name : split(text, ',')) {
    bool ok = false;
    for (const auto& a : available) ok = ok || a == name;
    if (ok) {
      out.push_back(name);
      continue;
    }
    if (parse_filter_kind(name))
      throw CliValueError(option + ": '" + name + "' needs additive_diffusion or additive_diffusion_covariance in model " +
                          model.name);
    std::string user;
    for (const auto& filter : model.user_filters) user += ", " + filter.name;
    throw CliValueError(option + ": unknown filter kind '" + name + "' (known: optimal, ekf, additive, ekf-additive" +
                        (user.empty() ? "" : "; model " + model.name + " also defines " + user.substr(2)) + ")");
  }
  return out;
}

}  // namespace pfgen::cli
