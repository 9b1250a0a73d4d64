#include "pfgen/notation/expression_printer.hpp"

#include <algorithm>
#include <optional>

#include "pfgen/notation/polynomial_writer.hpp"

namespace pfgen {
namespace {

bool is_negative_integer_power(const GiNaC::ex& e) {
  return GiNaC::is_exactly_a<GiNaC::power>(e) && e.op(1).info(GiNaC::info_flags::negint);
}

}  // namespace

std::optional<CanonicalSumFactor> canonical_sum_factor(const GiNaC::ex& factor, const ExpressionPrinter& printer) {
  long exponent = 1;
  GiNaC::ex sum = factor;
  if (!GiNaC::is_exactly_a<GiNaC::add>(factor)) {
    if (!GiNaC::is_exactly_a<GiNaC::power>(factor) || !GiNaC::is_exactly_a<GiNaC::add>(factor.op(0))) return std::nullopt;
    if (!factor.op(1).info(GiNaC::info_flags::integer)) return std::nullopt;
    const GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(factor.op(1));
    if (k.is_zero() || GiNaC::abs(k) > GiNaC::numeric(1L << 30)) return std::nullopt;
    exponent = k.to_long();
    sum = factor.op(0);
  }
  std::string text = printer.print(sum);
  if (text.empty() || text.front() != '-') return CanonicalSumFactor{sum, std::move(text), exponent, false};
  const GiNaC::ex negated = -sum;  // a sum again: GiNaC multiplies a lone sum's terms out
  return CanonicalSumFactor{negated, printer.print(negated), exponent, true};
}

std::string ExpressionPrinter::print(const GiNaC::ex& e) const {
  std::vector<Term> terms;
  if (GiNaC::is_exactly_a<GiNaC::add>(e)) {
    for (std::size_t k = 0; k < e.nops(); ++k) terms.push_back(to_term(e.op(k)));
  } else {
    terms.push_back(to_term(e));
  }
  // Coefficient expressions have no variable order of their own: sort by text.
  std::stable_sort(terms.begin(), terms.end(), [this](const Term& a, const Term& b) {
    std::string ka = print_term_body(a), kb = print_term_body(b);
    if (ka != kb) return ka < kb;
    return a.negative < b.negative;
  });
  return print_sum(terms);
}

// Terms in Polynomial::ordered_view's order; a coefficient that is a sum is one parenthesised
// factor. PolynomialWriter does the work (and keeps what repeats across many polynomials).
std::string ExpressionPrinter::print(const Polynomial& p, const VariableNamer& name) const {
  return PolynomialWriter(*this, name).print(p);
}

std::string ExpressionPrinter::print_sum(std::vector<Term> terms) const {
  if (terms.empty()) return "0";
  std::string out;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    const Term& term = terms[k];
    if (k == 0) {
      out += term.negative ? "-" : "";
    } else {
      out += term.negative ? " - " : " + ";
    }
    out += print_term_body(term);
  }
  return out;
}

std::string ExpressionPrinter::join_factors(const std::vector<std::string>& factors) const {
  std::vector<const std::string*> pointers;
  pointers.reserve(factors.size());
  for (const std::string& factor : factors) pointers.push_back(&factor);
  std::string out;
  append_factors(out, pointers.data(), pointers.size());
  return out;
}

std::string ExpressionPrinter::print_term_body(const Term& term) const {
  std::vector<std::string> numerator;
  if (term.magnitude != 1 || term.numerator_factors.empty()) numerator.push_back(number(term.magnitude));
  numerator.insert(numerator.end(), term.numerator_factors.begin(), term.numerator_factors.end());
  std::string top = join_factors(numerator);
  if (term.denominator_factors.empty()) return top;
  return quotient(top, join_factors(term.denominator_factors));
}

ExpressionPrinter::Term ExpressionPrinter::to_term(const GiNaC::ex& e) const {
  Term term;
  auto absorb = [&](const GiNaC::ex& factor) {
    if (GiNaC::is_exactly_a<GiNaC::numeric>(factor)) {
      GiNaC::numeric value = GiNaC::ex_to<GiNaC::numeric>(factor);
      if (value.is_negative()) {
        term.negative = !term.negative;
        value = -value;
      }
      term.magnitude *= value;
    } else if (const std::optional<CanonicalSumFactor> sum = canonical_sum_factor(factor, *this)) {
      // The sum with pfgen's sign, not GiNaC's run-dependent one; an odd power's sign goes to the term.
      if (sum->flips_sign()) term.negative = !term.negative;
      const std::string base = parenthesized(sum->text);
      if (sum->exponent > 0) {
        term.numerator_factors.push_back(print_integer_power(base, sum->exponent));
      } else {
        term.denominator_factors.push_back(print_integer_power(base, -sum->exponent));
      }
    } else if (is_negative_integer_power(factor)) {
      long exponent = -GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).to_long();
      term.denominator_factors.push_back(print_integer_power(print_factor(factor.op(0)), exponent));
    } else {
      term.numerator_factors.push_back(print_factor(factor));
    }
  };
  if (GiNaC::is_exactly_a<GiNaC::mul>(e)) {
    for (std::size_t k = 0; k < e.nops(); ++k) absorb(e.op(k));
  } else {
    absorb(e);
  }
  std::sort(term.numerator_factors.begin(), term.numerator_factors.end());
  std::sort(term.denominator_factors.begin(), term.denominator_factors.end());
  return term;
}

std::string ExpressionPrinter::print_factor(const GiNaC::ex& e) const {
  if (GiNaC::is_exactly_a<GiNaC::symbol>(e)) return symbol_name(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
  if (GiNaC::is_exactly_a<GiNaC::constant>(e)) return constant(e);
  if (GiNaC::is_exactly_a<GiNaC::numeric>(e)) {
    const auto& value = GiNaC::ex_to<GiNaC::numeric>(e);
    std::string text = number(GiNaC::abs(value));
    if (value.is_negative() || !value.is_integer()) return parenthesized((value.is_negative() ? "-" : "") + text);
    return text;
  }
  if (GiNaC::is_a<GiNaC::function>(e)) {
    std::vector<std::string> args;
    for (std::size_t k = 0; k < e.nops(); ++k) args.push_back(print(e.op(k)));
    return function_call(GiNaC::ex_to<GiNaC::function>(e).get_name(), args);
  }
  if (GiNaC::is_exactly_a<GiNaC::power>(e)) {
    const GiNaC::ex& base = e.op(0);
    const GiNaC::ex& exponent = e.op(1);
    bool simple_base = GiNaC::is_exactly_a<GiNaC::symbol>(base) || GiNaC::is_a<GiNaC::function>(base) ||
                       GiNaC::is_exactly_a<GiNaC::constant>(base) ||
                       (GiNaC::is_exactly_a<GiNaC::numeric>(base) && GiNaC::ex_to<GiNaC::numeric>(base).is_pos_integer());
    std::string base_text = simple_base ? print_factor(base) : parenthesized(print(base));
    if (exponent.info(GiNaC::info_flags::posint))
      return print_integer_power(base_text, GiNaC::ex_to<GiNaC::numeric>(exponent).to_long());
    return power(base_text, print(exponent));
  }
  return parenthesized(print(e));
}

std::string ExpressionPrinter::print_integer_power(const std::string& base, long exponent) const {
  if (exponent == 1) return base;
  return power(base, std::to_string(exponent));
}

}  // namespace pfgen
