#pragma once
// Truth schemes: one step of an Ito SDE on a fixed grid, given the Wiener increment dW of the
// step (drawn by the caller, so every scheme can be driven by the same Brownian path).
//
// | scheme                 | strong order | conditions                                          |
// |------------------------|--------------|-----------------------------------------------------|
// | EulerMaruyama          | 0.5 (1 if g is constant) | globally Lipschitz f, g                 |
// | Milstein               | 1            | commutative noise (scalar, diagonal, ...);          |
// |                        |              | needs the diffusion Jacobian                        |
// | DerivativeFreeMilstein | 1            | commutative noise; only f and g (Kloeden-Platen     |
// |                        |              | 11.1, "Platen's explicit order 1.0 strong scheme")  |
// | IncrementTamedEuler    | 0.5          | superlinear f and g allowed (Hutzenthaler-Jentzen   |
// |                        |              | 2015): no step moves x by more than 1/dt            |
// | AdaptiveEuler          | 0.5 (in the  | superlinear f and g: Euler-Maruyama on Brownian-    |
// |                        | substeps)    | bridge substeps sized to the local coefficients     |
// | RungeKutta4            | 4 (ODE)      | deterministic truths only (q == 0): classical RK4   |
//
// Scheme objects keep work arrays: use one per thread (clone()).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pfgen_runtime/lane_flag.hpp"
#include "pfgen_runtime/random.hpp"

#include <limits>

#include <Eigen/Core>

#include "pfgen_runtime/sde_system.hpp"

namespace pfgen_runtime {


class TruthScheme {
 public:
  explicit TruthScheme(SdeSystem system);
  virtual ~TruthScheme() = default;

  virtual std::string name() const = 0;
  virtual double strong_order() const = 0;
  // x(t) -> x(t + dt) in place; dW has q entries, the increment of W over [t, t + dt].
  virtual void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) = 0;
  virtual std::unique_ptr<TruthScheme> clone() const = 0;
  // Steps `count` states at once over [t, t + dt]. x is entry-major (x[i * count + k] is entry i
  // of state k), and so is dW (dW[j * count + k]). Lanes with live[k] == 0 are left alone; a lane
  // whose step cannot be finished (last_step_incomplete, or CovarianceIndefinite from its
  // diffusion) gets live[k] = 0, its x then unspecified. Each lane's result is bit for bit
  // step()'s on that state, and the scheme's own draws (AdaptiveEuler's bridge) are taken in lane
  // order, as a loop over step() takes them: step_lanes_at_once, then step() for the lanes it left.
  void step_batch(double t, std::size_t count, double* x, double dt, const double* dW, LaneFlag* live);
  // The part of step_batch a scheme does for all lanes at once. take[k] is 1 for the lanes to step
  // (the live ones) on entry; the scheme steps those it can from one batched evaluation and sets
  // take[k] = 0 for the others, leaving them as they were for step() (whose own draws they need).
  // This default takes none; EulerMaruyama takes every lane and AdaptiveEuler those whose whole
  // grid step passes its size test, where the system has batched forms. Each lane taken is bit for
  // bit step()'s.
  virtual void step_lanes_at_once(double t, std::size_t count, double* x, double dt, const double* dW, LaneFlag* take);
  // True when the last step() stopped short of t + dt because it would have needed more work than
  // the scheme allows (AdaptiveEuler's substep budget); x is then not x(t + dt) and the run stops.
  virtual bool last_step_incomplete() const { return false; }
  // Called before the first step of each Monte Carlo run; schemes that draw random numbers of
  // their own (AdaptiveEuler's Brownian bridge) take them from the run's streams.
  virtual void start_run(std::uint64_t seed, std::uint64_t run) {
    (void)seed;
    (void)run;
  }

  const SdeSystem& system() const { return system_; }
  // The divergence bound of the run (DivergenceGuard). A scheme that takes substeps inside a grid
  // step (AdaptiveEuler) ends the step as soon as an entry passes it: the path has diverged there,
  // and integrating it on could carry it through infinity and back (a Stratonovich state that
  // explodes, x = -10/u with u crossing 0, came back as a finite negative x the guard never saw).
  void set_escape_bound(double bound) { escape_bound_ = bound; }

 protected:
  void evaluate_drift(double t, const Eigen::Ref<const Eigen::VectorXd>& x);      // -> f_
  void evaluate_diffusion(double t, const Eigen::Ref<const Eigen::VectorXd>& x);  // -> g_
  // Whether the system has the batched forms step_batch needs (a drift, and a diffusion if q > 0).
  bool has_batch() const;
  // f and g of `count` entry-major states into batch_f_ (n x count) and batch_g_ (n q x count).
  void evaluate_batch(double t, std::size_t count, const double* x);
  // x + f dt + g dW with evaluate_batch's f and g, for the lanes with take[k] (euler_increment's
  // sums in its order, so step()'s values), in passes over contiguous lanes that compilers
  // vectorise.
  void euler_lanes(std::size_t count, double* x, double dt, const double* dW, const LaneFlag* take);
  // Lane k of step_batch through step(): gathered, stepped, scattered; false when it could not
  // finish.
  bool step_lane(double t, std::size_t count, std::size_t k, double* x, double dt, const double* dW);
  SdeSystem system_;
  Eigen::VectorXd f_;  // n
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> g_;  // n x q
  Eigen::VectorXd increment_;  // n
  Eigen::VectorXd lane_x_, lane_dW_;     // step_lane's state and increment
  std::vector<double> batch_f_, batch_g_;  // evaluate_batch's values
  std::vector<LaneFlag> batch_take_;                  // step_batch's lanes taken at once
  double escape_bound_ = std::numeric_limits<double>::infinity();
};

// x + f dt + g dW.
class EulerMaruyama : public TruthScheme {
 public:
  explicit EulerMaruyama(SdeSystem system);
  std::string name() const override { return "euler-maruyama"; }
  double strong_order() const override { return 0.5; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  void step_lanes_at_once(double t, std::size_t count, double* x, double dt, const double* dW, LaneFlag* take) override;
  std::unique_ptr<TruthScheme> clone() const override;
};

// x + f dt + g dW + 1/2 sum_{j,k} (L^j g_k) (dW_j dW_k - delta_jk dt), with
// (L^j g_k)_i = sum_l g_lj d g_ik / d x_l. Exact Milstein for commutative noise (no Levy areas);
// for non-commutative noise it drops the Levy-area terms and falls back to order 0.5.
class Milstein : public TruthScheme {
 public:
  explicit Milstein(SdeSystem system);  // std::invalid_argument without a diffusion Jacobian
  std::string name() const override { return "milstein"; }
  double strong_order() const override { return 1.0; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  std::unique_ptr<TruthScheme> clone() const override;

 private:
  Eigen::VectorXd jacobian_;  // n * q * n
};

// Kloeden & Platen (1992), section 11.1: with the supporting values
//   Y_j = x + f dt + g_j sqrt(dt)                 (g_j: column j of g)
//   x + f dt + g dW + 1/(2 sqrt(dt)) sum_{j,k} (g_k(Y_j) - g_k(x)) (dW_j dW_k - delta_jk dt).
// (g_k(Y_j) - g_k(x)) / sqrt(dt) = L^j g_k + O(sqrt(dt)), so this is Milstein without
// derivatives: strong order 1 for commutative noise, q + 1 diffusion evaluations per step.
class DerivativeFreeMilstein : public TruthScheme {
 public:
  explicit DerivativeFreeMilstein(SdeSystem system);
  std::string name() const override { return "derivative-free-milstein"; }
  double strong_order() const override { return 1.0; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  std::unique_ptr<TruthScheme> clone() const override;

 private:
  Eigen::VectorXd support_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> g_support_;
};

// Increment-tamed Euler-Maruyama (Hutzenthaler & Jentzen, Mem. AMS 236, 2015):
//   D = f dt + g dW,   x + D / max(1, dt |D|).
// Equal to Euler-Maruyama whenever |D| <= 1/dt, so strong order 0.5 where EM converges; but no
// step moves x by more than 1/dt, so superlinear drift *and* diffusion cannot make it overflow.
// (The drift-only taming of Hutzenthaler-Jentzen-Kloeden 2012 needs a Lipschitz diffusion, which
// paper 000's 0.1x^2 dW is not.) This is the scheme for truths with superlinear coefficients.
class IncrementTamedEuler : public TruthScheme {
 public:
  explicit IncrementTamedEuler(SdeSystem system);
  std::string name() const override { return "tamed-euler"; }
  double strong_order() const override { return 0.5; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  std::unique_ptr<TruthScheme> clone() const override;
};

// Euler-Maruyama on adaptive substeps of each grid step, with the grid step's Wiener increment
// refined by Brownian-bridge bisection (the Brownian tree of Gaines & Lyons 1997): the substep
// [s, s + h] with known increment dW is halved, drawing W(s + h/2) - W(s) ~ N(dW/2, h/4 I), until
//   h |f_i(x)| + sqrt(h) |row i of g(x)| <= tolerance (|x_i| + scale)   for every i,
// i.e. no substep is expected to change an entry by more than a fraction `tolerance` of its size
// (floored at `scale`). The test looks at x(s) and h only, never at dW: the substep ends are then
// stopping times and the sampled quadratic variation is unbiased (testing |g dW| instead refines
// exactly the large increments, under-samples the Ito correction and drives paper 000's state to
// blow-up). The grid increments stay those the caller passed, so observations and filters see
// the same Brownian path; the bridge draws come from the run's substream::truth_refinement stream
// (start_run), keeping runs reproducible. Where the coefficients are moderate the whole grid step
// is taken at once and this is plain Euler-Maruyama; where they are large (paper 000's Ito state
// near x ~ 100, i.e. z = 10/x near 0) substeps shrink like 1/x^2 and the law stays right where
// fixed-step schemes overshoot (to negative x, or overflow). At the depth limit a substep may not
// change an entry by more than its size plus `scale`, so nothing overflows.
class AdaptiveEuler : public TruthScheme {
 public:
  struct Options {
    double tolerance = 0.05;   // relative change of x allowed per substep
    double scale = 1.0;        // |x| floor of the relative test
    int max_depth = 60;        // substeps no shorter than dt / 2^max_depth
    // Substeps one grid step may take; beyond, the step stops short and the run is reported
    // (--T 1e20 --dt 1e19 used to spin for minutes towards 2^max_depth substeps a step).
    std::uint64_t max_substeps = std::uint64_t(1) << 20;
  };
  explicit AdaptiveEuler(SdeSystem system);
  AdaptiveEuler(SdeSystem system, Options options);
  std::string name() const override { return "adaptive-euler"; }
  double strong_order() const override { return 0.5; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  // The lanes whose whole grid step passes the size test take it at once, from one batched
  // evaluation of f and g; the others go through step(), bridge draws and all.
  void step_lanes_at_once(double t, std::size_t count, double* x, double dt, const double* dW, LaneFlag* take) override;
  std::unique_ptr<TruthScheme> clone() const override;
  void start_run(std::uint64_t seed, std::uint64_t run) override;

  const Options& options() const { return options_; }
  std::uint64_t substeps() const { return substeps_; }        // taken since construction
  std::uint64_t depth_limit_hits() const { return depth_hits_; }  // substeps forced at the limit
  bool last_step_incomplete() const override { return incomplete_; }

 private:
  bool small_enough(const Eigen::Ref<const Eigen::VectorXd>& x, double h) const;
  struct Pending {
    double t;
    double h;
    int depth;
    Eigen::Index offset;  // of its increment in bridge_
  };
  Options options_;
  RandomStream bridge_stream_;
  std::vector<Pending> stack_;
  std::vector<double> bridge_;  // q entries per pending interval
  Eigen::VectorXd increment_dW_;
  std::uint64_t substeps_ = 0;
  std::uint64_t depth_hits_ = 0;
  bool incomplete_ = false;
};

// Classical fourth-order Runge-Kutta on the drift, for deterministic truths dx = f(t, x) dt
// (paper 001's state has no process noise). It refuses systems with q > 0 rather than silently
// dropping their noise: a caller whose diffusion is identically zero passes q = 0. The Euler
// schemes integrate such a truth to order 1 only; with RK4 (global error O(dt^4)) the truth's own
// error is negligible next to the filters'.
class RungeKutta4 : public TruthScheme {
 public:
  explicit RungeKutta4(SdeSystem system);  // std::invalid_argument when system.q > 0
  std::string name() const override { return "rk4"; }
  double strong_order() const override { return 4.0; }
  void step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) override;
  std::unique_ptr<TruthScheme> clone() const override;

 private:
  Eigen::VectorXd k1_, k2_, k3_, k4_, stage_;
};

// In the order of the names in pfgen_support::truth_schemes() (the one table of scheme names).
enum class SchemeKind { euler_maruyama, milstein, derivative_free_milstein, tamed_euler, adaptive_euler, rk4 };
// "euler-maruyama", "milstein", "derivative-free-milstein", "tamed-euler", "adaptive-euler", "rk4".
std::string to_string(SchemeKind kind);
SchemeKind scheme_kind_from_string(const std::string& name);  // std::invalid_argument if unknown
std::unique_ptr<TruthScheme> make_scheme(SchemeKind kind, SdeSystem system);

}  // namespace pfgen_runtime
