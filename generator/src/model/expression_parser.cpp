#include "pfgen/model/expression_parser.hpp"

#include <cctype>
#include <sstream>

#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/expression_limits.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/text_characters.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace pfgen {
namespace {

// GiNaC's parser accepts only what a model may contain once unknown names are
// rejected; but it also knows the literals I, Pi, Euler and Catalan and a set of
// functions. Complex numbers have no place in a real SDE.
bool has_imaginary_part(const GiNaC::ex& e) { return e.has(GiNaC::I); }

std::string first_identifier_not_in(const std::string& text, const GiNaC::symtab& symbols) {
  std::size_t i = 0;
  while (i < text.size()) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isalpha(c) || c == '_') {
      std::size_t j = i;
      while (j < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
        ++j;
      std::string name = text.substr(i, j - i);
      std::size_t k = j;
      while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      bool is_call = k < text.size() && text[k] == '(';
      if (!is_call && symbols.find(name) == symbols.end() && name != "Pi" && name != "Euler" &&
          name != "Catalan" && name != "I")
        return name;
      i = j;
    } else if (std::isdigit(c) || c == '.') {
      // Skip numbers, including exponents such as 1e-3, so 'e' is not a name.
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '.'))
        ++i;
    } else {
      ++i;
    }
  }
  return {};
}

// GiNaC's message is "GiNaC: parse error at line 0, column 0: WHY\n[function(file:line)]":
// keep WHY only, so that the error stays on one line and names no GiNaC internals.
std::string parse_error_reason(const std::string& message) {
  std::string why = message.substr(0, message.find('\n'));
  const std::string prefix = "GiNaC: parse error at ";
  if (why.compare(0, prefix.size(), prefix) == 0) {
    std::size_t colon = why.find(": ", prefix.size());
    if (colon != std::string::npos) why = why.substr(colon + 2);
  }
  while (!why.empty() && (why.back() == ' ' || why.back() == '\r')) why.pop_back();
  return why.empty() ? "syntax error" : why;
}

// A number's order of magnitude for a message: 1/10^400 as 1.0E-400, not as its 401 digits.
std::string approximately(const GiNaC::ex& number) {
  std::ostringstream out;
  out << GiNaC::ex(number).evalf();
  std::string text = out.str();
  const auto exponent = text.find('E');
  const auto dot = text.find('.');
  if (dot != std::string::npos && exponent != std::string::npos && exponent > dot + 3)
    text.erase(dot + 3, exponent - dot - 3);
  return text;
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
  std::string unknown = first_identifier_not_in(text, symbols_);
  if (!unknown.empty()) throw fail("unknown symbol " + pfgen_support::quoted(unknown) + " in " + pfgen_support::quoted(text));
  GiNaC::parser reader(symbols_, /*strict=*/true);
  GiNaC::ex value;
  try {
    value = reader(rationalize_decimal_literals(text));
  } catch (const GiNaC::parse_error& e) {
    throw fail("cannot parse " + pfgen_support::quoted(text) + ": " + parse_error_reason(e.what()));
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
        throw fail(pfgen_support::quoted(text) + " holds a number, about " + approximately(*it) + ", that " + *problem);
  return value;
}

}  // namespace pfgen
