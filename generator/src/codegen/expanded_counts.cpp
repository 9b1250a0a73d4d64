#include "pfgen/codegen/expanded_counts.hpp"

#include <algorithm>
#include <vector>

namespace pfgen::codegen {

void for_each_expanded_output(const FilterEquations& eq, const std::function<void(const Polynomial&)>& visit) {
  const std::size_t n = eq.n();
  for (const Polynomial& p : eq.m_drift) visit(p);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) visit(eq.P_drift(i, j));
  // A moment filter's central moments above P follow it (FilterVariables).
  for (const Polynomial& p : eq.higher_drift) visit(p);
  // A delayed filter with Phi* integrates x* beside m and P: its drift follows them in `out`.
  for (const Polynomial& p : eq.x_star_drift) visit(p);
}

namespace {

// A term of an output with its sign taken out: the lower bound compares outputs by these.
struct Term {
  Monomial monomial;
  GiNaC::numeric coefficient;
};

// The first terms of an output, signed so that its first coefficient is positive: an operation
// of the sum's chain computes plus or minus the sum of an output's first k terms, so two outputs
// share it only where these agree. Only the first kKeptTerms are kept; beyond them two outputs
// are taken to agree, which can only lower the bound.
constexpr std::size_t kKeptTerms = 64;
struct Prefix {
  std::vector<Term> terms;
  std::size_t length = 0;  // the output's number of terms
};

// How many first terms of `p` an operation of an earlier output may share (an upper bound).
std::size_t shared_length(const Prefix& p, const Prefix& q) {
  const std::size_t stored = std::min(p.terms.size(), q.terms.size());
  std::size_t k = 0;
  while (k < stored && p.terms[k].monomial == q.terms[k].monomial &&
         p.terms[k].coefficient == q.terms[k].coefficient)
    ++k;
  if (k == stored && (p.length > stored || q.length > stored)) return std::min(p.length, q.length);
  return k;
}

}  // namespace

std::optional<ExpandedCounts> expanded_counts(const FilterEquations& eq) {
  static const GiNaC::numeric one(1), minus_one(-1);
  ExpandedCounts counts;
  bool numbers = true;
  std::vector<Prefix> prefixes;
  for_each_expanded_output(eq, [&](const Polynomial& p) {
    if (!numbers) return;
    Prefix prefix;
    bool all_negative = true;
    GiNaC::numeric sign = 1;
    for (const auto* entry : p.ordered_view()) {
      const auto& [m, coefficient] = *entry;
      if (!GiNaC::is_exactly_a<GiNaC::numeric>(coefficient) || coefficient.is_zero()) {
        numbers = false;
        return;
      }
      const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(coefficient);
      const bool negative = c.is_negative();
      if (prefix.length == 0 && negative) sign = -1;
      all_negative = all_negative && negative;
      // As GraphBuilder::scaled: a constant alone, else the monomial, times |c| unless it is 1.
      // (|c| = 1 is tested without making |c|: negating every coefficient of a dense cubic's
      // outputs was a twentieth of codegen.)
      if (!m.is_one()) {
        std::size_t factors = 0;
        for (const auto& [variable, exponent] : m.factors()) {
          if (exponent < 1) {  // not a polynomial's monomial: left to the graph
            numbers = false;
            return;
          }
          // GraphBuilder::integer_power squares and multiplies; counted as a tree, a square counts
          // its operand twice, so x^e is e - 1 multiplications.
          counts.naive.muls += exponent - 1;
          ++factors;
        }
        counts.naive.muls += factors - 1 + (c == (negative ? minus_one : one) ? 0 : 1);
      }
      if (prefix.terms.size() < kKeptTerms)
        prefix.terms.push_back(Term{m, sign * GiNaC::ex_to<GiNaC::numeric>(coefficient)});
      ++prefix.length;
    }
    // SignedSum: an addition or subtraction per term after the first; a negation where all are negative.
    if (prefix.length > 1) counts.naive.adds += prefix.length - 1;
    if (prefix.length > 0 && all_negative) counts.naive.adds += 1;
    // The chain's operations not shared with an earlier output's: those past their common terms.
    std::size_t shared = 1;
    for (const Prefix& earlier : prefixes) shared = std::max(shared, shared_length(prefix, earlier));
    if (prefix.length > shared) counts.shared_lower_bound += prefix.length - shared;
    prefixes.push_back(std::move(prefix));
  });
  if (!numbers) return std::nullopt;
  return counts;
}

}  // namespace pfgen::codegen
