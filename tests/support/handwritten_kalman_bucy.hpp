#pragma once
// The Kalman-Bucy filter of a DenseLinearSystem written by hand with fixed-size Eigen matrices, as
// a user without pfgen would write it: the baseline of benchmarks/bench_handwritten (docs/benchmarks.md,
// "Generated code against hand-written code") and of tests/test_handwritten_agreement.cpp.
//
// It takes the same Heun step as the generated `step` of the `optimal` filter
// (generator/src/codegen/backends/cpp/templates/filter.hpp.tmpl): with the increment
//   dm = A m dt + K (dy - C m dt),   dP = (A P + P A^T + W - P C^T R^-1 C P) dt,   K = P C^T R^-1,
// first = increment(m, P), predicted = (m, P) + first, second = increment(predicted), and
// (m, P) += (first + second) / 2. So both compute the same numbers up to rounding.
//
// Written the way one writes it well, not naively: A P once and its transpose for P A^T (P is
// symmetric), P C^T once and reused for K and for P C^T R^-1 C P = K (P C^T)^T. It keeps the whole
// symmetric P, as Eigen's fixed-size products want it; nothing exploits the symmetry further.
// All set-up (W = G G^T, R^-1) is computed once in double, then rounded to Scalar.
#include <Eigen/Core>
#include <Eigen/LU>

#include "support/dense_linear_system.hpp"

namespace pfgen_test {

template <class Scalar, int N, int Q>
class HandwrittenKalmanBucy {
 public:
  using Vec = Eigen::Matrix<Scalar, N, 1>;
  using Mat = Eigen::Matrix<Scalar, N, N>;
  using Obs = Eigen::Matrix<Scalar, Q, 1>;
  using ObsMat = Eigen::Matrix<Scalar, Q, N>;
  using Gain = Eigen::Matrix<Scalar, N, Q>;
  using ObsSquare = Eigen::Matrix<Scalar, Q, Q>;

  explicit HandwrittenKalmanBucy(const DenseLinearSystem& s) {
    using MatD = Eigen::Matrix<double, N, N>;
    MatD a, g;
    Eigen::Matrix<double, Q, N> c;
    Eigen::Matrix<double, Q, Q> b = Eigen::Matrix<double, Q, Q>::Zero();
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        a(i, j) = s.a_tenths[i][j] / 10.0;
        g(i, j) = s.g_tenths[i][j] / 10.0;
      }
    for (int r = 0; r < Q; ++r) {
      for (int j = 0; j < N; ++j) c(r, j) = s.c_tenths[r][j] / 10.0;
      b(r, r) = s.b_tenths[r] / 10.0;
    }
    A_ = a.template cast<Scalar>();
    W_ = (g * g.transpose()).template cast<Scalar>();
    C_ = c.template cast<Scalar>();
    Ct_ = C_.transpose();
    R_inverse_ = (b * b.transpose()).inverse().template cast<Scalar>();
    for (int i = 0; i < N; ++i) m0_(i) = Scalar(s.m0_tenths[i] / 10.0);
    P0_.setIdentity();
  }

  const Vec& m0() const { return m0_; }
  const Mat& P0() const { return P0_; }

  // One Heun step over the increment dy (Q entries) of length dt, in place.
  void step(Vec& m, Mat& P, const Scalar* dy, Scalar dt) const {
    const Eigen::Map<const Obs> y(dy);
    Vec dm1, dm2;
    Mat dP1, dP2;
    increment(m, P, y, dt, dm1, dP1);
    const Vec m_predicted = m + dm1;
    const Mat P_predicted = P + dP1;
    increment(m_predicted, P_predicted, y, dt, dm2, dP2);
    m += (dm1 + dm2) / Scalar(2);
    P += (dP1 + dP2) / Scalar(2);
  }

 private:
  void increment(const Vec& m, const Mat& P, const Obs& dy, Scalar dt, Vec& dm, Mat& dP) const {
    Gain PCt;
    PCt.noalias() = P * Ct_;
    Gain K;
    K.noalias() = PCt * R_inverse_;
    Mat AP;
    AP.noalias() = A_ * P;
    dP = (AP + AP.transpose() + W_ - K * PCt.transpose()) * dt;
    dm = (A_ * m) * dt + K * (dy - (C_ * m) * dt);
  }

  Mat A_, W_;
  ObsMat C_;
  Gain Ct_;
  ObsSquare R_inverse_;
  Vec m0_;
  Mat P0_;
};

}  // namespace pfgen_test
