// The fast paths of the polynomial arithmetic and printing (packed monomial keys, one sort per sum,
// the writer's merged sums) against the plain definitions they replace: add_term one term after
// another, a sort by displays_before, and printing the built sum. Monomials that have no packed key
// (five factors, an exponent of 256 or more, a variable index beyond 2^24) take the old paths and are
// mixed in, so both paths and their boundary are checked; long lists take the radix sort.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/notation/polynomial_writer.hpp"
#include "pfgen/notation/text_printer.hpp"

using pfgen::Monomial;
using pfgen::Polynomial;

namespace {

// A random monomial: mostly small (keyed), sometimes one without a packed key.
Monomial random_monomial(std::mt19937& rng, bool allow_unkeyed) {
  std::uniform_int_distribution<int> kind(0, 19);
  const int k = allow_unkeyed ? kind(rng) : 0;
  Monomial m;
  if (k == 1) {  // five factors
    for (std::uint32_t v = 0; v < 5; ++v) m = m * Monomial::variable(v * 3 + rng() % 3, 1 + rng() % 2);
    return m;
  }
  if (k == 2) return Monomial::variable(rng() % 4, 256 + rng() % 3);            // exponent beyond 8 bits
  if (k == 3) return Monomial::variable((1u << 24) + rng() % 3, 1 + rng() % 2);  // variable beyond 24 bits
  std::uniform_int_distribution<int> factors(0, 3);
  const int count = factors(rng);
  // Mostly few variables (like terms to merge); some indices up to 70,000, so that the keys
  // differ in several bytes (each a radix pass).
  for (int f = 0; f < count; ++f) m = m * Monomial::variable(rng() % (rng() % 4 == 0 ? 70000 : 6), 1 + rng() % 3);
  return m;
}

// Coefficients that cancel now and then, and a few expressions in a parameter.
GiNaC::ex random_coefficient(std::mt19937& rng, const GiNaC::symbol& a) {
  const int n = static_cast<int>(rng() % 7) - 3;
  if (rng() % 10 == 0) return n * a + GiNaC::numeric(1, 2);
  return GiNaC::numeric(n, 1 + static_cast<int>(rng() % 2));
}

bool same_terms(const Polynomial& x, const Polynomial& y) {
  if (x.terms().size() != y.terms().size()) return false;
  auto a = x.terms().begin();
  for (auto b = y.terms().begin(); b != y.terms().end(); ++a, ++b)
    if (!(a->first == b->first) || !a->second.is_equal(b->second)) return false;
  return true;
}

std::vector<const Polynomial::Terms::value_type*> reference_display_order(const Polynomial& p) {
  std::vector<const Polynomial::Terms::value_type*> order;
  for (const auto& term : p.terms()) order.push_back(&term);
  std::stable_sort(order.begin(), order.end(), [](const auto* x, const auto* y) {
    if (x->first.degree() != y->first.degree()) return x->first.degree() > y->first.degree();
    return pfgen::displays_before(x->first, y->first);
  });
  return order;
}

Polynomial random_polynomial(std::mt19937& rng, const GiNaC::symbol& a, bool allow_unkeyed, int terms) {
  Polynomial p;
  for (int k = 0; k < terms; ++k) p.add_term(random_monomial(rng, allow_unkeyed), random_coefficient(rng, a));
  return p;
}

}  // namespace

TEST_CASE("polynomial order: sum_of equals add_term term after term, keyed and unkeyed monomials", "[polynomial][unit]") {
  std::mt19937 rng(20261125);
  const GiNaC::symbol a("a");
  for (int trial = 0; trial < 200; ++trial) {
    const bool unkeyed = trial % 2 == 1;
    std::vector<std::pair<Monomial, GiNaC::ex>> terms;
    // Short sums are sorted by comparisons, long ones (256 terms and more) by radix passes.
    const int count = 1 + static_cast<int>(rng() % (trial < 100 ? 60 : 1500));
    for (int k = 0; k < count; ++k) terms.emplace_back(random_monomial(rng, unkeyed), random_coefficient(rng, a));
    Polynomial one_by_one;
    for (const auto& [m, c] : terms) one_by_one.add_term(m, c);
    const Polynomial summed = Polynomial::sum_of(std::move(terms));
    INFO("trial " << trial);
    CHECK(same_terms(summed, one_by_one));
  }
}

TEST_CASE("polynomial order: ordered_view equals a sort by displays_before", "[polynomial][unit]") {
  std::mt19937 rng(7);
  const GiNaC::symbol a("a");
  for (int trial = 0; trial < 200; ++trial) {
    const Polynomial p = random_polynomial(rng, a, trial % 2 == 1, 1 + static_cast<int>(rng() % (trial < 100 ? 80 : 1500)));
    INFO("trial " << trial);
    CHECK(p.ordered_view() == reference_display_order(p));
  }
  // The order itself, on monomials whose order is known by hand: degree first, then the lowest
  // variable's exponent, larger first, a longer list before its prefix.
  Polynomial p;
  for (const Monomial& m : {Monomial::variable(1), Monomial::variable(0) * Monomial::variable(2), Monomial::variable(0, 2),
                            Monomial(), Monomial::variable(0), Monomial::variable(0) * Monomial::variable(1)})
    p.add_term(m, 1);
  std::vector<Monomial> expected = {Monomial::variable(0, 2), Monomial::variable(0) * Monomial::variable(1),
                                    Monomial::variable(0) * Monomial::variable(2), Monomial::variable(0),
                                    Monomial::variable(1), Monomial()};
  const auto view = p.ordered_view();
  REQUIRE(view.size() == expected.size());
  for (std::size_t k = 0; k < view.size(); ++k) CHECK(view[k]->first == expected[k]);
}

TEST_CASE("polynomial order: ordered_union_view keeps like terms together, in the parts' order", "[polynomial][unit]") {
  std::mt19937 rng(11);
  const GiNaC::symbol a("a");
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<Polynomial> parts;
    for (int k = 0; k < 3; ++k) parts.push_back(random_polynomial(rng, a, trial % 2 == 1, static_cast<int>(rng() % 40)));
    const auto view = Polynomial::ordered_union_view({&parts[0], &parts[1], &parts[2]});
    Polynomial all;  // the monomials of the three parts, each once
    for (const auto& part : parts)
      for (const auto& term : part.terms()) all.add_term(term.first, 1);
    std::vector<const Monomial*> distinct;
    for (std::size_t k = 0; k < view.size(); ++k) {
      if (k == 0 || !(view[k].second->first == view[k - 1].second->first)) {
        distinct.push_back(&view[k].second->first);
      } else {
        CHECK(view[k].first > view[k - 1].first);  // the parts' order within a monomial
      }
    }
    const auto expected = reference_display_order(all);
    REQUIRE(distinct.size() == expected.size());
    for (std::size_t k = 0; k < distinct.size(); ++k) CHECK(*distinct[k] == expected[k]->first);
  }
}

TEST_CASE("polynomial order: the writer's merged sum prints as the built sum does", "[polynomial][unit]") {
  std::mt19937 rng(3);
  const GiNaC::symbol a("a");
  const pfgen::TextPrinter printer;
  auto name = [](std::uint32_t v) { return "v" + std::to_string(v); };
  for (int trial = 0; trial < 200; ++trial) {
    const bool unkeyed = trial % 2 == 1;
    const Polynomial p1 = random_polynomial(rng, a, unkeyed, static_cast<int>(rng() % 30));
    // The second and third parts share many monomials with the first, so that sums cancel.
    Polynomial p2 = random_polynomial(rng, a, unkeyed, static_cast<int>(rng() % 10));
    for (const auto& [m, c] : p1.terms()) if (rng() % 3 == 0) p2.add_term(m, rng() % 2 ? c : GiNaC::ex(1));
    Polynomial p3 = random_polynomial(rng, a, unkeyed, static_cast<int>(rng() % 10));
    for (const auto& [m, c] : p1.terms()) if (rng() % 3 == 0) p3.add_term(m, c);
    pfgen::PolynomialWriter writer(printer, name);
    std::string merged;
    writer.append_sum(merged, {{&p1}, {&p2}, {&p3, true}});
    INFO("trial " << trial);
    CHECK(merged == printer.print(p1 + p2 - p3, name));
  }
}
