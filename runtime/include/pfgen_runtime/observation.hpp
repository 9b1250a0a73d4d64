#pragma once
// Continuous observations dy = (A0(t) + A(t) x(t - h)) dt + B(t) dW2 on the truth's grid, h = 0
// unless set_delay() gives a delay (docs/theory.md §2.6); or, after set_rate(), dy = h(t, x) dt +
// B(t) dW2 with any rate h (a polynomial observation, docs/theory.md §2.9), A0 and A unused.
#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace pfgen_runtime {

class LinearObservation {
 public:
  // Fills A0 (p), A (p x n) and B (p x r) at time t; the arguments arrive sized.
  using Coefficients = std::function<void(double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B)>;
  // h(t, x) into h (p entries), x the n states; reentrant.
  using Rate = std::function<void(double t, const double* x, double* h)>;
  // h(t, x) of `count` states at once, entry-major (x[i * count + k], h[a * count + k]); lane k
  // equal to Rate on state k, bit for bit.
  using BatchRate = std::function<void(double t, std::size_t count, const double* x, double* h)>;

  // Constant coefficients.
  LinearObservation(Eigen::VectorXd A0, Eigen::MatrixXd A, Eigen::MatrixXd B);
  // Time-varying coefficients: p observations of n states with r noise dimensions.
  LinearObservation(std::size_t p, std::size_t n, std::size_t r, Coefficients coefficients);

  std::size_t p() const { return p_; }
  std::size_t n() const { return n_; }
  std::size_t r() const { return r_; }

  // The observation delay h >= 0 (default 0): dy over [t, t + dt] reads the truth at t - h and
  // t + dt - h, and x(s) = x(0) for s < 0. std::invalid_argument unless h is finite and >= 0.
  void set_delay(double h);
  double delay() const { return delay_; }
  // The rate h(t, x) in place of A0 + A x (the coefficients then give B only); std::invalid_argument
  // for an empty function or with a delay.
  // `batch`, when given, is the same rate over many states (nonlinear_rate_batch).
  void set_rate(Rate rate, BatchRate batch = {});
  // Whether the rate is A0 + A x (no set_rate).
  bool is_linear() const { return !rate_; }
  // h(t, x) of set_rate into h (p entries); std::logic_error for a linear rate, whose A0 and A
  // coefficients() gives.
  void nonlinear_rate(double t, const double* x, double* h) const;
  // The same for `count` states stored entry-major (x[i * count + k] into h[a * count + k]): by the
  // batched rate, or state by state without one. Not thread-safe, like increment().
  void nonlinear_rate_batch(double t, std::size_t count, const double* x, double* h);
  // h in steps of the grid: D = round(h / dt); std::invalid_argument when h / dt is not a whole
  // number (relative tolerance 1e-9) or D > max_delay_steps (the truth would keep nothing
  // longer, but a filter's history of D grid values would not fit).
  std::size_t delay_steps(double dt) const;
  static constexpr std::size_t max_delay_steps = 10000000;

  // The increment over [t, t + dt] given the truth at both ends and dW2 (r entries); with a delay
  // the caller passes x(t - h) and x(t + dt - h) as x_start and x_end:
  //   dy = 1/2 [(A0 + A x)(t) + (A0 + A x)(t + dt)] dt + B(t) dW2.
  // The trapezoid integrates the drift to O(dt^1.5) strongly, as accurate as the truth itself;
  // B(t) at the left end keeps the noise term Ito. Not thread-safe (work arrays): copy per thread.
  void increment(double t, double dt, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                 const Eigen::Ref<const Eigen::VectorXd>& x_end, const Eigen::Ref<const Eigen::VectorXd>& dW2,
                 Eigen::Ref<Eigen::VectorXd> dy);

  // increment() without a delay for `count` states side by side, entry-major (x[i * count + k],
  // dW2[j * count + k], dy[a * count + k]): lane k bit for bit increment()'s on state k.
  void increment_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                       const double* dW2, double* dy);
  // A0, A and B at time t into the caller's arrays, which must already be p, p x n and p x r (then
  // nothing is allocated). Not thread-safe, like increment().
  void coefficients(double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A, Eigen::MatrixXd& B);

  // h(t, x) = A0(t) + A(t) x, or set_rate's h: the observation rate.
  Eigen::VectorXd rate(double t, const Eigen::Ref<const Eigen::VectorXd>& x);

 private:
  void evaluate(double t);
  std::size_t p_, n_, r_;
  Coefficients coefficients_;  // empty for constant coefficients
  Eigen::VectorXd A0_;
  Eigen::MatrixXd A_, B_;
  Eigen::VectorXd work_, start_;
  Rate rate_;  // empty: A0 + A x
  BatchRate batch_rate_;  // optional
  Eigen::VectorXd lane_x_, lane_h_;  // nonlinear_rate_batch's lanes, without a batched rate
  std::vector<double> lane_end_, lane_start_;  // increment_lanes' rates at both ends
  double delay_ = 0;
};

}  // namespace pfgen_runtime
