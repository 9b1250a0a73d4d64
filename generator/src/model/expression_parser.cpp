#include "pfgen/model/expression_parser.hpp"

#include <cctype>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "pfgen/kinds/model_functions.hpp"
#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/expression_limits.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/text_characters.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace pfgen {
namespace {

// GiNaC's parser knows the literals I, Pi, Euler and Catalan and a set of functions. Complex
// numbers have no place in a real SDE.
bool has_imaginary_part(const GiNaC::ex& e) { return e.has(GiNaC::I); }

// The literals GiNaC's lexer reads as its constants whatever the symbol table holds: outside a
// model's names, Pi, Euler and Catalan are those constants in a model file too, and I is refused
// as not real.
bool is_ginac_literal(const std::string& name) {
  return name == "Pi" || name == "Euler" || name == "Catalan" || name == "I";
}

// One name in an expression's text: where it is, and whether a '(' follows (a function call).
struct Identifier {
  std::size_t begin = 0, end = 0;
  bool is_call = false;
};

// The names of `text` in order, as GiNaC's lexer cuts them ([A-Za-z_][A-Za-z0-9_]*), numbers
// such as 1e-3 skipped whole so that their 'e' is no name.
std::vector<Identifier> identifiers(const std::string& text) {
  std::vector<Identifier> found;
  std::size_t i = 0;
  while (i < text.size()) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isalpha(c) || c == '_') {
      std::size_t j = i;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      std::size_t k = j;
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      found.push_back({i, j, k < text.size() && text[k] == '('});
      i = j;
    } else if (std::isdigit(c) || c == '.') {
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
    } else {
      ++i;
    }
  }
  return found;
}

// Why `text` names something the model does not have: a name that is not the model's (nor one of
// GiNaC's constants), or a call of a function that is not one a model may call; or nothing.
std::optional<std::string> unknown_name_problem(const std::string& text, const GiNaC::symtab& symbols) {
  for (const Identifier& identifier : identifiers(text)) {
    const std::string name = text.substr(identifier.begin, identifier.end - identifier.begin);
    if (!identifier.is_call && symbols.find(name) == symbols.end() && !is_ginac_literal(name))
      return "unknown symbol " + pfgen_support::quoted(name) + " in " + pfgen_support::quoted(text);
    // GiNaC's parser knows more functions (zeta, psi, step, Li2, ...): eval could compute them,
    // no generated code could.
    if (identifier.is_call && !model_function(name) && name != "sqrt" && name != "pow")
      return "unknown function " + pfgen_support::quoted(name) + " in " + pfgen_support::quoted(text) +
             "; a model may call " + model_function_list() + " (those C++'s <cmath> and C's <math.h> both have)";
  }
  return std::nullopt;
}

// The text GiNaC's parser reads, with every name of the model replaced by an alias of the same
// symbol: GiNaC gives some names a meaning of its own whatever the symbol table says (its lexer
// reads I, Pi, Euler and Catalan as its constants), and a model's name is the model's symbol,
// whatever GiNaC calls it (an SIR model's state I). The aliases are "a0", "a1", ... in the order the
// names first appear: no name of the model is left in the text for one to meet, GiNaC reads them
// as plain names, and they stand for the symbols, which keep the user's names for every printer.
// A name followed by '(' is a function call and stays; so do GiNaC's constants outside the model.
// `alias_of` maps each name replaced to its alias.
std::string with_aliases(const std::string& text, const GiNaC::symtab& symbols, GiNaC::symtab& aliases,
                         std::map<std::string, std::string>& alias_of) {
  std::string out;
  std::size_t copied = 0;
  for (const Identifier& identifier : identifiers(text)) {
    if (identifier.is_call) continue;
    const std::string name = text.substr(identifier.begin, identifier.end - identifier.begin);
    const auto symbol = symbols.find(name);
    if (symbol == symbols.end()) continue;
    auto [alias, added] = alias_of.emplace(name, "a" + std::to_string(alias_of.size()));
    if (added) aliases[alias->second] = symbol->second;
    out.append(text, copied, identifier.begin - copied);
    out += alias->second;
    copied = identifier.end;
  }
  out.append(text, copied, std::string::npos);
  return out;
}

// GiNaC's message is "GiNaC: parse error at line 0, column 0: WHY\n[function(file:line)]":
// keep WHY only, so that the error stays on one line and names no GiNaC internals, and with the
// model's names where WHY quotes an alias ('expected EOF, got: "a1"').
std::string parse_error_reason(const std::string& message, const std::map<std::string, std::string>& alias_of) {
  std::string why = message.substr(0, message.find('\n'));
  const std::string prefix = "GiNaC: parse error at ";
  if (why.compare(0, prefix.size(), prefix) == 0) {
    std::size_t colon = why.find(": ", prefix.size());
    if (colon != std::string::npos) why = why.substr(colon + 2);
  }
  while (!why.empty() && (why.back() == ' ' || why.back() == '\r')) why.pop_back();
  if (why.empty()) return "syntax error";
  // GiNaC quotes a token by its code, which for its constants is no character: got: "\xfa".
  const auto quote = why.find("got: \"");
  if (quote != std::string::npos && quote + 7 < why.size() && why[quote + 7] == '"' &&
      !std::isprint(static_cast<unsigned char>(why[quote + 6])))
    why.replace(quote, 8, "got: a constant (I, Pi, Euler or Catalan)");
  std::map<std::string, std::string> name_of;
  for (const auto& [name, alias] : alias_of) name_of[alias] = name;
  std::string out;
  std::size_t copied = 0;
  for (const Identifier& identifier : identifiers(why)) {
    const auto name = name_of.find(why.substr(identifier.begin, identifier.end - identifier.begin));
    if (name == name_of.end()) continue;
    out.append(why, copied, identifier.begin - copied);
    out += name->second;
    copied = identifier.end;
  }
  return out.append(why, copied, std::string::npos);
}

}  // namespace

ExpressionParser::ExpressionParser(const GiNaC::symtab& symbols) : symbols_(symbols) {}

GiNaC::ex ExpressionParser::parse(const std::string& text, const ExpressionSite& site) const {
  auto fail = [&](const std::string& why) {
    return ModelError(site.field, why, site.row, site.column);
  };
  std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) throw fail("empty expression");
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 && c != ' ' && c != '\t')
      throw fail("expression contains a control character");
  }
  if (auto character = first_non_ascii(text))
    throw fail(pfgen_support::quoted(text) + " contains " + *character +
               "; expressions are ASCII: names of letters, digits and _, numbers, + - * / ^ ( ) ,");
  // Before GiNaC's parser, which recurses per nesting level and evaluates numeric powers at once.
  if (auto problem = expression_limit_problem(text)) throw fail(*problem);
  if (auto problem = unknown_name_problem(text, symbols_)) throw fail(*problem);
  GiNaC::symtab aliases;
  std::map<std::string, std::string> alias_of;
  const std::string aliased = with_aliases(text, symbols_, aliases, alias_of);
  GiNaC::parser reader(aliases, /*strict=*/true);
  GiNaC::ex value;
  try {
    value = reader(rationalize_decimal_literals(aliased));
  } catch (const GiNaC::parse_error& e) {
    throw fail("cannot parse " + pfgen_support::quoted(text) + ": " + parse_error_reason(e.what(), alias_of));
  } catch (const std::exception& e) {
    // GiNaC's parser reads a^b^c as a power of three operands and fails while evaluating it.
    if (std::string(e.what()).find("power should have exactly 2 operands") != std::string::npos)
      throw fail("cannot parse " + pfgen_support::quoted(text) + ": a power of a power needs parentheses, (a^b)^c or a^(b^c)");
    throw fail("cannot evaluate " + pfgen_support::quoted(text) + ": " + e.what());
  }
  if (has_imaginary_part(value)) throw fail(pfgen_support::quoted(text) + " is not real");
  // A number no double holds (1e-400 would be 0 in generated code and simulation, 1e400 infinite).
  for (GiNaC::const_preorder_iterator it = value.preorder_begin(); it != value.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::numeric>(*it))
      if (auto problem = double_range_problem(GiNaC::ex_to<GiNaC::numeric>(*it)))
        throw fail(pfgen_support::quoted(text) + " holds a number, about " + approximate_text(GiNaC::ex_to<GiNaC::numeric>(*it)) + ", that " + *problem);
  return value;
}

}  // namespace pfgen
