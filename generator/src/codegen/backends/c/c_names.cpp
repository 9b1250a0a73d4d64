#include "pfgen/codegen/backends/c/c_names.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <regex>

#include "pfgen/codegen/backends/c/c_backend.hpp"
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/codegen/observation_code.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen_support/content_hash.hpp"

namespace pfgen::codegen {
namespace {

bool is_word(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

bool is_header(const std::string& template_name) {
  return template_name.size() > 7 && template_name.compare(template_name.size() - 7, 7, ".h.tmpl") == 0;
}

// A name the model gives (its time, states, parameters, a filter's definitions) and its field.
struct ModelName {
  std::string name, field;
};

std::vector<ModelName> model_names(const Model& model) {
  std::vector<ModelName> names = {{model.time.get_name(), "time"}};
  for (const auto& state : model.state_names) names.push_back({state, "states"});
  for (const auto& p : model.parameters) names.push_back({p.name, "parameters." + p.name});
  for (const auto& filter : model.user_filters)
    for (const auto& d : filter.definitions)
      names.push_back({d.name.get_name(), "filters." + filter.name + ".define." + d.name.get_name()});
  return names;
}

bool is_user_filter(const Model& model, const std::string& filter) {
  return std::any_of(model.user_filters.begin(), model.user_filters.end(),
                     [&](const UserFilter& f) { return f.name == filter; });
}

// The field a clash between two filters' names is reported at: the model's own filter (a built-in
// kind's name is not the user's to change), the later one when both are the model's.
std::string clash_field(const Model& model, const std::string& first, const std::string& second) {
  if (is_user_filter(model, second)) return "filters." + second;
  if (is_user_filter(model, first)) return "filters." + first;
  return "name";
}

}  // namespace

CNameSuffixes c_name_suffixes(const std::vector<std::string>& templates) {
  static const std::string marker = "{{prefix}}_";
  CNameSuffixes suffixes;
  std::set<std::string> all;
  for (const std::string& name : templates) {
    const std::string text = expanded_template(name);
    for (std::size_t at = text.find(marker); at != std::string::npos; at = text.find(marker, at + 1)) {
      std::size_t end = at + marker.size();
      while (end < text.size() && is_word(text[end])) ++end;
      if (end == at + marker.size()) continue;
      const std::string suffix = text.substr(at + marker.size(), end - at - marker.size());
      all.insert(suffix);
      if (is_header(name) && end < text.size() && text[end] == '(') suffixes.external.insert(suffix);
    }
  }
  all.insert("h");  // the include guard, {{guard}}
  for (const std::string& suffix : all)
    if (!suffixes.external.count(suffix)) suffixes.internal.insert(suffix);
  return suffixes;
}

void check_c_names(const Model& model, const std::string& name_space) {
  const std::string spelled_space = std::regex_replace(name_space, std::regex("::"), "_");
  const std::string model_prefix = spelled_space + "_" + model.name + "_";
  const std::string file = source_place(model);
  // The namespace's part: a name of the model and the filters' are refused by the model room
  // already (reserved_names: no '__', nothing ending in '_').
  if (spelled_space.find("__") != std::string::npos || spelled_space.back() == '_')
    throw CodegenError("--namespace: '" + name_space + "' gives the C names the prefix '" + model_prefix +
                       "', and a name holding '__' is reserved (in C++, which the headers serve too); "
                       "give parts that neither start nor end with '_'");
  for (const ModelName& name : model_names(model))
    if (name.name.rfind(model_prefix, 0) == 0)
      throw CodegenError(file + name.field + ": '" + name.name + "' starts with '" + model_prefix +
                         "', the prefix of every name the generated C code declares (include guards, enum "
                         "constants, functions), which it would replace or hide; give it another name");

  const ObservationCode& part = observation_code(model.observation);
  const std::vector<std::string> templates = c_module_templates(part);
  const CNameSuffixes suffixes = c_name_suffixes(templates);
  std::map<std::string, std::string> declared;          // name -> the filter declaring it
  std::vector<std::pair<std::string, std::string>> internal;  // (name, filter)
  for (const std::string& filter : available_filter_names(model)) {
    const std::string prefix = c_symbol_prefix(name_space, model.name, filter);
    for (const auto* kind : {&suffixes.external, &suffixes.internal})
      for (const std::string& suffix : *kind) {
        const std::string name = prefix + "_" + suffix;
        const auto [it, fresh] = declared.emplace(name, filter);
        if (!fresh && it->second != filter)
          throw CodegenError(file + clash_field(model, it->second, filter) + ": filters '" + it->second +
                             "' and '" + filter + "' would both declare the C name '" + name +
                             "', so their files could not be built into one program; give the model's filter "
                             "another name");
        if (kind == &suffixes.internal) internal.emplace_back(name, filter);
      }
  }
  // Names equal in their first 63 characters sort next to each other.
  std::sort(internal.begin(), internal.end());
  const std::size_t limit = kCSignificantInternalCharacters;
  for (std::size_t k = 1; k < internal.size(); ++k) {
    const std::string& a = internal[k - 1].first;
    const std::string& b = internal[k].first;
    if (a != b && a.size() >= limit && b.size() >= limit && a.compare(0, limit, b, 0, limit) == 0)
      throw CodegenError(file + "name: the C names '" + a + "' and '" + b + "' agree in their first " +
                         std::to_string(limit) + " characters, all that C99 promises to tell apart in an "
                         "enum constant, a typedef, a macro or a static function; give the model (" +
                         std::to_string(model.name.size()) + " characters), its filters or --namespace shorter names");
  }
}

std::string c_part_name(const std::string& prefix, const std::string& function, std::size_t k) {
  const std::string tail = "_" + function + "_part" + std::to_string(k);
  if (prefix.size() + tail.size() <= kCSignificantInternalCharacters) return prefix + tail;
  // The prefix's head, and at the end 8 hex digits of the whole prefix's hash, which tell filters (and
  // models) with the same head apart when their files are built as one translation unit. At the end, since
  // no name made whole ends so: a filter or model named <head>_<hash> would meet <head>_<hash>_..._part<k>.
  const std::string tag = "_" + pfgen_support::ContentHash().add(prefix).hex().substr(0, 8);
  const std::size_t room = kCSignificantInternalCharacters - std::min(kCSignificantInternalCharacters, tag.size() + tail.size());
  std::string head = prefix.substr(0, room);
  while (!head.empty() && head.back() == '_') head.pop_back();  // "__" is reserved
  if (head.empty())
    throw CPartNameError("the C name of a part of the split function " + function + " cannot be made within " +
                         std::to_string(kCSignificantInternalCharacters) + " characters; write the function whole "
                         "(--max-function-ops 0)");
  return head + tail + tag;
}

}  // namespace pfgen::codegen
