#pragma once
// Draws from a Gaussian N(mean, covariance) whose covariance may be singular: the filters' prior,
// from which the particle reference starts its particles and `--x0 prior` draws each run's truth.
#include <string>

#include <Eigen/Core>

#include "pfgen_runtime/random.hpp"

namespace pfgen_runtime {

// The symmetric square root S (S S^T = covariance) by eigen-decomposition; round-off negative
// eigenvalues are clipped to 0, so a positive semi-definite covariance is fine. std::invalid_argument
// "<what>: ..." for a covariance that is not finite and symmetric, or clearly not positive
// semi-definite.
Eigen::MatrixXd covariance_square_root(const Eigen::MatrixXd& covariance, const std::string& what);

// mean + root z, with z the next root.cols() standard normals of `stream`, in order.
Eigen::VectorXd draw_gaussian(const Eigen::VectorXd& mean, const Eigen::MatrixXd& root, RandomStream& stream);

}  // namespace pfgen_runtime
