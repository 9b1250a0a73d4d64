#include "pfgen_runtime/observation_noise.hpp"

#include <stdexcept>
#include <utility>

namespace pfgen_runtime {

ObservationNoise::ObservationNoise(Eigen::MatrixXd factor) : factor_(std::move(factor)), evaluated_(true) {
  if (factor_.rows() == 0 || factor_.cols() == 0)
    throw std::invalid_argument("observation: the noise factor must be p x r with p, r >= 1");
}

ObservationNoise::ObservationNoise(std::size_t p, std::size_t r, Factor factor)
    : fill_(std::move(factor)), factor_(Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(r))) {
  if (p == 0 || r == 0) throw std::invalid_argument("observation: the noise factor must be p x r with p, r >= 1");
  if (!fill_) throw std::invalid_argument("observation: the noise callback is missing");
}

const Eigen::MatrixXd& ObservationNoise::at(double t) {
  if (!fill_ || (evaluated_ && t == evaluated_t_)) return factor_;
  const Eigen::Index p = factor_.rows(), r = factor_.cols();
  fill_(t, factor_);
  if (factor_.rows() != p || factor_.cols() != r) throw std::logic_error("observation: the noise callback resized its factor");
  evaluated_t_ = t;
  evaluated_ = true;
  return factor_;
}

}  // namespace pfgen_runtime
