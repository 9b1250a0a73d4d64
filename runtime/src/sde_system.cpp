#include "pfgen_runtime/sde_system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

namespace pfgen_runtime {

void SdeSystem::validate() const {
  if (n == 0) throw std::invalid_argument("SDE system: n must be at least 1");
  if (!drift) throw std::invalid_argument("SDE system: the drift is missing");
  if (q > 0 && !diffusion) throw std::invalid_argument("SDE system: q > 0 but the diffusion is missing");
}

CovarianceIndefinite::CovarianceIndefinite(double t_, double eigenvalue_)
    : std::runtime_error("the diffusion covariance G is not positive semi-definite"), t(t_), eigenvalue(eigenvalue_) {}

SdeSystem::Diffusion diffusion_from_covariance(std::size_t n, CovarianceCallback G) {
  if (!G) throw std::invalid_argument("diffusion_from_covariance: G is missing");
  return [n, G = std::move(G)](double t, const double* x, double* g) {
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor cov(n, n);
    G(t, x, cov.data());
    const Eigen::MatrixXd symmetric = 0.5 * (cov + cov.transpose());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(symmetric);
    const double smallest = solver.eigenvalues().minCoeff();
    if (smallest < -kCovarianceRoundOff * solver.eigenvalues().cwiseAbs().maxCoeff()) throw CovarianceIndefinite(t, smallest);
    const Eigen::VectorXd roots = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    const RowMajor root = solver.eigenvectors() * roots.asDiagonal() * solver.eigenvectors().transpose();
    std::copy(root.data(), root.data() + n * n, g);
  };
}

double commutativity_defect(const SdeSystem& system, double t, const Eigen::Ref<const Eigen::VectorXd>& x) {
  system.validate();
  if (!system.diffusion_jacobian) throw std::invalid_argument("commutativity_defect: the diffusion Jacobian is missing");
  const std::size_t n = system.n, q = system.q;
  std::vector<double> g(n * q), dg(n * q * n);
  system.diffusion(t, x.data(), g.data());
  system.diffusion_jacobian(t, x.data(), dg.data());
  // L^j g_k, component i.
  auto L = [&](std::size_t j, std::size_t k, std::size_t i) {
    double s = 0;
    for (std::size_t l = 0; l < n; ++l) s += g[l * q + j] * dg[(i * q + k) * n + l];
    return s;
  };
  double defect = 0;
  for (std::size_t j = 0; j < q; ++j)
    for (std::size_t k = j + 1; k < q; ++k)
      for (std::size_t i = 0; i < n; ++i) defect = std::max(defect, std::abs(L(j, k, i) - L(k, j, i)));
  return defect;
}

}  // namespace pfgen_runtime
