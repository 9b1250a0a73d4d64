#pragma once
// C++ (double, with common-subexpression elimination) of what a simulation needs of the model
// itself besides its filters: the truth dx = f dt + g dW1, the observation coefficients and x0,
// all at the parameters' default values. The simulation plugin (simulation_plugin.hpp) places
// these definitions in a namespace of its own. Each function names the inputs it reads at its top,
// as the model does (`const Scalar y = x[1];`, `const Scalar a = params.a;`); its arguments and
// temporaries keep clear of those names (local_names.hpp), the time argument has the model's name.
#include <cstddef>
#include <string>

#include "pfgen/model/model.hpp"

namespace pfgen::codegen {

struct TruthCode {
  std::size_t n = 0;  // states
  std::size_t q = 0;  // Wiener processes of the truth: columns of g, n when only G is given, 0 when g = 0
  std::size_t p = 0;  // observations
  std::size_t r = 0;  // columns of the observation noise's matrix (B, or a sampled observation's Uv)
  bool diffusion_is_zero = false;        // g identically zero: no diffusion functions at all
  bool diffusion_is_covariance = false;  // only G = g g^T given: diffusion_covariance(), no g, no Jacobian
  bool observation_is_constant = true;   // A0, A, B free of the time symbol (a sampled observation: true)
  bool observation_is_sampled = false;   // the observation's timing: samples, not increments
  bool has_observation_rate = false;     // the rate's rows are not affine: observation_rate(t, x, h or c)
  bool has_initial_state = false;        // the model gives initial.x0
  // Definitions, in this order (bracketed ones only when they exist; argument names as below
  // unless the model uses them, see local_names.hpp):
  //   using Scalar = double;  struct Params { <parameters with defaults> };
  //   void drift(double t, const double* x, double* f);                      // f: n
  //   [void diffusion(double t, const double* x, double* g);]                // n x q row-major
  //   [void diffusion_jacobian(double t, const double* x, double* dg);]     // dg[(i*q+j)*n+l] = dg_ij/dx_l
  //   [void diffusion_covariance(double t, const double* x, double* G);]    // n x n row-major
  //   the observation's functions, from its axes (the rate's A0 + A x, zeros for rows that are not affine):
  //   void observation(double t, double* A0, double* A, double* B);         // p, p x n, p x r
  //   (sampled: void sampled_observation(double t, double* C0, double* C, double* Uv), p, p x n, p x r)
  //   [void observation_rate(double t, const double* x, double* h);]        // rows not affine (sampled: c)
  //   [void observation_noise(const double* values, double t, double* B);]  // increments only
  //   [void initial_state(double* x0);]                                     // initial.x0
  std::string definitions;
};

TruthCode generate_truth_code(const Model& model);

}  // namespace pfgen::codegen
