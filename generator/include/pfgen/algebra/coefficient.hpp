#pragma once
// Coefficients of pfgen polynomials are GiNaC expressions free of the
// polynomial's variables: exact rationals in the common case, otherwise
// expressions in parameters and time (a*sin(t)). The helpers take a fast path
// for plain numbers, which dominate the derivation's arithmetic.
#include <ginac/ginac.h>

namespace pfgen {

GiNaC::ex coefficient_sum(const GiNaC::ex& a, const GiNaC::ex& b);
GiNaC::ex coefficient_product(const GiNaC::ex& a, const GiNaC::ex& b);
// Expanded form; symbolic rational functions are brought over a common denominator.
GiNaC::ex normalize_coefficient(const GiNaC::ex& c);
bool coefficient_is_zero(const GiNaC::ex& c);
// Starts loading the coefficient's GiNaC object into the cache; taking its address does not read
// it. Loops over millions of terms in an order the objects do not lie in (a sort's result, the
// display order) ask for one a few terms ahead.
inline void prefetch_coefficient(const GiNaC::ex& c) { __builtin_prefetch(&GiNaC::ex_to<GiNaC::basic>(c)); }

}  // namespace pfgen
