#pragma once
// The polynomial observation dy = h(x, t) dt + B dW2 as the module's rooms read it: h as
// polynomials in the states (the rate's rows, model/observation_model.hpp), whose affine case
// A0 + A x the rate found when the model was built.
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

// The rate's rows h_r as polynomials in the states.
std::vector<Polynomial> observation_polynomials(const Model& model);

// The highest total degree of an h_r in the states.
unsigned observation_degree(const Model& model);

// Whether a derived filter's observation reads as A0 + A m: its predicted observation has degree
// <= 1 in the filter's variables (E[h] of a nonlinear h holds P, or m^2), which the reports and
// eval ask to print such a filter exactly as the continuous observation's.
bool predicts_linearly(const FilterEquations& eq);

}  // namespace pfgen
