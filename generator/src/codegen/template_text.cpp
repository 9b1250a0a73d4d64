#include "pfgen/codegen/template_text.hpp"

#include <set>
#include <stdexcept>

namespace pfgen::codegen {

std::string fill_template(const std::string& name, const std::string& text,
                          const std::map<std::string, std::string>& values) {
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

}  // namespace pfgen::codegen
