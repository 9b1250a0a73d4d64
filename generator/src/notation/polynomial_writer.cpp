#include "pfgen/notation/polynomial_writer.hpp"

#include <algorithm>
#include <optional>

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {
namespace {

constexpr std::size_t kPrefetchDistance = 8;  // terms ahead (prefetch_coefficient)

}  // namespace

PolynomialWriter::PolynomialWriter(const ExpressionPrinter& printer, ExpressionPrinter::VariableNamer name)
    : printer_(printer), name_(std::move(name)) {}

void PolynomialWriter::append(std::string& out, const Polynomial& p, bool negated, bool continuing) {
  if (p.is_zero()) {
    out += continuing ? " + 0" : "0";
    return;
  }
  bool first = !continuing;
  const auto ordered = p.ordered_view();
  for (std::size_t k = 0; k < ordered.size(); ++k) {
    // The coefficients are GiNaC objects spread over the heap, in no order the display follows:
    // asking for one a few terms ahead hides most of the wait for memory (a third of the writer's time).
    if (k + kPrefetchDistance < ordered.size()) prefetch_coefficient(ordered[k + kPrefetchDistance]->second);
    append_term(out, ordered[k]->first, ordered[k]->second, negated, first);
    first = false;
  }
}

void PolynomialWriter::append_sum(std::string& out, const std::vector<SignedPolynomial>& parts) {
  std::vector<const Polynomial*> polynomials;
  for (const SignedPolynomial& part : parts) polynomials.push_back(part.polynomial);
  const auto ordered = Polynomial::ordered_union_view(polynomials);
  bool first = true;
  for (std::size_t k = 0; k < ordered.size();) {
    if (k + kPrefetchDistance < ordered.size()) prefetch_coefficient(ordered[k + kPrefetchDistance].second->second);
    const Monomial& monomial = ordered[k].second->first;
    std::size_t next = k + 1;
    while (next < ordered.size() && ordered[next].second->first == monomial) ++next;
    // A monomial of one part, not negated: its coefficient as the polynomial holds it.
    if (next == k + 1 && !parts[ordered[k].first].negated && ordered[k].first == 0) {
      append_term(out, monomial, ordered[k].second->second, false, first);
      first = false;
      k = next;
      continue;
    }
    // Summed as Polynomial's operator+ and operator- sum the parts: each later part's coefficient
    // normalised (operator+ copies the first part as it is), negated by coefficient_product(c, -1),
    // added by coefficient_sum; a zero sum drops the term, and a later part's term starts anew.
    std::optional<GiNaC::ex> sum;
    for (std::size_t r = k; r < next; ++r) {
      const auto& [part, term] = ordered[r];
      GiNaC::ex c = parts[part].negated ? coefficient_product(term->second, -1) : term->second;
      if (part != 0) c = normalize_coefficient(c);
      if (sum) {
        GiNaC::ex total = coefficient_sum(*sum, c);
        sum.reset();
        if (!coefficient_is_zero(total)) sum = std::move(total);
      } else if (!coefficient_is_zero(c)) {
        sum = std::move(c);
      }
    }
    if (sum) {
      append_term(out, monomial, *sum, false, first);
      first = false;
    }
    k = next;
  }
  if (first) out += "0";
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
  const PrintedNumber& value = number(GiNaC::ex_to<GiNaC::numeric>(coefficient));
  const bool negative = value.negative != negated;
  out += first ? (negative ? "-" : "") : (negative ? " - " : " + ");
  factors_.clear();
  if (!value.unit || monomial.is_one()) factors_.push_back(&value.magnitude);
  for (const auto& [variable, exponent] : monomial.factors()) factors_.push_back(&variable_power(variable, exponent));
  printer_.append_factors(out, factors_.data(), factors_.size());
}

const PolynomialWriter::PrintedNumber& PolynomialWriter::number(const GiNaC::numeric& value) {
  auto found = numbers_.find(value);
  if (found != numbers_.end()) return found->second;
  const GiNaC::numeric magnitude = GiNaC::abs(value);
  PrintedNumber printed{value.is_negative(), magnitude.is_equal(GiNaC::numeric(1)), printer_.number(magnitude)};
  return numbers_.emplace(value, std::move(printed)).first->second;
}

const std::string& PolynomialWriter::variable_power(std::uint32_t variable, std::uint32_t exponent) {
  if (exponent <= kTabulatedExponents && variable < kTabulatedVariables) {
    if (variable >= tabulated_powers_.size()) tabulated_powers_.resize(variable + 1);
    std::vector<std::string>& powers = tabulated_powers_[variable];
    if (powers.empty()) powers.resize(kTabulatedExponents + 1);
    std::string& text = powers[exponent];
    if (text.empty()) text = printer_.print_integer_power(name_(variable), exponent);
    return text;
  }
  const std::uint64_t key = static_cast<std::uint64_t>(variable) << 32 | exponent;
  auto found = other_powers_.find(key);
  if (found != other_powers_.end()) return found->second;
  return other_powers_.emplace(key, printer_.print_integer_power(name_(variable), exponent)).first->second;
}

}  // namespace pfgen
