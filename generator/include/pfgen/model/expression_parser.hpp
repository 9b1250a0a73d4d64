#pragma once
// Turns the strings of a model file into GiNaC expressions over a fixed symbol
// table (states, parameters, time). Unknown names and syntax errors become
// ModelErrors naming the field and entry.
#include <ginac/ginac.h>
#include <optional>
#include <string>
#include <vector>

namespace pfgen {

struct ExpressionSite {
  std::string field;
  std::optional<int> row;     // 1-based
  std::optional<int> column;  // 1-based
};

class ExpressionParser {
 public:
  explicit ExpressionParser(const GiNaC::symtab& symbols);
  GiNaC::ex parse(const std::string& text, const ExpressionSite& site) const;

 private:
  GiNaC::symtab symbols_;
};

}  // namespace pfgen
