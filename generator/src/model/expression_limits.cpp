#include "pfgen/model/expression_limits.hpp"

#include "pfgen/notation/number_format.hpp"

#include <algorithm>
#include <iterator>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace pfgen {
namespace {

// What the estimate knows of a subexpression: whether it is one number (and roughly which),
// the digits of its numeric coefficients, and how many terms its expansion has.
struct Estimate {
  bool constant = false;
  double value = 0;   // when constant; may be inf
  double digits = 0;  // log10 of numerator plus log10 of denominator, largest coefficient
  double terms = 1;   // terms of the expanded polynomial (capped by double's range, inf beyond)
};

// Follows GiNaC's grammar: sum of products of signed powers of numbers, names, calls and
// parenthesised sums. The recursion is bounded by the limits it checks.
class Estimator {
 public:
  explicit Estimator(const std::string& text) : text_(text) {}

  std::optional<std::string> run() {
    sum();
    return problem_;
  }

 private:
  const std::string& text_;
  std::size_t at_ = 0;
  int nesting_ = 0;  // signs and exponents around the current position
  std::optional<std::string> problem_;
  bool failed_ = false;  // a syntax error, or a problem found: stop

  char peek() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
    return at_ < text_.size() ? text_[at_] : '\0';
  }

  void check(const Estimate& e, std::size_t from) {
    if (failed_ || !(e.digits > kMaxConstantDigits)) return;
    std::string part = text_.substr(from, at_ - from);
    if (part.size() > 60) part = part.substr(0, 57) + "...";
    problem_ = "'" + part + "' gives a number of " + (std::isfinite(e.digits) ? "about " + three_digits(e.digits) : "more than 1e+308") +
               " digits; numbers are limited to " + std::to_string(static_cast<long>(kMaxConstantDigits)) + " digits";
    failed_ = true;
  }

  Estimate sum() {
    const std::size_t from = at_;
    Estimate a = product();
    while (!failed_ && (peek() == '+' || peek() == '-')) {
      const char op = text_[at_++];
      const Estimate b = product();
      if (a.constant && b.constant) {
        a.value = op == '+' ? a.value + b.value : a.value - b.value;
        a.digits = std::max(a.digits, b.digits) + std::log10(2.0);
      } else {
        a.constant = false;
        a.digits = std::max(a.digits, b.digits);
        a.terms += b.terms;
      }
      check(a, from);
    }
    return a;
  }

  Estimate product() {
    const std::size_t from = at_;
    Estimate a = unary();
    while (!failed_ && (peek() == '*' || peek() == '/')) {
      const char op = text_[at_++];
      const Estimate b = unary();
      a.digits += b.digits + std::log10(std::min(a.terms, b.terms));
      a.terms *= b.terms;
      if (a.constant && b.constant) a.value = op == '*' ? a.value * b.value : a.value / b.value;
      a.constant = a.constant && b.constant;
      check(a, from);
    }
    return a;
  }

  Estimate unary() {
    if (peek() != '-' && peek() != '+') return power();
    if (++nesting_ > kMaxOperatorNesting) return fail_nesting();
    const bool minus = text_[at_++] == '-';
    Estimate e = unary();
    if (minus) e.value = -e.value;
    --nesting_;
    return e;
  }

  Estimate power() {
    const std::size_t from = at_;
    Estimate base = primary();
    while (!failed_ && peek() == '^') {
      ++at_;
      if (++nesting_ > kMaxOperatorNesting) return fail_nesting();
      const Estimate exponent = unary();
      --nesting_;
      if (failed_) return base;
      // Also for a power of a sum of states or parameters: GiNaC expands (a+1)^(10^9) for a
      // parameter a, which no degree limit bounds. (x^(2^40) has one coefficient, 1, and is left
      // to the degree limit.)
      if (exponent.constant) {
        // NaN (1e400 - 1e399 in doubles) is an exponent too large to know: count it as infinite.
        const double times = std::isnan(exponent.value) ? HUGE_VAL : std::fabs(exponent.value);
        const double per_factor = base.digits + std::log10(base.terms);
        base.digits = per_factor > 0 ? per_factor * times : 0;
        base.terms = base.terms > 1 ? std::pow(base.terms, times) : 1;
        if (base.constant) base.value = std::pow(base.value, exponent.value);
      }
      base.constant = base.constant && exponent.constant;
      check(base, from);
    }
    return base;
  }

  Estimate primary() {
    Estimate e;
    const char c = peek();
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t from = at_;
      while (at_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[at_])) || text_[at_] == '_')) ++at_;
      const std::string name = text_.substr(from, at_ - from);
      if (peek() != '(') return e;  // a state, parameter, time or constant such as Pi
      // A call: GiNaC keeps sin(2^x) and the like symbolic; its arguments are checked.
      ++at_;
      // GiNaC's parser finds a function of no arguments (exp(), found by scripts/fuzz.sh) and
      // evaluating it dereferences a null pointer (signal 11). No function of a model has none.
      if (peek() == ')') {
        problem_ = "'" + name + "()': a function needs an argument";
        failed_ = true;
        return e;
      }
      double largest = 0;  // the largest constant argument
      do {
        if (peek() == ',') ++at_;
        const Estimate argument = sum();
        e.digits = std::max(e.digits, argument.digits);
        if (argument.constant) largest = std::max(largest, std::fabs(argument.value));
      } while (!failed_ && peek() == ',');
      if (peek() == ')') ++at_; else failed_ = true;
      // These GiNaC evaluates exactly at whole numbers: factorial(n) and its relatives have about
      // n log10 n digits, and zeta(n) needs the Bernoulli number B_n (zeta(100000) ran for minutes).
      static const char* const exact_at_integers[] = {"factorial", "tgamma", "lgamma", "binomial", "beta", "zeta", "psi"};
      if (largest > 1 && std::find(std::begin(exact_at_integers), std::end(exact_at_integers), name) != std::end(exact_at_integers))
        e.digits = std::max(e.digits, largest * std::log10(largest));
      // zeta(n) computes every Bernoulli number up to B_n on the way: about n^2 log10(n) / 2 digits
      // in all (zeta(2640) took 2 s, and the time grows as n^3; found by scripts/fuzz.sh).
      if (largest > 1 && name == "zeta") e.digits = std::max(e.digits, largest * largest * std::log10(largest) / 2);
      check(e, from);
      return e;
    }
    if (c == '(') {
      ++at_;
      e = sum();
      if (peek() == ')') ++at_; else failed_ = true;
      return e;
    }
    failed_ = true;  // a syntax error: GiNaC's parser says which
    return e;
  }

  // A literal such as 12.5e-3 = 125/10^4: digits of the mantissa plus the power of ten.
  Estimate number() {
    const std::size_t from = at_;
    double leading = 0;  // the first 15 significant digits
    int significant = 0;
    long shift = 0;
    bool dot = false;
    for (; at_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[at_])) || text_[at_] == '.'); ++at_) {
      if (text_[at_] == '.') { dot = true; continue; }
      if (dot) --shift;
      if (significant == 0 && text_[at_] == '0') continue;
      if (++significant <= 15) leading = leading * 10 + (text_[at_] - '0');
    }
    if (at_ < text_.size() && (text_[at_] == 'e' || text_[at_] == 'E')) {
      std::size_t j = at_ + 1;
      if (j < text_.size() && (text_[j] == '+' || text_[j] == '-')) ++j;
      const std::size_t digits_from = j;
      while (j < text_.size() && std::isdigit(static_cast<unsigned char>(text_[j]))) ++j;
      // Exponents longer than 4 digits are the literal reader's to refuse (decimal_literals).
      if (j - digits_from - std::min(j - digits_from, text_.substr(digits_from, j - digits_from).find_first_not_of('0')) > 4) {
        failed_ = true;
        return Estimate{};
      }
      if (j > digits_from) {
        shift += std::strtol(text_.substr(at_ + 1, std::min<std::size_t>(j - at_ - 1, 12)).c_str(), nullptr, 10);
        at_ = j;
      }
    }
    Estimate e;
    e.constant = true;
    e.value = std::strtod(text_.substr(from, at_ - from).c_str(), nullptr);
    const double mantissa_digits = significant <= 15 ? (leading > 1 ? std::log10(leading) : 0) : significant;
    e.digits = mantissa_digits + std::fabs(static_cast<double>(shift));
    return e;
  }

  Estimate fail_nesting() {
    if (!failed_)
      problem_ = "expression nests signs and exponents deeper than " + std::to_string(kMaxOperatorNesting) + " levels";
    failed_ = true;
    return Estimate{};
  }
};

}  // namespace

std::optional<std::string> expression_limit_problem(const std::string& text) {
  if (text.size() > kMaxExpressionLength)
    return "expression is longer than " + std::to_string(kMaxExpressionLength) + " characters";
  int depth = 0;
  for (char c : text) {
    if (c == '(' && ++depth > kMaxParenthesisDepth)
      return "expression nests deeper than " + std::to_string(kMaxParenthesisDepth) + " parentheses";
    if (c == ')') --depth;
  }
  return Estimator(text).run();
}

}  // namespace pfgen
