#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {
namespace {
bool has_symbolic_denominator(const GiNaC::ex& e) {
  return !GiNaC::is_a<GiNaC::numeric>(GiNaC::denom(e));
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
  if (has_symbolic_denominator(expanded)) return GiNaC::normal(expanded);
  return expanded;
}

bool coefficient_is_zero(const GiNaC::ex& c) { return c.is_zero(); }

}  // namespace pfgen
