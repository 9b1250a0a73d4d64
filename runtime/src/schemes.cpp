#include "pfgen_runtime/schemes.hpp"

#include "pfgen_runtime/lane_pack.hpp"

#include "pfgen_support/truth_schemes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace pfgen_runtime {

namespace {

void check_dimensions(const SdeSystem& system, Eigen::Index x_size, Eigen::Index dW_size) {
  if (x_size != static_cast<Eigen::Index>(system.n) || dW_size != static_cast<Eigen::Index>(system.q))
    throw std::invalid_argument("truth scheme: x must have n entries and dW q entries");
}

// out = f h + g dW with plain loops: the systems are small, and Eigen's dynamic-size product
// costs more than the arithmetic at these sizes.
template <class G, class W>
void euler_increment(const Eigen::VectorXd& f, double h, const G& g, const W& dW, Eigen::VectorXd& out) {
  const Eigen::Index n = f.size(), q = dW.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    double value = f[i] * h;
    for (Eigen::Index j = 0; j < q; ++j) value += g(i, j) * dW[j];
    out[i] = value;
  }
}

// The length of a row of g, its q entries `stride` apart, summed in order: the one-state and the
// batched size tests of AdaptiveEuler compute it alike, so they decide alike.
double row_norm(const double* first, std::size_t stride, std::size_t q) {
  double sum = 0;
  for (std::size_t j = 0; j < q; ++j) sum += first[j * stride] * first[j * stride];
  return std::sqrt(sum);
}

}  // namespace

TruthScheme::TruthScheme(SdeSystem system)
    : system_(std::move(system)), f_(Eigen::VectorXd::Zero(system_.n)), g_(system_.n, system_.q),
      increment_(system_.n), lane_x_(system_.n), lane_dW_(system_.q) {
  system_.validate();
  g_.setZero();
}

void TruthScheme::step_batch(double t, std::size_t count, double* x, double dt, const double* dW, LaneFlag* live) {
  batch_take_.assign(live, live + count);
  step_lanes_at_once(t, count, x, dt, dW, batch_take_.data());
  // Most often every living lane was taken (a taken lane is a living one): then none is left.
  if (lanes_set(batch_take_.data(), count) == lanes_set(live, count)) return;
  for (std::size_t k = 0; k < count; ++k)
    if (live[k] != 0 && batch_take_[k] == 0 && !step_lane(t, count, k, x, dt, dW)) live[k] = 0;
}

void TruthScheme::step_lanes_at_once(double, std::size_t count, double*, double, const double*, LaneFlag* take) {
  std::fill(take, take + count, 0.0);
}

bool TruthScheme::step_lane(double t, std::size_t count, std::size_t k, double* x, double dt, const double* dW) {
  const std::size_t n = system_.n, q = system_.q;
  for (std::size_t i = 0; i < n; ++i) lane_x_[static_cast<Eigen::Index>(i)] = x[i * count + k];
  for (std::size_t j = 0; j < q; ++j) lane_dW_[static_cast<Eigen::Index>(j)] = dW[j * count + k];
  bool finished = true;
  try {
    step(t, lane_x_, dt, lane_dW_);
    finished = !last_step_incomplete();
  } catch (const CovarianceIndefinite&) {
    finished = false;
  }
  for (std::size_t i = 0; i < n; ++i) x[i * count + k] = lane_x_[static_cast<Eigen::Index>(i)];
  return finished;
}

bool TruthScheme::has_batch() const {
  return system_.drift_batch && (system_.q == 0 || system_.diffusion_batch);
}

void TruthScheme::euler_lanes(std::size_t count, double* x, double dt, const double* dW, const LaneFlag* take) {
  namespace lp = lane_pack;
  const std::size_t n = system_.n, q = system_.q;
  const double* f = batch_f_.data();
  const double* g = batch_g_.data();
  // Each lane's x + (f dt + sum_j g_j dW_j), in that order, kept where the lane takes the step.
  for (std::size_t i = 0; i < n; ++i) {
    double* xi = x + i * count;
    lp::for_lanes(count, [&](std::size_t k, auto lanes) {
      auto value = lp::load(f + i * count + k, lanes) * lp::splat(dt, lanes);
      for (std::size_t j = 0; j < q; ++j)
        value = value + lp::load(g + (i * q + j) * count + k, lanes) * lp::load(dW + j * count + k, lanes);
      const auto old = lp::load(xi + k, lanes);
      const auto taking = lp::not_equal(lp::load(take + k, lanes), lp::splat(0.0, lanes));
      lp::store(xi + k, lp::choose(taking, old + value, old), lanes);
    });
  }
}

void TruthScheme::evaluate_batch(double t, std::size_t count, const double* x) {
  batch_f_.resize(system_.n * count);
  system_.drift_batch(t, count, x, batch_f_.data());
  if (system_.q == 0) return;
  batch_g_.resize(system_.n * system_.q * count);
  system_.diffusion_batch(t, count, x, batch_g_.data());
}

void TruthScheme::evaluate_drift(double t, const Eigen::Ref<const Eigen::VectorXd>& x) {
  system_.drift(t, x.data(), f_.data());
}

void TruthScheme::evaluate_diffusion(double t, const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (system_.q > 0) system_.diffusion(t, x.data(), g_.data());
}

// --- Euler-Maruyama ---------------------------------------------------------------------------

EulerMaruyama::EulerMaruyama(SdeSystem system) : TruthScheme(std::move(system)) {}

void EulerMaruyama::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  evaluate_drift(t, x);
  evaluate_diffusion(t, x);
  euler_increment(f_, dt, g_, dW, increment_);
  x += increment_;
}

void EulerMaruyama::step_lanes_at_once(double t, std::size_t count, double* x, double dt, const double* dW,
                                       LaneFlag* take) {
  if (!has_batch()) return TruthScheme::step_lanes_at_once(t, count, x, dt, dW, take);
  evaluate_batch(t, count, x);
  euler_lanes(count, x, dt, dW, take);
}

std::unique_ptr<TruthScheme> EulerMaruyama::clone() const { return std::make_unique<EulerMaruyama>(system_); }

// --- Milstein ---------------------------------------------------------------------------------

Milstein::Milstein(SdeSystem system) : TruthScheme(std::move(system)), jacobian_(system_.n * system_.q * system_.n) {
  if (system_.q > 0 && !system_.diffusion_jacobian)
    throw std::invalid_argument("Milstein: the diffusion Jacobian is missing (use derivative-free-milstein)");
}

void Milstein::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  const std::size_t n = system_.n, q = system_.q;
  evaluate_drift(t, x);
  evaluate_diffusion(t, x);
  increment_.noalias() = f_ * dt;
  if (q > 0) {
    increment_.noalias() += g_ * dW;
    system_.diffusion_jacobian(t, x.data(), jacobian_.data());
    for (std::size_t j = 0; j < q; ++j) {
      for (std::size_t k = 0; k < q; ++k) {
        const double w = 0.5 * (dW[j] * dW[k] - (j == k ? dt : 0.0));
        for (std::size_t i = 0; i < n; ++i) {
          double Ljgk = 0;  // (L^j g_k)_i
          for (std::size_t l = 0; l < n; ++l) Ljgk += g_(l, j) * jacobian_[(i * q + k) * n + l];
          increment_[i] += Ljgk * w;
        }
      }
    }
  }
  x += increment_;
}

std::unique_ptr<TruthScheme> Milstein::clone() const { return std::make_unique<Milstein>(system_); }

// --- derivative-free Milstein (Kloeden-Platen 11.1) -------------------------------------------

DerivativeFreeMilstein::DerivativeFreeMilstein(SdeSystem system)
    : TruthScheme(std::move(system)), support_(system_.n), g_support_(system_.n, system_.q) {}

void DerivativeFreeMilstein::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt,
                                  const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  const std::size_t q = system_.q;
  evaluate_drift(t, x);
  evaluate_diffusion(t, x);
  increment_.noalias() = f_ * dt;
  if (q > 0) {
    increment_.noalias() += g_ * dW;
    const double root_dt = std::sqrt(dt);
    for (std::size_t j = 0; j < q; ++j) {
      support_ = x + f_ * dt + g_.col(j) * root_dt;
      system_.diffusion(t, support_.data(), g_support_.data());
      for (std::size_t k = 0; k < q; ++k) {
        const double w = (dW[j] * dW[k] - (j == k ? dt : 0.0)) / (2.0 * root_dt);
        increment_ += (g_support_.col(k) - g_.col(k)) * w;
      }
    }
  }
  x += increment_;
}

std::unique_ptr<TruthScheme> DerivativeFreeMilstein::clone() const {
  return std::make_unique<DerivativeFreeMilstein>(system_);
}

// --- increment-tamed Euler --------------------------------------------------------------------

IncrementTamedEuler::IncrementTamedEuler(SdeSystem system) : TruthScheme(std::move(system)) {}

void IncrementTamedEuler::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt,
                               const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  evaluate_drift(t, x);
  evaluate_diffusion(t, x);
  euler_increment(f_, dt, g_, dW, increment_);
  const double size = dt * increment_.norm();
  // A non-finite increment stays non-finite, so the divergence guard sees it.
  if (size > 1.0)
    x += increment_ / size;
  else
    x += increment_;
}

std::unique_ptr<TruthScheme> IncrementTamedEuler::clone() const {
  return std::make_unique<IncrementTamedEuler>(system_);
}

// --- adaptive Euler with Brownian-bridge substeps ---------------------------------------------

AdaptiveEuler::AdaptiveEuler(SdeSystem system) : AdaptiveEuler(std::move(system), Options()) {}

AdaptiveEuler::AdaptiveEuler(SdeSystem system, Options options)
    : TruthScheme(std::move(system)), options_(options), bridge_stream_(0, 0, substream::truth_refinement),
      increment_dW_(system_.q) {
  if (!(options_.tolerance > 0) || !(options_.scale > 0) || options_.max_depth < 0 || options_.max_depth > 62)
    throw std::invalid_argument("adaptive Euler: need tolerance > 0, scale > 0 and 0 <= max_depth <= 62");
}

// The size test of a substep of length h from x, with f_ and g_ at x. NaN compares false, so a
// non-finite state is stepped and the guard sees it.
bool AdaptiveEuler::small_enough(const Eigen::Ref<const Eigen::VectorXd>& x, double h) const {
  const std::size_t n = system_.n, q = system_.q;
  const double root_h = std::sqrt(h);
  for (std::size_t i = 0; i < n; ++i) {
    const double spread = q > 0 ? row_norm(g_.data() + i * q, 1, q) * root_h : 0.0;
    if (std::abs(f_[i]) * h + spread > options_.tolerance * (std::abs(x[i]) + options_.scale)) return false;
  }
  return true;
}

void AdaptiveEuler::start_run(std::uint64_t seed, std::uint64_t run) {
  bridge_stream_ = RandomStream(seed, run, substream::truth_refinement);
}

void AdaptiveEuler::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  const std::size_t n = system_.n, q = system_.q;
  incomplete_ = false;
  // f_ and g_ are at the start (t, x) of the interval on top of the stack: evaluated there and x not
  // moved since. The functions are pure, so they are not evaluated there again.
  bool evaluated = false;
  // The common case first: the whole grid step passes the size test and is one Euler substep, as
  // the loop below would take it, without its stack of pending intervals.
  if (options_.max_substeps > 0) {
    evaluate_drift(t, x);
    evaluate_diffusion(t, x);
    if (small_enough(x, dt)) {
      euler_increment(f_, dt, g_, dW, increment_);
      x += increment_;
      ++substeps_;
      return;
    }
    evaluated = true;
  }
  // Pending intervals, the leftmost on top; bridge_ holds their increments in the same order.
  stack_.clear();
  bridge_.clear();
  stack_.push_back({t, dt, 0, 0});
  bridge_.insert(bridge_.end(), dW.data(), dW.data() + q);
  Eigen::VectorXd& increment_dW = increment_dW_;
  const std::uint64_t budget_end = substeps_ + options_.max_substeps;
  while (!stack_.empty()) {
    if (substeps_ >= budget_end) {
      incomplete_ = true;
      return;
    }
    const Pending interval = stack_.back();
    stack_.pop_back();
    for (std::size_t j = 0; j < q; ++j) increment_dW[j] = bridge_[interval.offset + j];
    bridge_.resize(bridge_.size() - q);

    if (!evaluated) {
      evaluate_drift(interval.t, x);
      evaluate_diffusion(interval.t, x);
    }
    evaluated = false;
    // The size test uses x and h only, never the increment itself: refining the intervals whose
    // increments came out large would shrink the sampled quadratic variation below the elapsed
    // time and bias the Ito correction (for paper 000's state, towards blow-up). With a
    // previsible test the substep ends are stopping times and sum dW^2 is unbiased.
    const bool small = small_enough(x, interval.h);
    if (small || interval.depth >= options_.max_depth) {
      euler_increment(f_, interval.h, g_, increment_dW, increment_);
      if (!small) {
        // At the depth limit: no substep changes an entry by more than its size (plus scale).
        ++depth_hits_;
        double ratio = 0;
        for (std::size_t i = 0; i < n; ++i)
          ratio = std::max(ratio, std::abs(increment_[i]) / (std::abs(x[i]) + options_.scale));
        if (ratio > 1.0) increment_ /= ratio;
      }
      x += increment_;
      ++substeps_;
      // Past the bound (or non-finite: NaN fails <=) the run has diverged; the guard reports it.
      if (!(x.cwiseAbs().maxCoeff() <= escape_bound_)) return;
      continue;
    }
    // Bisect: W(s + h/2) - W(s) given W(s + h) - W(s) = dW is N(dW/2, h/4 I).
    const double half = 0.5 * interval.h, spread = 0.5 * std::sqrt(interval.h);
    const Eigen::Index right_offset = interval.offset, left_offset = interval.offset + static_cast<Eigen::Index>(q);
    bridge_.resize(bridge_.size() + 2 * q);
    for (std::size_t j = 0; j < q; ++j) {
      const double left = 0.5 * increment_dW[j] + spread * bridge_stream_.normal();
      bridge_[left_offset + j] = left;
      bridge_[right_offset + j] = increment_dW[j] - left;
    }
    stack_.push_back({interval.t + half, half, interval.depth + 1, right_offset});
    stack_.push_back({interval.t, half, interval.depth + 1, left_offset});
    evaluated = true;  // the left half, now on top, starts where its interval did
  }
}

void AdaptiveEuler::step_lanes_at_once(double t, std::size_t count, double* x, double dt, const double* dW,
                                       LaneFlag* take) {
  if (!has_batch() || options_.max_substeps == 0) return TruthScheme::step_lanes_at_once(t, count, x, dt, dW, take);
  evaluate_batch(t, count, x);
  const std::size_t n = system_.n, q = system_.q;
  const double* f = batch_f_.data();
  const double* g = batch_g_.data();
  const double root_h = std::sqrt(dt), tolerance = options_.tolerance, scale = options_.scale;
  // step()'s first interval is the whole grid step: its size test for every lane, the row norms
  // summed as row_norm sums them. A lane takes the Euler substep at once when it takes steps and
  // no entry fails the test; the others are left for step(), which bisects.
  namespace lp = lane_pack;
  lp::for_lanes(count, [&](std::size_t k, auto lanes) {
    auto exceeding = lp::splat(0.0, lanes);  // the entries failing the test, counted in doubles
    for (std::size_t i = 0; i < n; ++i) {
      auto spread = lp::splat(0.0, lanes);
      for (std::size_t j = 0; j < q; ++j) {
        const auto gij = lp::load(g + (i * q + j) * count + k, lanes);
        spread = spread + gij * gij;
      }
      if (q > 0) spread = lp::sqrt(spread) * lp::splat(root_h, lanes);
      const auto fi = lp::load(f + i * count + k, lanes), xi = lp::load(x + i * count + k, lanes);
      const auto size = lp::abs(fi) * lp::splat(dt, lanes) + spread;
      const auto allowed = lp::splat(tolerance, lanes) * (lp::abs(xi) + lp::splat(scale, lanes));
      exceeding = exceeding + lp::flag(lp::greater(size, allowed));
    }
    const auto taking = lp::both(lp::not_equal(lp::load(take + k, lanes), lp::splat(0.0, lanes)),
                                 lp::equal(exceeding, lp::splat(0.0, lanes)));
    lp::store(take + k, lp::flag(taking), lanes);
  });
  euler_lanes(count, x, dt, dW, take);
  substeps_ += lanes_set(take, count);
  incomplete_ = false;
}

std::unique_ptr<TruthScheme> AdaptiveEuler::clone() const {
  auto copy = std::make_unique<AdaptiveEuler>(system_, options_);
  copy->bridge_stream_ = bridge_stream_;
  return copy;
}

// --- classical Runge-Kutta 4 (deterministic truths) -------------------------------------------

RungeKutta4::RungeKutta4(SdeSystem system)
    : TruthScheme(std::move(system)), k1_(system_.n), k2_(system_.n), k3_(system_.n), k4_(system_.n),
      stage_(system_.n) {
  if (system_.q > 0)
    throw std::invalid_argument("rk4: for deterministic truths only (q = 0); this system has " +
                                std::to_string(system_.q) + " Wiener processes");
}

void RungeKutta4::step(double t, Eigen::Ref<Eigen::VectorXd> x, double dt, const Eigen::Ref<const Eigen::VectorXd>& dW) {
  check_dimensions(system_, x.size(), dW.size());
  const Eigen::Index n = x.size();
  const double half = 0.5 * dt;
  system_.drift(t, x.data(), k1_.data());
  for (Eigen::Index i = 0; i < n; ++i) stage_[i] = x[i] + half * k1_[i];
  system_.drift(t + half, stage_.data(), k2_.data());
  for (Eigen::Index i = 0; i < n; ++i) stage_[i] = x[i] + half * k2_[i];
  system_.drift(t + half, stage_.data(), k3_.data());
  for (Eigen::Index i = 0; i < n; ++i) stage_[i] = x[i] + dt * k3_[i];
  system_.drift(t + dt, stage_.data(), k4_.data());
  for (Eigen::Index i = 0; i < n; ++i) x[i] += dt / 6.0 * (k1_[i] + 2.0 * (k2_[i] + k3_[i]) + k4_[i]);
}

std::unique_ptr<TruthScheme> RungeKutta4::clone() const { return std::make_unique<RungeKutta4>(system_); }

// --- names and factory ------------------------------------------------------------------------

// The names are the support library's table (pfgen_support/truth_schemes.hpp), whose rows are in
// the order of SchemeKind.
std::string to_string(SchemeKind kind) {
  const auto& schemes = pfgen_support::truth_schemes();
  const auto index = static_cast<std::size_t>(kind);
  if (index >= schemes.size()) throw std::invalid_argument("unknown scheme kind");
  return schemes[index].name;
}

SchemeKind scheme_kind_from_string(const std::string& name) {
  const auto& schemes = pfgen_support::truth_schemes();
  std::string known;
  for (std::size_t k = 0; k < schemes.size(); ++k) {
    if (schemes[k].name == name) return static_cast<SchemeKind>(k);
    known += (known.empty() ? "" : ", ") + schemes[k].name;
  }
  throw std::invalid_argument("unknown truth scheme '" + name + "' (" + known + ")");
}

std::unique_ptr<TruthScheme> make_scheme(SchemeKind kind, SdeSystem system) {
  switch (kind) {
    case SchemeKind::euler_maruyama: return std::make_unique<EulerMaruyama>(std::move(system));
    case SchemeKind::milstein: return std::make_unique<Milstein>(std::move(system));
    case SchemeKind::derivative_free_milstein: return std::make_unique<DerivativeFreeMilstein>(std::move(system));
    case SchemeKind::tamed_euler: return std::make_unique<IncrementTamedEuler>(std::move(system));
    case SchemeKind::adaptive_euler: return std::make_unique<AdaptiveEuler>(std::move(system));
    case SchemeKind::rk4: return std::make_unique<RungeKutta4>(std::move(system));
  }
  throw std::invalid_argument("unknown scheme kind");
}

}  // namespace pfgen_runtime
