// The filters for sampled observations (cd-optimal, cd-ekf, cd-euler) against references written
// here, independently of the derivation (docs/theory.md, "Continuous-discrete filters"):
//   - cd-optimal on a linear model with constant g is the discrete Kalman filter of the exactly
//     discretised model (matrix exponentials by a series, Van Loan's block for the noise), to the
//     accuracy of the prediction's sub-steps, which shrinks with them;
//   - as the period T shrinks with Uv Uv^T = R / T, cd-optimal approaches the Kalman-Bucy filter;
//   - cd-euler is paper 003's recursion (its eqs 4-9, written out below) for gamma = 0, 0.5, 1;
//   - cd-euler's dt^2 term Cov(f) of a nonlinear model is the Isserlis-Wick E[f f^T] - E[f] E[f]^T.
// The filters are run through the evaluator (what `pfgen eval` prints: prediction drifts, gain),
// stepped here by the scheme the generated predict() uses (Heun for cd-optimal, one Euler map per
// sub-step for cd-euler), and updated in Joseph form.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/isserlis_reference.hpp"

using namespace pfgen;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

// The filter's quantities at (m, P), as `pfgen eval` computes them.
EvaluatedFilter evaluate(const Model& model, const FilterEquations& eq, const VectorXd& m, const MatrixXd& P) {
  EvaluationPoint point;
  point.t = 0;
  const auto n = static_cast<Eigen::Index>(m.size());
  for (Eigen::Index i = 0; i < n; ++i) point.m.push_back(GiNaC::numeric(m(i)));
  point.P.assign(m.size(), std::vector<GiNaC::numeric>(m.size()));
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i; j < n; ++j) {
      const double v = 0.5 * (P(i, j) + P(j, i));
      point.P[i][j] = point.P[j][i] = GiNaC::numeric(v);
    }
  return evaluate_at(model, eq, point);
}

VectorXd vector_of(const std::vector<double>& v) { return Eigen::Map<const VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())); }

MatrixXd matrix_of(const std::vector<std::vector<double>>& rows) {
  MatrixXd M(rows.size(), rows.empty() ? 0 : rows[0].size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
  return M;
}

struct Moments {
  VectorXd m;
  MatrixXd P;
};

// One Heun (trapezoidal predictor-corrector) sub-step of the prediction ODEs, as the generated
// predict() of cd-optimal and cd-ekf.
void heun(const Model& model, const FilterEquations& eq, Moments& x, double dt) {
  const EvaluatedFilter first = evaluate(model, eq, x.m, x.P);
  Moments predicted{x.m + dt * vector_of(first.m_drift), x.P + dt * matrix_of(first.P_drift)};
  const EvaluatedFilter second = evaluate(model, eq, predicted.m, predicted.P);
  x.m += dt / 2 * (vector_of(first.m_drift) + vector_of(second.m_drift));
  x.P += dt / 2 * (matrix_of(first.P_drift) + matrix_of(second.P_drift));
}

// One cd-euler sub-step: m' = m + m_drift dt, P' = P + P_drift dt + Cov(f) dt^2.
void euler_map(const Model& model, const FilterEquations& eq, Moments& x, double dt) {
  const EvaluatedFilter e = evaluate(model, eq, x.m, x.P);
  REQUIRE(!e.P_dt2.empty());
  x.m += dt * vector_of(e.m_drift);
  x.P += dt * matrix_of(e.P_drift) + dt * dt * matrix_of(e.P_dt2);
}

// The update with the evaluator's gain, Joseph form.
void joseph_update(const Model& model, const FilterEquations& eq, Moments& x, const VectorXd& y, const MatrixXd& C,
                   const VectorXd& C0, const MatrixXd& R) {
  const EvaluatedFilter e = evaluate(model, eq, x.m, x.P);
  const MatrixXd K = matrix_of(e.gain);
  const MatrixXd S = matrix_of(e.innovation_covariance);
  CHECK((S - (C * x.P * C.transpose() + R)).norm() <= 1e-12 * S.norm());
  const MatrixXd I_KC = MatrixXd::Identity(x.m.size(), x.m.size()) - K * C;
  x.m += K * (y - C0 - C * x.m);
  x.P = I_KC * x.P * I_KC.transpose() + K * R * K.transpose();
}

// exp(M) by scaling and squaring of the Taylor series (the test's own, not Eigen's).
MatrixXd expm(const MatrixXd& M) {
  int squarings = 0;
  double norm = M.cwiseAbs().rowwise().sum().maxCoeff();
  while (norm > 0.25) {
    norm /= 2;
    ++squarings;
  }
  const MatrixXd X = M / std::pow(2.0, squarings);
  MatrixXd sum = MatrixXd::Identity(M.rows(), M.cols()), term = sum;
  for (int k = 1; k <= 20; ++k) {
    term = term * X / k;
    sum += term;
  }
  for (int s = 0; s < squarings; ++s) sum = sum * sum;
  return sum;
}

// dx = (A x + b) dt + G dW over one period T, exactly: x' = Phi x + c + w, w ~ N(0, Qd), with
// [Phi c; 0 1] = exp([A b; 0 0] T) and Van Loan's exp([-A Q; 0 A^T] T) = [. F12; 0 F22],
// Phi = F22^T, Qd = Phi F12.
struct Discretised {
  MatrixXd Phi, Qd;
  VectorXd c;
};

Discretised discretise(const MatrixXd& A, const VectorXd& b, const MatrixXd& Q, double T) {
  const auto n = A.rows();
  MatrixXd drift = MatrixXd::Zero(n + 1, n + 1);
  drift.topLeftCorner(n, n) = A;
  drift.topRightCorner(n, 1) = b;
  const MatrixXd E = expm(drift * T);
  MatrixXd van_loan = MatrixXd::Zero(2 * n, 2 * n);
  van_loan.topLeftCorner(n, n) = -A;
  van_loan.topRightCorner(n, n) = Q;
  van_loan.bottomRightCorner(n, n) = A.transpose();
  const MatrixXd F = expm(van_loan * T);
  Discretised d;
  d.Phi = E.topLeftCorner(n, n);
  d.c = E.topRightCorner(n, 1);
  d.Qd = F.bottomRightCorner(n, n).transpose() * F.topRightCorner(n, n);
  CHECK((d.Phi - F.bottomRightCorner(n, n).transpose()).norm() < 1e-12);
  return d;
}

// The linear test system: dx = (A x + b) dt + g dW, g constant, samples y = C0 + C x + Uv v.
const MatrixXd& A_lin() {
  static const MatrixXd A = (MatrixXd(2, 2) << -1.0, 0.5, 0.3, -0.8).finished();
  return A;
}
const VectorXd& b_lin() {
  static const VectorXd b = (VectorXd(2) << 0.2, -0.1).finished();
  return b;
}
const MatrixXd& g_lin() {
  static const MatrixXd g = (MatrixXd(2, 2) << 0.5, 0.0, 0.2, 0.3).finished();
  return g;
}
const MatrixXd& C_lin() {
  static const MatrixXd C = (MatrixXd(1, 2) << 1.0, 0.5).finished();
  return C;
}

std::string linear_model_text(const std::string& observation) {
  return "name: linear\nstates: [x1, x2]\n"
         "drift: [\"-x1 + 0.5*x2 + 0.2\", \"0.3*x1 - 0.8*x2 - 0.1\"]\n"
         "diffusion: [[\"0.5\", \"0\"], [\"0.2\", \"0.3\"]]\n"
         "observation:\n" + observation +
         "initial: {x0: [1, -1], m0: [0.5, 0.2], P0: [[1, 0.1], [0.1, 0.5]]}\n";
}

double relative_error(const MatrixXd& a, const MatrixXd& b) { return (a - b).norm() / b.norm(); }

}  // namespace

TEST_CASE("cd-optimal on a linear model with constant g is the Kalman filter of the exactly discretised model",
          "[sampled][unit]") {
  const double T = 0.5;
  const Model model = load_model_text(
      linear_model_text("  sampled:\n    period: 0.5\n    C0: [\"0.1\"]\n    C: [[\"1\", \"0.5\"]]\n    Uv: [[\"0.4\"]]\n"),
      "linear.yaml");
  const FilterEquations eq = derive_filter(model, FilterKind::CdOptimal);
  REQUIRE(eq.observation == pfgen::ObservationKind::Sampled);
  REQUIRE(eq.exactness.exact);
  const VectorXd C0 = VectorXd::Constant(1, 0.1);
  const MatrixXd R = MatrixXd::Constant(1, 1, 0.16);
  const Discretised d = discretise(A_lin(), b_lin(), g_lin() * g_lin().transpose(), T);
  const std::vector<double> samples = {0.7, 0.2, -0.4, 0.9, 0.1, -0.3};

  // The reference: the discrete Kalman filter (prediction, then the textbook update P - K S K^T).
  Moments reference{(VectorXd(2) << 0.5, 0.2).finished(), (MatrixXd(2, 2) << 1, 0.1, 0.1, 0.5).finished()};
  std::vector<Moments> expected;
  for (double y : samples) {
    reference.m = d.Phi * reference.m + d.c;
    reference.P = d.Phi * reference.P * d.Phi.transpose() + d.Qd;
    const MatrixXd S = C_lin() * reference.P * C_lin().transpose() + R;
    const MatrixXd K = reference.P * C_lin().transpose() * S.inverse();
    reference.m += K * (VectorXd::Constant(1, y) - C0 - C_lin() * reference.m);
    reference.P -= K * S * K.transpose();
    expected.push_back(reference);
  }

  std::vector<double> errors;
  for (int substeps : {8, 16}) {
    Moments x{(VectorXd(2) << 0.5, 0.2).finished(), (MatrixXd(2, 2) << 1, 0.1, 0.1, 0.5).finished()};
    double worst = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      for (int s = 0; s < substeps; ++s) heun(model, eq, x, T / substeps);
      joseph_update(model, eq, x, VectorXd::Constant(1, samples[k]), C_lin(), C0, R);
      worst = std::max({worst, (x.m - expected[k].m).norm() / expected[k].m.norm(), relative_error(x.P, expected[k].P)});
    }
    INFO(substeps << " sub-steps: largest relative error " << worst);
    CHECK(worst < 1e-2);
    errors.push_back(worst);
  }
  // Heun is second order: halving the sub-step divides the error by about 4.
  INFO("errors " << errors[0] << ", " << errors[1]);
  CHECK(errors[1] < errors[0] / 3);
  CHECK(errors[1] > errors[0] / 6);
}

TEST_CASE("cd-optimal approaches the Kalman-Bucy filter as the period shrinks with Uv Uv^T = R / T",
          "[sampled][unit]") {
  // Continuous: dy = C x dt + B dW2 with B B^T = R. Kalman-Bucy, written here:
  //   dP/dt = A P + P A^T + g g^T - P C^T R^-1 C P,  gain P C^T R^-1.
  const double R = 0.25, horizon = 1.0;
  const MatrixXd Q = g_lin() * g_lin().transpose();
  const MatrixXd P0 = (MatrixXd(2, 2) << 1, 0.1, 0.1, 0.5).finished();
  auto riccati = [&](const MatrixXd& P) {
    return MatrixXd(A_lin() * P + P * A_lin().transpose() + Q - P * C_lin().transpose() * C_lin() * P / R);
  };
  MatrixXd P = P0;
  const int steps = 4000;
  const double h = horizon / steps;
  for (int k = 0; k < steps; ++k) {  // RK4
    const MatrixXd k1 = riccati(P), k2 = riccati(P + h / 2 * k1), k3 = riccati(P + h / 2 * k2), k4 = riccati(P + h * k3);
    P += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  const MatrixXd kalman_bucy_gain = P * C_lin().transpose() / R;

  std::vector<double> P_errors, gain_errors;
  for (int samples : {10, 20, 40}) {
    const double T = horizon / samples;
    const double Uv = std::sqrt(R / T);
    const Model model = load_model_text(linear_model_text("  sampled:\n    period: " + number(T) +
                                                          "\n    C: [[\"1\", \"0.5\"]]\n    Uv: [[\"" + number(Uv) +
                                                          "\"]]\n    substeps: 4\n"),
                                        "linear.yaml");
    const FilterEquations eq = derive_filter(model, FilterKind::CdOptimal);
    const MatrixXd Rd = MatrixXd::Constant(1, 1, Uv * Uv);
    Moments x{VectorXd::Zero(2), P0};
    for (int k = 0; k < samples; ++k) {
      for (int s = 0; s < 4; ++s) heun(model, eq, x, T / 4);
      joseph_update(model, eq, x, VectorXd::Zero(1), C_lin(), VectorXd::Zero(1), Rd);
    }
    // The discrete gain per unit time, K / T, stands for the continuous gain.
    const MatrixXd K = matrix_of(evaluate(model, eq, x.m, x.P).gain) / T;
    P_errors.push_back(relative_error(x.P, P));
    gain_errors.push_back(relative_error(K, kalman_bucy_gain));
  }
  INFO("P errors " << P_errors[0] << ", " << P_errors[1] << ", " << P_errors[2]);
  INFO("gain errors " << gain_errors[0] << ", " << gain_errors[1] << ", " << gain_errors[2]);
  for (std::size_t k = 1; k < P_errors.size(); ++k) {
    // First order in T: each halving roughly halves the distance.
    CHECK(P_errors[k] < 0.7 * P_errors[k - 1]);
    CHECK(P_errors[k] > 0.3 * P_errors[k - 1]);
    CHECK(gain_errors[k] < 0.7 * gain_errors[k - 1]);
  }
  CHECK(P_errors.back() < 0.05);
  CHECK(gain_errors.back() < 0.05);
}

namespace {

// Paper 003's Example 2 shape with a nonzero B: dx = (A x + B) dt + Uw dW + sum_j G_j x_j^gamma dS_j.
const MatrixXd& A2() {
  static const MatrixXd A = (MatrixXd(2, 2) << -1.0, 0.5, 1.0, -1.0).finished();
  return A;
}
const VectorXd& B2() {
  static const VectorXd B = (VectorXd(2) << 0.3, -0.2).finished();
  return B;
}
const VectorXd& Uw2() {
  static const VectorXd U = (VectorXd(2) << -6.0, 1.0).finished();
  return U;
}
const MatrixXd& G2() {
  static const MatrixXd G = (MatrixXd(2, 2) << 0.12, 0.02, 0.15, 0.1).finished();
  return G;
}
const MatrixXd& C2() {
  static const MatrixXd C = (MatrixXd(1, 2) << -100.0, 10.0).finished();
  return C;
}

std::string paper003_model(int gamma_times_two, int substeps) {
  std::string text = "name: paper003_gamma" + std::to_string(gamma_times_two) +
                     "\nstates: [x1, x2]\ndrift: [\"-x1 + 0.5*x2 + 0.3\", \"x1 - x2 - 0.2\"]\n";
  if (gamma_times_two == 0)  // g = [Uw, G]
    text += "diffusion: [[\"-6\", \"0.12\", \"0.02\"], [\"1\", \"0.15\", \"0.1\"]]\n";
  else if (gamma_times_two == 2)  // g = [Uw, G diag(x)]
    text += "diffusion: [[\"-6\", \"0.12*x1\", \"0.02*x2\"], [\"1\", \"0.15*x1\", \"0.1*x2\"]]\n";
  else  // g g^T = Uw Uw^T + sum_j G_j G_j^T x_j, affine in x
    text += "diffusion_covariance: [[\"36 + 0.0144*x1 + 0.0004*x2\", \"-6 + 0.018*x1 + 0.002*x2\"],"
            " [\"-6 + 0.018*x1 + 0.002*x2\", \"1 + 0.0225*x1 + 0.01*x2\"]]\n";
  return text + "observation:\n  sampled:\n    period: 1\n    C: [[\"-100\", \"10\"]]\n    Uv: [[\"1\"]]\n    substeps: " +
         std::to_string(substeps) + "\n";
}

}  // namespace

TEST_CASE("cd-euler is paper 003's recursion (eqs 4-9) for gamma = 0, 0.5 and 1", "[sampled][unit]") {
  const int substeps = 10;
  const double Delta = 1.0 / substeps;
  // Eq 3: A~ = I + A Delta, B~ = B Delta, U~ = Uw sqrt(Delta), G~ = G sqrt(Delta).
  const MatrixXd At = MatrixXd::Identity(2, 2) + A2() * Delta;
  const VectorXd Bt = B2() * Delta;
  const VectorXd Ut = Uw2() * std::sqrt(Delta);
  const MatrixXd Gt = G2() * std::sqrt(Delta);
  const MatrixXd R = MatrixXd::Identity(1, 1);
  for (int gamma_times_two : {0, 1, 2}) {
    INFO("gamma = " << gamma_times_two / 2.0);
    const Model model = load_model_text(paper003_model(gamma_times_two, substeps), "paper003.yaml");
    const FilterEquations eq = derive_filter(model, FilterKind::CdEuler);
    REQUIRE(eq.update.substeps == static_cast<std::size_t>(substeps));
    // Eq 9: E[diag(x^gamma) diag(x^gamma)^T] = diag(P_jj + m_j^2), diag(m_j), I.
    auto noise = [&](const Moments& x) {
      VectorXd e(2);
      for (int j = 0; j < 2; ++j)
        e(j) = gamma_times_two == 2 ? x.P(j, j) + x.m(j) * x.m(j) : gamma_times_two == 1 ? x.m(j) : 1.0;
      return MatrixXd(Ut * Ut.transpose() + Gt * e.asDiagonal() * Gt.transpose());
    };
    Moments pfgen{(VectorXd(2) << 3.0, 1.5).finished(), (MatrixXd(2, 2) << 2.0, 0.3, 0.3, 1.0).finished()};
    Moments paper = pfgen;
    const std::vector<double> samples = {-250.0, -180.0, -120.0};
    for (double y : samples) {
      for (int s = 0; s < substeps; ++s) {
        // Eq 4 and eq 8 (with eq 9): the prediction over one sub-step.
        const Moments before = paper;
        paper.m = At * before.m + Bt;
        paper.P = At * before.P * At.transpose() + noise(before);
        euler_map(model, eq, pfgen, Delta);
        INFO("sub-step " << s);
        CHECK((pfgen.m - paper.m).norm() <= 1e-12 * paper.m.norm());
        CHECK(relative_error(pfgen.P, paper.P) <= 1e-12);
      }
      // Eq 7 (gain), eq 5 (mean) and the posterior covariance (I - K C) P of the paper's proof.
      const MatrixXd S = C2() * paper.P * C2().transpose() + R;
      const MatrixXd K = paper.P * C2().transpose() * S.inverse();
      CHECK(relative_error(matrix_of(evaluate(model, eq, pfgen.m, pfgen.P).gain), K) <= 1e-12);
      paper.m += K * (VectorXd::Constant(1, y) - C2() * paper.m);
      paper.P = (MatrixXd::Identity(2, 2) - K * C2()) * paper.P;
      joseph_update(model, eq, pfgen, VectorXd::Constant(1, y), C2(), VectorXd::Zero(1), R);
      CHECK((pfgen.m - paper.m).norm() <= 1e-9 * paper.m.norm());
      CHECK(relative_error(pfgen.P, paper.P) <= 1e-8);
    }
  }
}

TEST_CASE("cd-euler's dt^2 term is Cov(f) under the Gaussian closure, by Isserlis-Wick", "[sampled][unit]") {
  const Model model = load_model_text(
      "name: cubic\nstates: [x1, x2]\n"
      "drift: [\"x1 - x1^3 + 0.5*x2\", \"-x2 + x1*x2 - 0.25*x1^2\"]\n"
      "diffusion: [[\"0.5 + 0.1*x1\"], [\"0.2*x2\"]]\n"
      "observation:\n  sampled:\n    period: 0.5\n    C: [[\"1\", \"0\"]]\n    Uv: [[\"0.3\"]]\n",
      "cubic.yaml");
  const FilterEquations euler = derive_filter(model, FilterKind::CdEuler);
  const FilterEquations optimal = derive_filter(model, FilterKind::CdOptimal);
  pfgen_test::IsserlisReference ref(model.states, euler.variables);
  const std::vector<GiNaC::ex>& symbols = euler.variables.symbols();
  std::vector<GiNaC::ex> Ef;
  for (const auto& fi : model.drift) Ef.push_back(ref.expectation(fi));
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = i; j < 2; ++j) {
      INFO("Cov(f)[" << i + 1 << "][" << j + 1 << "]");
      const GiNaC::ex expected = (ref.expectation(model.drift[i] * model.drift[j]) - Ef[i] * Ef[j]).expand();
      const GiNaC::ex derived = euler.P_euler[euler.variables.upper_index(i, j)].to_ex(symbols);
      CHECK((expected - derived).expand().is_zero());
    }
  // cd-euler and cd-optimal share the first-order terms: the m drift and E[(x-m) f^T] + ... + E[g g^T].
  for (std::size_t u = 0; u < euler.P_moment.size(); ++u) {
    CHECK((euler.P_drift(u == 2 ? 1 : 0, u == 0 ? 0 : 1).to_ex(symbols) -
           optimal.P_drift(u == 2 ? 1 : 0, u == 0 ? 0 : 1).to_ex(symbols)).expand().is_zero());
  }
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK((euler.m_drift[i].to_ex(symbols) - ref.expectation(model.drift[i])).expand().is_zero());
    CHECK((optimal.m_drift[i].to_ex(symbols) - ref.expectation(model.drift[i])).expand().is_zero());
  }
  // The evaluator reads the same term at a point: P_dt2 of eval.
  const VectorXd m = (VectorXd(2) << 0.5, -1.0).finished();
  const MatrixXd P = (MatrixXd(2, 2) << 0.5, 0.125, 0.125, 0.25).finished();
  const EvaluatedFilter e = evaluate(model, euler, m, P);
  GiNaC::exmap at;
  at[symbols[euler.variables.m(0)]] = GiNaC::numeric(1, 2);
  at[symbols[euler.variables.m(1)]] = -1;
  at[symbols[euler.variables.P(0, 0)]] = GiNaC::numeric(1, 2);
  at[symbols[euler.variables.P(0, 1)]] = GiNaC::numeric(1, 8);
  at[symbols[euler.variables.P(1, 1)]] = GiNaC::numeric(1, 4);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j) {
      const GiNaC::ex exact = (ref.expectation(model.drift[i] * model.drift[j]) - Ef[i] * Ef[j]).subs(at).evalf();
      CHECK(e.P_dt2[i][j] == Approx(GiNaC::ex_to<GiNaC::numeric>(exact).to_double()).epsilon(1e-14));
    }
}

namespace {

// An epidemic observed once a day (period 1): S susceptible, Inf infected among N = 763, the
// infected counted with noise r. Its prediction's covariance grows at about 2 (beta S/N - gamma)
// = 2.5 a day at the prior, so one Heun step a day does not hold P positive definite.
std::string epidemic_model(const std::string& substeps_line) {
  return "name: epidemic\nstates: [S, Inf]\nparameters: {beta: 1.7, gamma: 0.45, N: 763, s: 0.05, r: 5}\n"
         "drift: [\"-beta*S*Inf/N\", \"beta*S*Inf/N - gamma*Inf\"]\n"
         "diffusion: [[\"-s*S\", \"0\"], [\"s*S\", \"-s*Inf\"]]\n"
         "observation:\n  sampled:\n    period: 1\n    C: [[\"0\", \"1\"]]\n    Uv: [[\"r\"]]\n" +
         substeps_line + "initial: {x0: prior, m0: [762, 1], P0: [[1, 0], [0, 1]]}\n";
}

// The spectral radius of the prediction's Jacobian at (m, P), by central differences of the
// evaluator's drifts (the test's own, not the derivation's term-wise Jacobian).
double prediction_rate(const Model& model, const FilterEquations& eq, const VectorXd& m, const MatrixXd& P) {
  const auto n = m.size();
  std::vector<std::pair<Eigen::Index, Eigen::Index>> entries;  // -1: m_i; else P_ij, i <= j
  for (Eigen::Index i = 0; i < n; ++i) entries.push_back({i, -1});
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i; j < n; ++j) entries.push_back({i, j});
  auto field = [&](const VectorXd& mm, const MatrixXd& PP) {
    const EvaluatedFilter e = evaluate(model, eq, mm, PP);
    VectorXd out(static_cast<Eigen::Index>(entries.size()));
    for (std::size_t k = 0; k < entries.size(); ++k)
      out(static_cast<Eigen::Index>(k)) = entries[k].second < 0 ? e.m_drift[entries[k].first]
                                                                : e.P_drift[entries[k].first][entries[k].second];
    return out;
  };
  const auto d = static_cast<Eigen::Index>(entries.size());
  MatrixXd J(d, d);
  for (Eigen::Index k = 0; k < d; ++k) {
    const double h = 1e-4;
    VectorXd m_plus = m, m_minus = m;
    MatrixXd P_plus = P, P_minus = P;
    const auto [i, j] = entries[static_cast<std::size_t>(k)];
    if (j < 0) {
      m_plus(i) += h, m_minus(i) -= h;
    } else {  // one variable for P_ij and P_ji
      P_plus(i, j) += h, P_minus(i, j) -= h;
      if (i != j) P_plus(j, i) += h, P_minus(j, i) -= h;
    }
    J.col(k) = (field(m_plus, P_plus) - field(m_minus, P_minus)) / (2 * h);
  }
  return Eigen::EigenSolver<MatrixXd>(J, false).eigenvalues().cwiseAbs().maxCoeff();
}

// The filter over `days` daily samples of a noise-free epidemic curve, `substeps` Heun steps a
// day; the moments after each update, or fewer where P stopped being positive definite.
std::vector<Moments> daily_filter(const Model& model, const FilterEquations& eq, int substeps, int days) {
  // The truth: the deterministic epidemic by RK4 at 1000 steps a day.
  auto f = [](const Eigen::Vector2d& x) {
    const double infections = 1.7 * x(0) * x(1) / 763;
    return Eigen::Vector2d(-infections, infections - 0.45 * x(1));
  };
  Eigen::Vector2d truth(762, 1);
  Moments x{(VectorXd(2) << 762, 1).finished(), MatrixXd::Identity(2, 2)};
  const MatrixXd C = (MatrixXd(1, 2) << 0, 1).finished();
  std::vector<Moments> out;
  for (int k = 0; k < days; ++k) {
    for (int s = 0; s < 1000; ++s) {
      const double h = 1e-3;
      const Eigen::Vector2d k1 = f(truth), k2 = f(truth + h / 2 * k1), k3 = f(truth + h / 2 * k2), k4 = f(truth + h * k3);
      truth += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    for (int s = 0; s < substeps; ++s) heun(model, eq, x, 1.0 / substeps);
    if (Eigen::LLT<MatrixXd>(x.P).info() != Eigen::Success || !x.m.allFinite()) break;
    joseph_update(model, eq, x, VectorXd::Constant(1, truth(1)), C, VectorXd::Zero(1), MatrixXd::Constant(1, 1, 25));
    out.push_back(x);
  }
  return out;
}

}  // namespace

TEST_CASE("a sampled model without substeps predicts in as many sub-steps as its rate at the prior needs",
          "[sampled][unit]") {
  const Model model = load_model_text(epidemic_model(""), "epidemic.yaml");
  for (FilterKind kind : {FilterKind::CdOptimal, FilterKind::CdEkf, FilterKind::CdEuler}) {
    const FilterEquations eq = derive_filter(model, kind);
    const double rho = prediction_rate(model, eq, (VectorXd(2) << 762, 1).finished(), MatrixXd::Identity(2, 2));
    INFO(eq.name << ": rate " << rho << ", sub-steps " << eq.update.substeps);
    CHECK(eq.update.substeps_chosen);
    CHECK(std::abs(eq.update.prior_rate - rho) <= 1e-6 * rho);
    // The rate's count (T = 1), doubled while the first period from the prior is not settled.
    const auto by_rate = static_cast<std::size_t>(std::ceil(rho / 0.25));
    CHECK(eq.update.substeps >= by_rate);
    CHECK(eq.update.substeps % by_rate == 0);
    CHECK(equations_text(model, eq).find("sub-steps of dt = T/" + std::to_string(eq.update.substeps) +
                                         " between samples (chosen from the prediction at the prior: rate ") !=
          std::string::npos);
  }

  // The chosen count holds the filter over the epidemic's peak: positive definite throughout and
  // within 2 % of a 400-sub-step reference after every update; one Heun step a day (the old
  // default) loses P's positive definiteness, and the rate's count alone (11) is 5 % off.
  const FilterEquations eq = derive_filter(model, FilterKind::CdOptimal);
  const int days = 14;
  const std::vector<Moments> reference = daily_filter(model, eq, 400, days);
  REQUIRE(reference.size() == static_cast<std::size_t>(days));
  const std::vector<Moments> chosen = daily_filter(model, eq, static_cast<int>(eq.update.substeps), days);
  REQUIRE(chosen.size() == static_cast<std::size_t>(days));
  double worst = 0;
  for (int k = 0; k < days; ++k)
    worst = std::max({worst, (chosen[k].m - reference[k].m).norm() / reference[k].m.norm(),
                      relative_error(chosen[k].P, reference[k].P)});
  INFO("largest relative difference from the reference " << worst);
  CHECK(worst < 2e-2);
  CHECK(daily_filter(model, eq, 1, days).size() < static_cast<std::size_t>(days));
}

TEST_CASE("a sampled model's own substeps are kept, with the rule's count beside when it asks for more",
          "[sampled][unit]") {
  const Model model = load_model_text(epidemic_model("    substeps: 2\n"), "epidemic.yaml");
  const FilterEquations eq = derive_filter(model, FilterKind::CdOptimal);
  CHECK(eq.update.substeps == 2);
  CHECK_FALSE(eq.update.substeps_chosen);
  CHECK(equations_text(model, eq).find("2 sub-steps of dt = T/2 between samples (fewer than the " +
                                       std::to_string(derive_filter(load_model_text(epidemic_model(""), "e.yaml"),
                                                                    FilterKind::CdOptimal).update.substeps) +
                                       " asked for by the prediction at the prior: rate 2.51 per unit of time, first "
                                       "period to 1 %)") != std::string::npos);
  // KIND@S is the count asked for by name: kept, not chosen.
  const FilterEquations named = derive_named_filter(model, "cd-euler@1");
  CHECK(named.update.substeps == 1);
  CHECK_FALSE(named.update.substeps_chosen);
}

TEST_CASE("a sampled model whose prediction is too fast for any chosen count is refused, naming the field",
          "[sampled][unit]") {
  const std::string text = "name: stiff\nstates: [x]\ndrift: [\"-1e6*x\"]\ndiffusion: [[\"1\"]]\n"
                           "observation:\n  sampled: {period: 1, C: [[\"1\"]], Uv: [[\"1\"]]}\n";
  const Model model = load_model_text(text, "stiff.yaml");
  try {
    derive_filter(model, FilterKind::CdOptimal);
    FAIL("no error");
  } catch (const ModelError& error) {
    const std::string message = error.what();
    INFO(message);
    CHECK(message.find("stiff.yaml") != std::string::npos);
    CHECK(message.find("observation.sampled") != std::string::npos);
    CHECK(message.find("prediction from the prior (rate 2e+06 per unit of time) needs more than 100000 sub-steps") !=
          std::string::npos);
    CHECK(message.find("give substeps, or a shorter period") != std::string::npos);
  }
  // With substeps given the model is the user's to run.
  const Model given = load_model_text(text.substr(0, text.size() - 2) + ", substeps: 3}\n", "stiff.yaml");
  CHECK(derive_filter(given, FilterKind::CdOptimal).update.substeps == 3);
}
