#include "pfgen/algebra/coefficient.hpp"

#include <cstdint>

namespace pfgen {
namespace {
bool has_symbolic_denominator(const GiNaC::ex& e) {
  return !GiNaC::is_a<GiNaC::numeric>(GiNaC::denom(e));
}

// True when a denominator is a sum (a power of an add with a negative exponent): only then does
// the expanded form fail to be canonical, so only then is normal() needed.
bool has_compound_denominator(const GiNaC::ex& e) {
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_exactly_a<GiNaC::power>(*it) && GiNaC::is_exactly_a<GiNaC::add>(it->op(0)) &&
        it->op(1).info(GiNaC::info_flags::negative))
      return true;
  return false;
}

// A value for each symbol that depends on its name only (FNV-1a of the name, mapped into
// (1, 2)), so that the sign test below gives the same answer in every run.
GiNaC::exmap name_point(const GiNaC::ex& e) {
  GiNaC::exmap point;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) {
      std::uint64_t hash = 1469598103934665603ULL;
      for (unsigned char c : GiNaC::ex_to<GiNaC::symbol>(*it).get_name()) hash = (hash ^ c) * 1099511628211ULL;
      point[*it] = GiNaC::numeric(1) + GiNaC::numeric(static_cast<long>(hash % 1000003), 1000003);
    }
  return point;
}

// normal() brings a rational function over one denominator, but which of n/d and (-n)/(-d) it
// returns, and whether n comes back expanded or as -(...), depends on GiNaC's internal term
// order, which varies from run to run (docs/theory.md §9.1): (2*r^2 - eps)/(eps*r^2) in one run,
// -(-2*r^2 + eps)/(eps*r^2) in the next. Expanding both parts and fixing the sign of the
// denominator by its value at a point chosen by the symbols' names gives one form.
GiNaC::ex canonical_fraction(const GiNaC::ex& normalized) {
  const GiNaC::ex parts = GiNaC::numer_denom(normalized);
  GiNaC::ex numerator = parts.op(0).expand(), denominator = parts.op(1).expand();
  const GiNaC::ex value = GiNaC::evalf(denominator.subs(name_point(denominator)));
  if (GiNaC::is_a<GiNaC::numeric>(value) && GiNaC::ex_to<GiNaC::numeric>(value).is_real() &&
      GiNaC::ex_to<GiNaC::numeric>(value).is_negative()) {
    numerator = (-numerator).expand();
    denominator = (-denominator).expand();
  }
  return numerator / denominator;
}
}  // namespace

GiNaC::ex coefficient_sum(const GiNaC::ex& a, const GiNaC::ex& b) {
  if (GiNaC::is_exactly_a<GiNaC::numeric>(a) && GiNaC::is_exactly_a<GiNaC::numeric>(b))
    return GiNaC::ex_to<GiNaC::numeric>(a).add(GiNaC::ex_to<GiNaC::numeric>(b));
  return normalize_coefficient(a + b);
}

GiNaC::ex coefficient_product(const GiNaC::ex& a, const GiNaC::ex& b) {
  if (GiNaC::is_exactly_a<GiNaC::numeric>(a) && GiNaC::is_exactly_a<GiNaC::numeric>(b))
    return GiNaC::ex_to<GiNaC::numeric>(a).mul(GiNaC::ex_to<GiNaC::numeric>(b));
  return normalize_coefficient(a * b);
}

GiNaC::ex normalize_coefficient(const GiNaC::ex& c) {
  if (GiNaC::is_exactly_a<GiNaC::numeric>(c)) return c;
  GiNaC::ex expanded = c.expand();
  // A sum of terms whose denominators are products of powers (2/eps - 1/r^2: parameters in R^-1
  // and 1/eps) is canonical as it is: GiNaC cancels equal terms, and the printers and the code
  // generator order its terms by text. Brought over one denominator instead, it would be a product
  // with a sum inside, (2*r^2 - eps)/(eps*r^2), whose sign GiNaC places by its run-dependent term
  // order (docs/theory.md §9.1).
  if (has_symbolic_denominator(expanded) && has_compound_denominator(expanded))
    return canonical_fraction(GiNaC::normal(expanded));
  return expanded;
}

bool coefficient_is_zero(const GiNaC::ex& c) {
  // A number asks CLN directly; ex::is_zero compares with GiNaC's 0 through is_equal (millions of
  // calls in a dense derivation).
  if (GiNaC::is_exactly_a<GiNaC::numeric>(c)) return GiNaC::ex_to<GiNaC::numeric>(c).is_zero();
  return c.is_zero();
}

}  // namespace pfgen
