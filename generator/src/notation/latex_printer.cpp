#include "pfgen/notation/latex_printer.hpp"

#include <set>
#include <sstream>

#include "pfgen/notation/number_format.hpp"

namespace pfgen {
namespace {

const std::set<std::string> kGreek = {
    "alpha", "beta",  "gamma", "delta", "epsilon", "zeta",  "eta",   "theta", "iota",  "kappa",  "lambda",
    "mu",    "nu",    "xi",    "pi",    "rho",     "sigma", "tau",   "upsilon", "phi", "chi",    "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda",  "Xi",    "Pi",    "Sigma", "Upsilon", "Phi",  "Psi", "Omega"};

const std::set<std::string> kLatexFunctions = {"sin",  "cos",  "tan",  "exp",  "log",  "sinh", "cosh",
                                               "tanh", "arcsin", "arccos", "arctan"};

std::string escape_underscores(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '_' ? std::string("\\_") : std::string(1, c);
  return out;
}

std::string base_name(const std::string& name) {
  if (kGreek.count(name)) return "\\" + name;
  if (name.size() == 1) return name;
  return "\\mathrm{" + escape_underscores(name) + "}";
}

}  // namespace

std::string LatexPrinter::number(const GiNaC::numeric& value) const {
  if (!value.is_rational()) return shortest_double(value.to_double());
  std::string decimal = exact_decimal(value);
  if (!decimal.empty()) return decimal;
  std::ostringstream out;
  out << "\\frac{" << value.numer() << "}{" << value.denom() << "}";
  return out.str();
}

std::string LatexPrinter::symbol_name(const std::string& name) const {
  // x_1 -> x_{1}; x1 -> x_{1}; alpha_2 -> \alpha_{2}
  std::size_t underscore = name.find('_');
  if (underscore != std::string::npos && underscore > 0 && underscore + 1 < name.size())
    return base_name(name.substr(0, underscore)) + "_{" + escape_underscores(name.substr(underscore + 1)) + "}";
  std::size_t digits = name.find_first_of("0123456789");
  if (digits != std::string::npos && digits > 0 && name.find_first_not_of("0123456789", digits) == std::string::npos)
    return base_name(name.substr(0, digits)) + "_{" + name.substr(digits) + "}";
  return base_name(name);
}

std::string LatexPrinter::power(const std::string& base, const std::string& exponent) const {
  return base + "^{" + exponent + "}";
}

void LatexPrinter::append_factors(std::string& out, const std::string* const* factors, std::size_t count) const {
  for (std::size_t k = 0; k < count; ++k) {
    if (k) out += "\\,";
    out += *factors[k];
  }
}

std::string LatexPrinter::quotient(const std::string& numerator, const std::string& denominator) const {
  return "\\frac{" + numerator + "}{" + denominator + "}";
}

std::string LatexPrinter::function_call(const std::string& name, const std::vector<std::string>& args) const {
  std::string out = kLatexFunctions.count(name) ? "\\" + name : "\\operatorname{" + escape_underscores(name) + "}";
  out += "\\left(";
  for (std::size_t k = 0; k < args.size(); ++k) out += (k ? ", " : "") + args[k];
  return out + "\\right)";
}

std::string LatexPrinter::parenthesized(const std::string& inner) const { return "\\left(" + inner + "\\right)"; }

std::string LatexPrinter::constant(const GiNaC::ex& c) const {
  std::ostringstream out;
  out << GiNaC::latex << c;
  return out.str();
}

std::string latex_escape_text(const std::string& text) {
  std::string out;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    switch (c) {
      case '&': case '%': case '$': case '#': case '_': case '{': case '}': out += std::string("\\") + c; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '\\': out += "\\textbackslash{}"; break;
      // The OT1 text fonts put other glyphs at these positions (h > 0 would print as h ¿ 0, a | b
      // as a — b): the text commands take them from fonts that have them.
      case '<': out += "\\textless{}"; break;
      case '>': out += "\\textgreater{}"; break;
      case '|': out += "\\textbar{}"; break;
      case '"': out += "{\\ttfamily\\char34}"; break;  // a straight double quote; OT1 has none in roman
      case '`': out += "\\textasciigrave{}"; break;
      // "--" would join into a dash.
      case '-': out += (k + 1 < text.size() && text[k + 1] == '-') ? "-{}" : "-"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace pfgen
