#include "pfgen_runtime/gaussian_draw.hpp"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace pfgen_runtime {

Eigen::MatrixXd covariance_square_root(const Eigen::MatrixXd& covariance, const std::string& what) {
  if (!covariance.allFinite() || !covariance.isApprox(covariance.transpose(), 1e-12))
    throw std::invalid_argument(what + " must be finite and symmetric");
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
  const Eigen::VectorXd values = solver.eigenvalues();
  const double scale = std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  if (values.minCoeff() < -1e-10 * scale) throw std::invalid_argument(what + " is not positive semi-definite");
  return solver.eigenvectors() * values.cwiseMax(0.0).cwiseSqrt().asDiagonal() * solver.eigenvectors().transpose();
}

Eigen::VectorXd draw_gaussian(const Eigen::VectorXd& mean, const Eigen::MatrixXd& root, RandomStream& stream) {
  Eigen::VectorXd z(root.cols());
  for (Eigen::Index k = 0; k < z.size(); ++k) z[k] = stream.normal();
  return mean + root * z;
}

}  // namespace pfgen_runtime
