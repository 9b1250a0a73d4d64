#pragma once
// How many terms GiNaC's expand() can give for an expression, bounded from its unexpanded form.
//
// The degree limit (1000 per state) does not bound the work of expanding: (x+y+1)^1000 has
// degree 1000 but 501501 terms, each with a coefficient of hundreds of digits, and expanding it
// exhausted 4 GB. The validator compares this bound with kMaxExpandedTerms before anything is
// expanded (docs/guide/model-file.md, limits).
#include <ginac/ginac.h>

namespace pfgen {

inline constexpr double kMaxExpandedTerms = 100000;

// An upper bound on the number of terms of e.expand(), counting every symbol and every function
// call as a variable: a sum adds, a product multiplies, and a power of a sum of T terms to the
// k-th gives at most C(T+k-1, k) terms. Each is capped by the number of monomials the degrees
// allow (per variable and in total), which is what keeps (x+1)^1000 at 1001. Computed in
// double: the bound may be +inf, never NaN.
double expanded_terms_bound(const GiNaC::ex& e);

}  // namespace pfgen
