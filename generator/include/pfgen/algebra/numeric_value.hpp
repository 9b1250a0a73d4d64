#pragma once
// The numerical value of an expression at given values of its symbols, the same in every process.
//
// GiNaC orders the operands of a sum or product by hash, and its hashes are seeded with the
// addresses of type names, which address-space randomisation moves from run to run. subs() then
// evalf() adds floating-point operands in that order, so the last digit of a value (a ukf's
// Cholesky entries, a user filter's definitions, sin(1) + cos(1)) changed in about one run in a
// dozen. Here every sum and product is taken in an order fixed by the operands' values (smallest
// magnitude first), so the result depends only on the expression and the values.
#include <ginac/ginac.h>

namespace pfgen {

// `e` with each symbol found in `values` replaced (by a number or an expression of numbers) and
// evaluated: exact where every input is exact (rationals stay rationals), otherwise a floating
// number of GiNaC's precision. Functions and non-integer powers of numbers are evaluated with
// evalf(). A symbol without a value stays, and so does every part that holds one (the result is
// then not a GiNaC::numeric; callers check). Throws what GiNaC throws for a pole (1/0).
GiNaC::ex numeric_value(const GiNaC::ex& e, const GiNaC::exmap& values);

}  // namespace pfgen
