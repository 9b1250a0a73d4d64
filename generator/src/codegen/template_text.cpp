#include "pfgen/codegen/template_text.hpp"

#include <set>
#include <stdexcept>

namespace pfgen::codegen {
namespace {

// `{{> PATH}}` is replaced by the embedded template PATH (a partial shared by several templates),
// itself expanded; a line holding only the include takes the partial's own final newline. Partials
// nest at most kMaxIncludeDepth deep, so a cycle is an error, not a hang.
constexpr int kMaxIncludeDepth = 8;

std::string expand_includes(const std::string& name, const std::string& text, int depth) {
  if (depth > kMaxIncludeDepth) throw std::logic_error(name + ": partials nest too deep (a cycle?)");
  std::string out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t open = text.find("{{>", pos);
    if (open == std::string::npos) break;
    const std::size_t close = text.find("}}", open);
    if (close == std::string::npos) throw std::logic_error(name + ": unterminated include");
    std::string path = text.substr(open + 3, close - open - 3);
    path.erase(0, path.find_first_not_of(' '));
    path.erase(path.find_last_not_of(' ') + 1);
    out.append(text, pos, open - pos);
    out += expand_includes(path, embedded_template(path), depth + 1);
    pos = close + 2;
    if (pos < text.size() && text[pos] == '\n' && !out.empty() && out.back() == '\n') ++pos;
  }
  out.append(text, pos, std::string::npos);
  return out;
}

}  // namespace

std::string expanded_template(const std::string& relative_path) {
  return expand_includes(relative_path, embedded_template(relative_path), 0);
}

std::string fill_template(const std::string& name, const std::string& raw_text,
                          const std::map<std::string, std::string>& values) {
  const std::string text = expand_includes(name, raw_text, 0);
  std::string out;
  std::set<std::string> used;
  std::size_t pos = 0;
  while (true) {
    std::size_t open = text.find("{{", pos);
    if (open == std::string::npos) break;
    std::size_t close = text.find("}}", open);
    if (close == std::string::npos) throw std::logic_error(name + ": unterminated placeholder");
    std::string key = text.substr(open + 2, close - open - 2);
    auto it = values.find(key);
    if (it == values.end()) throw std::logic_error(name + ": no value for placeholder {{" + key + "}}");
    out.append(text, pos, open - pos);
    out += it->second;
    used.insert(key);
    pos = close + 2;
  }
  out.append(text, pos, std::string::npos);
  for (const auto& [key, value] : values)
    if (!used.count(key)) throw std::logic_error(name + ": value for {{" + key + "}} has no placeholder");
  return out;
}

std::map<std::string, std::string> values_in_template(const std::string& relative_path,
                                                      const std::map<std::string, std::string>& values) {
  const std::string text = expanded_template(relative_path);
  std::map<std::string, std::string> used;
  for (const auto& [key, value] : values)
    if (text.find("{{" + key + "}}") != std::string::npos) used.emplace(key, value);
  return used;
}

std::string filled_template(const std::string& relative_path, const std::map<std::string, std::string>& values) {
  return fill_template(relative_path, embedded_template(relative_path), values_in_template(relative_path, values));
}

}  // namespace pfgen::codegen
