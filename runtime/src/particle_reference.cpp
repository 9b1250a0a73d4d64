#include "pfgen_runtime/particle_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

#include "pfgen_runtime/gaussian_draw.hpp"
#include "pfgen_runtime/sde_system.hpp"

namespace pfgen_runtime {

ParticleReference::ParticleReference(const TruthScheme& scheme, const LinearObservation& observation,
                                     const ParticleReferenceOptions& options, double bound)
    : scheme_(scheme.clone()), observation_(observation), N_(options.particles), n_(scheme.system().n),
      q_(scheme.system().q), p_(observation.p()), m0_(options.m0), bound_(bound) {
  if (observation.delay() != 0) throw std::invalid_argument("particle reference: delayed observations are not supported");
  if (observation.n() != n_) throw std::invalid_argument("particle reference: the observation must have the truth's n states");
  initialise(options);
  const auto n = static_cast<Eigen::Index>(n_), p = static_cast<Eigen::Index>(p_), N = static_cast<Eigen::Index>(N_);
  rate_start_.resize(p, N);
  rate_spare_.resize(p, N);
  A0_.resize(p);
  A_.resize(p, n);
  B_.resize(p, static_cast<Eigen::Index>(observation.r()));
  R_inv_.resize(p, p);
  R_inv_dy_.resize(p);
  h_.resize(p);
  R_inv_h_.resize(p);
}

ParticleReference::ParticleReference(const TruthScheme& scheme, const SampledMeasurement& measurement,
                                     const ParticleReferenceOptions& options, double bound)
    : scheme_(scheme.clone()), measurement_(measurement), N_(options.particles), n_(scheme.system().n),
      q_(scheme.system().q), p_(measurement.p()), m0_(options.m0), bound_(bound) {
  if (measurement.n() != n_) throw std::invalid_argument("particle reference: the samples must have the truth's n states");
  initialise(options);
  C0_.resize(p_);
  C_.resize(p_ * n_);
  Uv_.resize(p_ * measurement.q());
  innovation_.resize(static_cast<Eigen::Index>(p_));
  predicted_.resize(p_);
}

// The checks and buffers both observation kinds share.
void ParticleReference::initialise(const ParticleReferenceOptions& options) {
  if (N_ < 1 || N_ > kMaxParticles)
    throw std::invalid_argument("particle reference: the number of particles must be 1 .. " +
                                std::to_string(kMaxParticles));
  if (q_ == 0)
    throw std::invalid_argument("particle reference: the truth has no process noise (q = 0); the particles would "
                                "never spread");
  if (static_cast<std::size_t>(m0_.size()) != n_ || static_cast<std::size_t>(options.P0.rows()) != n_ ||
      static_cast<std::size_t>(options.P0.cols()) != n_)
    throw std::invalid_argument("particle reference: m0 and P0 must have the truth's n states");
  if (!m0_.allFinite()) throw std::invalid_argument("particle reference: m0 must be finite");
  root_ = covariance_square_root(options.P0, "particle reference: P0");
  const auto n = static_cast<Eigen::Index>(n_), N = static_cast<Eigen::Index>(N_);
  particles_.resize(n, N);
  spare_.resize(n, N);
  log_weight_.resize(N_);
  weight_.resize(N_);
  alive_.resize(N_);
  alive_spare_.resize(N_);
  dW_.resize(static_cast<Eigen::Index>(q_));
  z_.resize(n);
}

// The rate at t: A0 + A x with the coefficients last fetched (plain loops, no temporaries: p and n
// are small), or the observation's nonlinear h(t, x).
void ParticleReference::set_rate(double t, const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::VectorXd> rate) const {
  if (!observation_->is_linear()) return observation_->nonlinear_rate(t, x.data(), rate.data());
  for (Eigen::Index a = 0; a < A_.rows(); ++a) {
    double value = A0_[a];
    for (Eigen::Index j = 0; j < A_.cols(); ++j) value += A_(a, j) * x[j];
    rate[a] = value;
  }
}

// One grid step of particle i; false when it left the finite, bounded states (then it is dead).
bool ParticleReference::step_particle(std::size_t i, double t, double dt) {
  auto x = particles_.col(static_cast<Eigen::Index>(i));
  try {
    scheme_->step(t, x, dt, dW_);
  } catch (const CovarianceIndefinite&) {
    return false;  // the truth stops there too
  }
  if (scheme_->last_step_incomplete()) return false;
  for (Eigen::Index k = 0; k < x.size(); ++k)
    if (!(std::abs(x[k]) <= bound_)) return false;
  return true;
}

bool ParticleReference::weigh_and_resample(Eigen::Ref<Eigen::VectorXd> out, RandomStream& stream,
                                           std::uint64_t& resamplings) {
  double largest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < N_; ++i)
    if (alive_[i]) largest = std::max(largest, log_weight_[i]);
  if (!std::isfinite(largest)) return false;
  double sum = 0, squares = 0;
  for (std::size_t i = 0; i < N_; ++i) {
    const double w = alive_[i] ? std::exp(log_weight_[i] - largest) : 0.0;
    weight_[i] = w;
    sum += w;
    squares += w * w;
  }
  out.setZero();
  for (std::size_t i = 0; i < N_; ++i)
    if (weight_[i] > 0) out += (weight_[i] / sum) * particles_.col(static_cast<Eigen::Index>(i));
  // ESS = (sum w)^2 / sum w^2 for unnormalised w.
  if (sum * sum >= kResampleFraction * static_cast<double>(N_) * squares) return true;

  // Systematic resampling: the points (j + U) sum / N, j = 0 .. N - 1, one uniform U, each picking
  // the particle whose cumulative-weight interval holds it. A dead particle's interval is empty.
  ++resamplings;
  const double U = stream.uniform(), step = sum / static_cast<double>(N_);
  std::size_t i = 0;
  double cumulative = weight_[0];
  for (std::size_t j = 0; j < N_; ++j) {
    const double point = (static_cast<double>(j) + U) * step;
    while (cumulative <= point && i + 1 < N_) cumulative += weight_[++i];
    while (weight_[i] == 0 && i + 1 < N_) cumulative += weight_[++i];  // round-off at the end: never a dead one
    const auto from = static_cast<Eigen::Index>(i), to = static_cast<Eigen::Index>(j);
    spare_.col(to) = particles_.col(from);
    if (observation_) rate_spare_.col(to) = rate_start_.col(from);
    alive_spare_[j] = alive_[i];
  }
  particles_.swap(spare_);
  if (observation_) rate_start_.swap(rate_spare_);
  alive_.swap(alive_spare_);
  std::fill(log_weight_.begin(), log_weight_.end(), 0.0);
  return true;
}

// The prior: N draws from N(m0, P0) with equal weights; a draw beyond the bound is dead at once.
void ParticleReference::draw_prior(RandomStream& stream) {
  for (std::size_t i = 0; i < N_; ++i) {
    for (Eigen::Index k = 0; k < z_.size(); ++k) z_[k] = stream.normal();
    auto x = particles_.col(static_cast<Eigen::Index>(i));
    x = m0_ + root_ * z_;
    alive_[i] = x.allFinite() && x.cwiseAbs().maxCoeff() <= bound_;
    log_weight_[i] = 0;
  }
}

// Every living particle over [t, t + dt]; the increments are drawn for the dead too, so that the
// others' noise does not move when one dies.
void ParticleReference::propagate(double t, double dt, RandomStream& stream, ParticleReferenceRun& result) {
  for (std::size_t i = 0; i < N_; ++i) {
    stream.wiener_increment(dt, dW_);
    if (alive_[i]) {
      alive_[i] = step_particle(i, t, dt);
      ++result.particle_steps;
    }
  }
}

RandomStream ParticleReference::begin_run(std::uint64_t seed, std::uint64_t run) {
  RandomStream stream(seed, run, substream::particle_reference);
  scheme_->start_run(RandomStream::derive_key(seed, run, substream::particle_refinement), run);
  scheme_->set_escape_bound(bound_);
  draw_prior(stream);
  return stream;
}

ParticleReferenceRun ParticleReference::stopped(ParticleReferenceRun result, double t) {
  result.stopped = true;
  result.stop_t = t;
  return result;
}

ParticleReferenceRun ParticleReference::run(const TimeGrid& grid, const Eigen::MatrixXd& dy, std::ptrdiff_t truth_last,
                                            std::uint64_t seed, std::uint64_t run, Eigen::MatrixXd& mean) {
  if (!observation_) throw std::logic_error("particle reference: made for sampled observations, run with increments");
  ParticleReferenceRun result;
  if (truth_last < 0) return result;
  RandomStream stream = begin_run(seed, run);
  const auto p = static_cast<Eigen::Index>(p_);

  // Every particle's rate at t0.
  observation_->coefficients(grid.t0, A0_, A_, B_);
  for (std::size_t i = 0; i < N_; ++i) {
    const auto column = static_cast<Eigen::Index>(i);
    set_rate(grid.t0, particles_.col(column), rate_start_.col(column));
  }
  if (!weigh_and_resample(mean.col(0), stream, result.resamplings)) return stopped(result, grid.time(0));
  result.last = 0;

  for (std::size_t k = 0; static_cast<std::ptrdiff_t>(k) < truth_last; ++k) {
    const double t = grid.time(k);
    // R = B B^T at the step's left end, as the truth's noise term.
    observation_->coefficients(t, A0_, A_, B_);
    const Eigen::LLT<Eigen::MatrixXd> R(B_ * B_.transpose());
    if (R.info() != Eigen::Success) return stopped(result, grid.time(k));
    R_inv_ = R.solve(Eigen::MatrixXd::Identity(p, p));
    R_inv_dy_.noalias() = R_inv_ * dy.col(static_cast<Eigen::Index>(k));

    propagate(t, grid.dt, stream, result);
    observation_->coefficients(grid.time(k + 1), A0_, A_, B_);
    for (std::size_t i = 0; i < N_; ++i) {
      if (!alive_[i]) continue;
      const auto column = static_cast<Eigen::Index>(i);
      auto start = rate_start_.col(column);
      // start becomes the rate at t + dt, the next step's left end; h_ the trapezoid's average.
      h_ = 0.5 * start;
      set_rate(grid.time(k + 1), particles_.col(column), start);
      h_ += 0.5 * start;
      R_inv_h_.noalias() = R_inv_ * h_;
      log_weight_[i] += h_.dot(R_inv_dy_ - 0.5 * grid.dt * R_inv_h_);
      if (!std::isfinite(log_weight_[i])) alive_[i] = 0;
    }
    if (!weigh_and_resample(mean.col(static_cast<Eigen::Index>(k + 1)), stream, result.resamplings))
      return stopped(result, grid.time(k + 1));
    result.last = static_cast<std::ptrdiff_t>(k + 1);
  }
  return result;
}

ParticleReferenceRun ParticleReference::run_sampled(const TimeGrid& grid, std::size_t steps_per_sample,
                                                    const Eigen::MatrixXd& samples, std::size_t count,
                                                    std::ptrdiff_t truth_last, std::uint64_t seed, std::uint64_t run,
                                                    Eigen::MatrixXd& mean) {
  if (!measurement_) throw std::logic_error("particle reference: made for increments dy, run with samples");
  ParticleReferenceRun result;
  if (truth_last < 0) return result;
  RandomStream stream = begin_run(seed, run);
  const std::size_t q = measurement_->q();
  if (!weigh_and_resample(mean.col(0), stream, result.resamplings)) return stopped(result, grid.time(0));
  result.last = 0;

  for (std::size_t k = 0; static_cast<std::ptrdiff_t>(k) < truth_last; ++k) {
    propagate(grid.time(k), grid.dt, stream, result);
    const std::size_t sample = (k + 1) / steps_per_sample;
    if ((k + 1) % steps_per_sample == 0 && sample >= 1 && sample <= count) {
      // y_s ~ N(C0 + C x, Uv Uv^T) at t_s = t0 + s T, the time draw_samples used.
      measurement_->evaluate(grid.t0 + static_cast<double>(sample) * measurement_->period(), C0_.data(), C_.data(),
                             Uv_.data());
      const auto p = static_cast<Eigen::Index>(p_);
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Uv(
          Uv_.data(), p, static_cast<Eigen::Index>(q));
      const Eigen::LLT<Eigen::MatrixXd> S(Uv * Uv.transpose());
      if (S.info() != Eigen::Success) return stopped(result, grid.time(k + 1));
      const auto y = samples.col(static_cast<Eigen::Index>(sample - 1));
      for (std::size_t i = 0; i < N_; ++i) {
        if (!alive_[i]) continue;
        const double* x = particles_.col(static_cast<Eigen::Index>(i)).data();
        measurement_->noise_free(grid.t0 + static_cast<double>(sample) * measurement_->period(), C0_.data(), C_.data(),
                                 x, predicted_.data());
        for (Eigen::Index a = 0; a < p; ++a) innovation_[a] = y[a] - predicted_[a];
        S.matrixL().solveInPlace(innovation_);  // L^-1 e: |L^-1 e|^2 = e^T S^-1 e
        log_weight_[i] += -0.5 * innovation_.squaredNorm();
        if (!std::isfinite(log_weight_[i])) alive_[i] = 0;
      }
    }
    if (!weigh_and_resample(mean.col(static_cast<Eigen::Index>(k + 1)), stream, result.resamplings))
      return stopped(result, grid.time(k + 1));
    result.last = static_cast<std::ptrdiff_t>(k + 1);
  }
  return result;
}

}  // namespace pfgen_runtime
