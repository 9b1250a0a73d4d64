#pragma once
// Random polynomial stochastic systems for the derivation tests: drift f and
// multiplicative diffusion g with exact rational coefficients, optionally
// scaled by a model parameter `a` or by sin(t). The system keeps its own
// term lists, so a test can form the expected equations from them (without
// reading the Model back) and evaluate f and g fast in double precision for
// Monte Carlo sampling.
#include <random>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/model/model.hpp"

namespace pfgen_test {

struct RandomTerm {
  GiNaC::numeric coefficient;
  bool times_parameter = false;  // coefficient * a
  bool times_sin_t = false;      // coefficient * sin(t)
  std::vector<unsigned> exponents;
};

struct RandomPolynomial {
  std::vector<RandomTerm> terms;

  unsigned degree() const;
  GiNaC::ex to_ex(const std::vector<GiNaC::symbol>& x, const GiNaC::ex& a, const GiNaC::ex& t) const;
  // Value at the state x with the parameter a and time t given as doubles.
  double evaluate(const double* x, double a, double t) const;
};

struct RandomSystemOptions {
  std::size_t n = 2;
  std::size_t q = 2;                  // columns of g
  unsigned drift_degree = 3;          // f_1 has a term of exactly this degree
  unsigned diffusion_degree = 2;      // g_11 has a term of exactly this degree
  unsigned max_terms = 4;             // terms per polynomial: 1..max_terms
  bool symbolic_coefficients = true;  // allow a * c and sin(t) * c coefficients
  bool identity_observation = true;   // A = I (p = n); otherwise p in 1..n+1 random integer rows
  bool dense = false;                 // every monomial up to the degree, instead of 1..max_terms terms
};

struct RandomSystem {
  std::size_t n = 0, q = 0, p = 0;
  std::vector<GiNaC::symbol> x;
  GiNaC::symbol a, t;
  GiNaC::numeric a_default;
  std::vector<RandomPolynomial> f;                 // n
  std::vector<std::vector<RandomPolynomial>> g;    // n x q
  pfgen::ExVector A0;                              // p
  pfgen::ExMatrix A;                               // p x n
  pfgen::ExMatrix B;                               // p x p identity
  pfgen::Model model;

  pfgen::ExVector f_ex() const;
  pfgen::ExMatrix g_ex() const;
};

RandomSystem make_random_system(std::mt19937& rng, const RandomSystemOptions& options, const std::string& name);

}  // namespace pfgen_test
