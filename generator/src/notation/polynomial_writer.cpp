#include "pfgen/notation/polynomial_writer.hpp"

#include <algorithm>

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {

PolynomialWriter::PolynomialWriter(const ExpressionPrinter& printer, ExpressionPrinter::VariableNamer name)
    : printer_(printer), name_(std::move(name)) {}

void PolynomialWriter::append(std::string& out, const Polynomial& p, bool negated, bool continuing) {
  if (p.is_zero()) {
    out += continuing ? " + 0" : "0";
    return;
  }
  bool first = !continuing;
  for (const auto* term : p.ordered_view()) {
    append_term(out, term->first, term->second, negated, first);
    first = false;
  }
}

void PolynomialWriter::append_sum(std::string& out, const std::vector<SignedPolynomial>& parts) {
  // Merge the parts' terms (each part's map is sorted by monomial), summing like terms as
  // Polynomial's operator+ and operator- do: the next part's coefficient normalised, negated
  // by coefficient_product(c, -1), added by coefficient_sum, zero sums dropped.
  std::vector<std::pair<const Monomial*, GiNaC::ex>> merged;
  for (const SignedPolynomial& part : parts) {
    std::vector<std::pair<const Monomial*, GiNaC::ex>> next;
    next.reserve(merged.size() + part.polynomial->terms().size());
    auto a = merged.begin();
    for (const auto& [monomial, coefficient] : part.polynomial->terms()) {
      for (; a != merged.end() && *a->first < monomial; ++a) next.push_back(std::move(*a));
      GiNaC::ex c = part.negated ? coefficient_product(coefficient, -1) : coefficient;
      if (&part != &parts.front()) c = normalize_coefficient(c);  // operator+ copies the first part as it is
      if (a != merged.end() && *a->first == monomial) {
        GiNaC::ex sum = coefficient_sum(a->second, c);
        if (!coefficient_is_zero(sum)) next.emplace_back(a->first, std::move(sum));
        ++a;
      } else if (!coefficient_is_zero(c)) {
        next.emplace_back(&monomial, std::move(c));
      }
    }
    for (; a != merged.end(); ++a) next.push_back(std::move(*a));
    merged = std::move(next);
  }
  if (merged.empty()) {
    out += "0";
    return;
  }
  std::vector<std::pair<std::uint32_t, std::size_t>> order;  // (degree, index), as ordered_view
  order.reserve(merged.size());
  for (std::size_t k = 0; k < merged.size(); ++k) order.emplace_back(merged[k].first->degree(), k);
  std::stable_sort(order.begin(), order.end(), [&](const auto& x, const auto& y) {
    if (x.first != y.first) return x.first > y.first;
    return displays_before(*merged[x.second].first, *merged[y.second].first);
  });
  bool first = true;
  for (const auto& entry : order) {
    append_term(out, *merged[entry.second].first, merged[entry.second].second, false, first);
    first = false;
  }
}

// ExpressionPrinter::print(Polynomial) term by term: a sign, then the term's body, where a plain
// number coefficient (the common case) takes a path without GiNaC's printing and without a Term.
void PolynomialWriter::append_term(std::string& out, const Monomial& monomial, const GiNaC::ex& coefficient,
                                   bool negated, bool first) {
  if (!GiNaC::is_exactly_a<GiNaC::numeric>(coefficient)) {
    // Expressions in parameters: the printer's own path, on the coefficient scaled(-1) would hold.
    const GiNaC::ex c = negated ? coefficient_product(coefficient, -1) : coefficient;
    ExpressionPrinter::Term term;
    if (GiNaC::is_exactly_a<GiNaC::add>(c)) {
      term.numerator_factors.push_back(printer_.parenthesized(printer_.print(c)));
    } else {
      term = printer_.to_term(c);
    }
    for (const auto& [variable, exponent] : monomial.factors())
      term.numerator_factors.push_back(variable_power(variable, exponent));
    out += first ? (term.negative ? "-" : "") : (term.negative ? " - " : " + ");
    out += printer_.print_term_body(term);
    return;
  }
  const GiNaC::numeric& value = GiNaC::ex_to<GiNaC::numeric>(coefficient);
  const bool negative = value.is_negative() != negated;
  out += first ? (negative ? "-" : "") : (negative ? " - " : " + ");
  factors_.clear();
  const GiNaC::numeric magnitude = GiNaC::abs(value);
  if (magnitude != 1 || monomial.is_one()) factors_.push_back(number(magnitude));
  for (const auto& [variable, exponent] : monomial.factors()) factors_.push_back(variable_power(variable, exponent));
  out += printer_.join_factors(factors_);
}

const std::string& PolynomialWriter::number(const GiNaC::numeric& non_negative) {
  auto found = numbers_.find(non_negative);
  if (found != numbers_.end()) return found->second;
  return numbers_.emplace(non_negative, printer_.number(non_negative)).first->second;
}

const std::string& PolynomialWriter::variable_power(std::uint32_t variable, std::uint32_t exponent) {
  const std::uint64_t key = static_cast<std::uint64_t>(variable) << 32 | exponent;
  auto found = powers_.find(key);
  if (found != powers_.end()) return found->second;
  return powers_.emplace(key, printer_.print_integer_power(name_(variable), exponent)).first->second;
}

}  // namespace pfgen
