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

}  // namespace pfgen
