#pragma once
// The rate axis of an observation: what it measures of the state, h(t, x) (p entries of n
// states), the same for increments dy = h dt + B dW2 and for samples y_k = h(t_k, x) + Uv v_k
// (observation.hpp composes it with the timing and the noise). Two implementations:
// - AffineRate: A0(t) + A(t) x, its coefficients constant or from a callback (a linear
//   observation, or a polynomial one of degree 1);
// - FunctionRate: any h(t, x), one state at a time and optionally batched (a polynomial
//   observation, docs/theory.md §2.5 and §2.9).
// Each keeps the order of operations its users have always had, so that a rate's bits do not
// depend on which of its forms (one state, lanes, trapezoid) computed it. Not thread-safe (work
// arrays, the coefficients last evaluated): clone() one per thread.
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace pfgen_runtime {

class ObservationRate {
 public:
  ObservationRate(std::size_t p, std::size_t n);
  virtual ~ObservationRate() = default;
  virtual std::unique_ptr<ObservationRate> clone() const = 0;

  std::size_t p() const { return p_; }
  std::size_t n() const { return n_; }
  // Whether h is A0(t) + A(t) x: detected once, when the observation is made, for what a report
  // says of the estimates of h (the summary's words on a nonlinear c).
  virtual bool affine() const = 0;

  // h(t, x) into h (p entries).
  virtual void value(double t, const double* x, double* h) = 0;
  // The same for `count` states entry-major (x[i * count + k] into h[a * count + k]), lane k bit
  // for bit value()'s on state k.
  virtual void lanes(double t, std::size_t count, const double* x, double* h) = 0;
  // The drift part of an increment over [t, t + dt]: dt/2 [h(t + dt, x_end) + h(t, x_start)]
  // (p entries), and the same over `count` states entry-major, lane k bit for bit the one-state
  // form's. The trapezoid integrates the drift to O(dt^1.5) strongly, as accurate as the truth.
  virtual void trapezoid(double t, double dt, const double* x_start, const double* x_end, double* out) = 0;
  virtual void trapezoid_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                               double* out) = 0;

 private:
  std::size_t p_, n_;
};

class AffineRate final : public ObservationRate {
 public:
  // Fills A0 (p) and A (p x n) at t; the arguments arrive sized. A pure function of t.
  using Coefficients = std::function<void(double t, Eigen::VectorXd& A0, Eigen::MatrixXd& A)>;
  // Constant coefficients; std::invalid_argument unless A is p x n with p, n >= 1 and A0 has p entries.
  AffineRate(Eigen::VectorXd A0, Eigen::MatrixXd A);
  // Time-varying ones; std::invalid_argument for p or n 0 or an empty callback.
  AffineRate(std::size_t p, std::size_t n, Coefficients coefficients);

  std::unique_ptr<ObservationRate> clone() const override { return std::make_unique<AffineRate>(*this); }
  bool affine() const override { return true; }
  void value(double t, const double* x, double* h) override;
  void lanes(double t, std::size_t count, const double* x, double* h) override;
  void trapezoid(double t, double dt, const double* x_start, const double* x_end, double* out) override;
  void trapezoid_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                       double* out) override;
  // A0 and A at t (evaluated once per t: a run's many states at one time fetch them once).
  const Eigen::VectorXd& offset(double t) {
    evaluate(t);
    return A0_;
  }
  const Eigen::MatrixXd& matrix(double t) {
    evaluate(t);
    return A_;
  }

 private:
  void evaluate(double t);
  Coefficients coefficients_;  // empty for constant coefficients
  Eigen::VectorXd A0_;
  Eigen::MatrixXd A_;
  double evaluated_t_ = 0;
  bool evaluated_ = false;
};

class FunctionRate final : public ObservationRate {
 public:
  // h(t, x) into h (p entries), x the n states; reentrant.
  using Function = std::function<void(double t, const double* x, double* h)>;
  // h(t, x) of `count` states at once, entry-major; lane k equal to Function on state k, bit for bit.
  using BatchFunction = std::function<void(double t, std::size_t count, const double* x, double* h)>;
  // std::invalid_argument for p or n 0 or an empty function. Without `batch`, lanes() calls
  // `function` lane by lane.
  FunctionRate(std::size_t p, std::size_t n, Function function, BatchFunction batch = {});

  std::unique_ptr<ObservationRate> clone() const override { return std::make_unique<FunctionRate>(*this); }
  bool affine() const override { return false; }
  void value(double t, const double* x, double* h) override { function_(t, x, h); }
  void lanes(double t, std::size_t count, const double* x, double* h) override;
  void trapezoid(double t, double dt, const double* x_start, const double* x_end, double* out) override;
  void trapezoid_lanes(double t, double dt, std::size_t count, const double* x_start, const double* x_end,
                       double* out) override;

 private:
  Function function_;
  BatchFunction batch_;            // optional
  Eigen::VectorXd lane_x_, lane_h_;  // lanes() without a batched function
  std::vector<double> start_;      // the trapezoid's left-end rates
};

}  // namespace pfgen_runtime
