#pragma once
// The truth SDE of a model, dx = f(t, x) dt + g(t, x) dW (Ito), as plain callbacks over raw
// arrays, the calling convention of generated code.
#include <cstddef>
#include <functional>
#include <stdexcept>

#include <Eigen/Core>

namespace pfgen_runtime {

struct SdeSystem {
  // f: n entries.
  using Drift = std::function<void(double t, const double* x, double* f)>;
  // g: n x q, row-major (g[i * q + j]).
  using Diffusion = std::function<void(double t, const double* x, double* g)>;
  // dg[(i * q + j) * n + l] = d g_ij / d x_l (n x q x n); needed by Milstein only.
  using DiffusionJacobian = std::function<void(double t, const double* x, double* dg)>;

  // A function of `count` states at one t, entry-major (structure of arrays): x[i * count + k] is
  // entry i of state k, out[e * count + k] entry e of its value (g's entry e = i * q + j). Lane k
  // must equal the one-state function on state k, bit for bit.
  using Batch = std::function<void(double t, std::size_t count, const double* x, double* out)>;

  std::size_t n = 0;  // states
  std::size_t q = 0;  // Wiener processes (0: a deterministic truth)
  Drift drift;
  Diffusion diffusion;                   // may be empty when q == 0
  DiffusionJacobian diffusion_jacobian;  // optional
  // Optional batched forms of drift and diffusion (a plugin's); schemes that step many states at
  // once (TruthScheme::step_batch) use them, and step one state at a time without them.
  Batch drift_batch;
  Batch diffusion_batch;

  // Throws std::invalid_argument when n == 0, the drift is missing, or q > 0 without a diffusion.
  void validate() const;
};

// A diffusion g with g g^T = G(t, x), for models that give only G (n x n, row-major, symmetric
// positive semi-definite): the symmetric square root by eigen-decomposition, negative round-off
// eigenvalues clipped to 0. Then q = n. It has no Jacobian; use a derivative-free scheme.
// A state-dependent G can lose definiteness as x moves (G = 1 - x once x > 1): an eigenvalue
// below -kCovarianceRoundOff times the largest |eigenvalue| throws CovarianceIndefinite, which
// simulate_truth reports as the run's end (DivergenceKind::covariance_indefinite) rather than
// clipping it and simulating another model.
inline constexpr double kCovarianceRoundOff = 1e-10;
struct CovarianceIndefinite : std::runtime_error {
  CovarianceIndefinite(double t, double eigenvalue);
  double t, eigenvalue;
};
using CovarianceCallback = std::function<void(double t, const double* x, double* G)>;
SdeSystem::Diffusion diffusion_from_covariance(std::size_t n, CovarianceCallback G);

// The largest |L^j g_k - L^k g_j| over all i, j, k at (t, x), where (L^j g_k)_i =
// sum_l g_lj d g_ik / d x_l: zero exactly when the noise is commutative at (t, x), the condition
// under which the Milstein and derivative-free order-1 schemes here have strong order 1.
// Needs the diffusion Jacobian (std::invalid_argument otherwise).
double commutativity_defect(const SdeSystem& system, double t, const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace pfgen_runtime
