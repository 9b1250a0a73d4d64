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

namespace {

// The living lanes of a block.
std::uint64_t living(const LaneFlag* alive) { return lanes_set(alive, kParticleBlock); }

}  // namespace

ParticleReference::ParticleReference(const TruthScheme& scheme, const Observation& observation,
                                     const ParticleReferenceOptions& options, double bound)
    : scheme_(scheme.clone()), observation_(observation), N_(options.particles), n_(scheme.system().n),
      q_(scheme.system().q), p_(observation.p()), m0_(options.m0), bound_(bound) {
  if (observation.delay() != 0) throw std::invalid_argument("particle reference: delayed observations are not supported");
  if (observation.n() != n_) throw std::invalid_argument("particle reference: the observation must have the truth's n states");
  initialise(options);
  const auto p = static_cast<Eigen::Index>(p_);
  rate_start_.assign(blocks_ * p_ * kParticleBlock, 0.0);
  rate_spare_.assign(rate_start_.size(), 0.0);
  rate_end_.assign(p_ * kParticleBlock, 0.0);
  R_inv_.resize(p, p);
  R_inv_dy_.resize(p);
  h_.resize(p);
  R_inv_h_.resize(p);
  Uv_.resize(p_ * observation.r());
  innovation_.resize(p);
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
  blocks_ = (N_ + kParticleBlock - 1) / kParticleBlock;
  const std::size_t lanes = blocks_ * kParticleBlock;
  particles_.assign(lanes * n_, 0.0);
  spare_.assign(particles_.size(), 0.0);
  log_weight_.assign(lanes, 0.0);
  weight_.assign(N_, 0.0);
  share_.assign(N_, 0.0);
  alive_.assign(lanes, 0.0);  // the lanes beyond N stay dead
  alive_spare_.assign(lanes, 0.0);
  dW_.assign(q_ * kParticleBlock, 0.0);
  noise_.assign(q_ * kParticleBlock, 0.0);
  x_.resize(static_cast<Eigen::Index>(n_));
  z_.resize(static_cast<Eigen::Index>(n_));
}

// The observation's rate of every lane in one call over the block (each lane what the truth's
// one-state rate gives). Dead lanes are computed too, and never read.
void ParticleReference::block_rate(double t, std::size_t b, double* rate) {
  observation_.rate().lanes(t, kParticleBlock, block(particles_, n_, b), rate);
}

// log w_i += h_i^T R^-1 dy - 1/2 dt h_i^T R^-1 h_i with h_i the trapezoid 1/2 (start + end), for
// the living lanes of block b, whose end rates are in rate_end_ and then become their start. The
// arithmetic is the Eigen expressions' h.dot(R^-1 dy - 0.5 dt R^-1 h), in their order; for p = 1
// written out, without Eigen's overhead on 1-vectors.
void ParticleReference::weigh_block(std::size_t b, double dt) {
  weights_current_ = false;
  double* __restrict start = block(rate_start_, p_, b);
  const double* __restrict end = rate_end_.data();
  LaneFlag* __restrict alive = alive_.data() + b * kParticleBlock;
  double* __restrict log_weight = log_weight_.data() + b * kParticleBlock;
  if (p_ == 1) {  // one pass over the lanes, branch-free, that compilers vectorise
    const double R = R_inv_(0, 0), R_dy = R_inv_dy_[0], half_dt = 0.5 * dt;
    for (std::size_t k = 0; k < kParticleBlock; ++k) {
      const double h = 0.5 * start[k] + 0.5 * end[k];
      const double updated = log_weight[k] + h * (R_dy - half_dt * (R * h));
      log_weight[k] = alive[k] != 0 ? updated : log_weight[k];
      alive[k] = updated - updated == 0.0 ? alive[k] : 0.0;  // a non-finite weight ends it
      start[k] = end[k];  // a dead lane's rate is never read
    }
    return;
  }
  for (std::size_t k = 0; k < kParticleBlock; ++k) {
    if (!alive[k]) continue;
    for (std::size_t a = 0; a < p_; ++a)
      h_[static_cast<Eigen::Index>(a)] = 0.5 * start[a * kParticleBlock + k] + 0.5 * end[a * kParticleBlock + k];
    R_inv_h_.noalias() = R_inv_ * h_;
    log_weight[k] += h_.dot(R_inv_dy_ - 0.5 * dt * R_inv_h_);
    for (std::size_t a = 0; a < p_; ++a) start[a * kParticleBlock + k] = end[a * kParticleBlock + k];
    if (!std::isfinite(log_weight[k])) alive[k] = 0;
  }
}

bool ParticleReference::weigh_and_resample(Eigen::Ref<Eigen::VectorXd> out, RandomStream& stream,
                                           std::uint64_t& resamplings) {
  const LaneFlag* __restrict alive = alive_.data();
  const double* __restrict log_weight = log_weight_.data();
  double* __restrict weight = weight_.data();
  // Between samples (sampled observations) neither the log-weights nor the living change: the
  // weights are those of the last call, bit for bit, and their exp is not taken again.
  if (!weights_current_) {
    // The largest log-weight of the living (finite), in four running maxima and then theirs: a
    // maximum is the same in any order, but for the sign of a zero, which exp(w - largest) does not
    // see, and four chains of compares overlap where one waits on each.
    constexpr double none = -std::numeric_limits<double>::infinity();
    double top[4] = {none, none, none, none};
    std::size_t i = 0;
    for (; i + 4 <= N_; i += 4)
      for (std::size_t k = 0; k < 4; ++k) {
        const double candidate = alive[i + k] != 0 ? log_weight[i + k] : none;
        top[k] = candidate > top[k] ? candidate : top[k];
      }
    for (; i < N_; ++i) {
      const double candidate = alive[i] != 0 ? log_weight[i] : none;
      top[0] = candidate > top[0] ? candidate : top[0];
    }
    const double largest = std::max(std::max(top[0], top[1]), std::max(top[2], top[3]));
    if (!std::isfinite(largest)) return false;
    double sum = 0, squares = 0;
    for (std::size_t i = 0; i < N_; ++i) {
      const double w = alive[i] != 0 ? std::exp(log_weight[i] - largest) : 0.0;
      weight[i] = w;
      sum += w;
      squares += w * w;
    }
    weight_sum_ = sum;
    weight_squares_ = squares;
    // Each particle's share w / sum, once (a packed division) for all the entries of the mean.
    double* __restrict share = share_.data();
    for (std::size_t i = 0; i < N_; ++i) share[i] = weight[i] / sum;
    weights_current_ = true;
  }
  const double sum = weight_sum_, squares = weight_squares_;
  const double* __restrict share = share_.data();
  out.setZero();
  for (std::size_t e = 0; e < n_; ++e) {  // each entry's sum in particle order, as before
    // A particle of weight 0 adds +0, which leaves the sum as it was: it starts at +0 and so is
    // never -0. Adding it rather than branching keeps the loop free of branches.
    double mean = 0;
    for (std::size_t i = 0; i < N_; ++i) {
      const double term = share[i] * particles_[at(n_, i, e)];
      mean += weight[i] > 0 ? term : 0.0;
    }
    out[static_cast<Eigen::Index>(e)] = mean;
  }
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
    for (std::size_t e = 0; e < n_; ++e) spare_[at(n_, j, e)] = particles_[at(n_, i, e)];
    // The rates at the step's left end (read only for increments) go with their particles.
    for (std::size_t a = 0; a < p_; ++a) rate_spare_[at(p_, j, a)] = rate_start_[at(p_, i, a)];
    alive_spare_[j] = alive_[i];
  }
  particles_.swap(spare_);
  rate_start_.swap(rate_spare_);
  alive_.swap(alive_spare_);
  std::fill(log_weight_.begin(), log_weight_.end(), 0.0);
  weights_current_ = false;
  return true;
}

// The prior: N draws from N(m0, P0) with equal weights; a draw beyond the bound is dead at once.
void ParticleReference::draw_prior(RandomStream& stream) {
  for (std::size_t i = 0; i < N_; ++i) {
    for (Eigen::Index k = 0; k < z_.size(); ++k) z_[k] = stream.normal();
    x_ = m0_ + root_ * z_;
    for (std::size_t e = 0; e < n_; ++e) particles_[at(n_, i, e)] = x_[static_cast<Eigen::Index>(e)];
    alive_[i] = x_.allFinite() && x_.cwiseAbs().maxCoeff() <= bound_ ? 1.0 : 0.0;
    log_weight_[i] = 0;
  }
  weights_current_ = false;
}

// Block by block: the block's increments (drawn for the dead too, in particle order, so that the
// others' noise does not move when one dies), one batched step of its living lanes, the bound, and
// with continuous observations the step's weights.
void ParticleReference::propagate(double t, double dt, double t_end, RandomStream& stream,
                                  ParticleReferenceRun& result, bool weigh) {
  const double scale = std::sqrt(dt);  // dW ~ N(0, dt I), as RandomStream::wiener_increment
  for (std::size_t b = 0; b < blocks_; ++b) {
    const std::size_t lanes = std::min(kParticleBlock, N_ - b * kParticleBlock);
    const double* __restrict noise = noise_.data();
    double* __restrict dW = dW_.data();
    stream.normals(noise_.data(), lanes * q_);
    for (std::size_t k = 0; k < lanes; ++k)
      for (std::size_t j = 0; j < q_; ++j) dW[j * kParticleBlock + k] = scale * noise[k * q_ + j];
    LaneFlag* __restrict alive = alive_.data() + b * kParticleBlock;
    const std::uint64_t stepped = living(alive);
    result.particle_steps += stepped;
    double* x = block(particles_, n_, b);
    scheme_->step_batch(t, kParticleBlock, x, dt, dW, alive);
    // A particle that left the finite, bounded states is dead (NaN fails <=).
    for (std::size_t e = 0; e < n_; ++e) {
      const double* __restrict xe = x + e * kParticleBlock;
      for (std::size_t k = 0; k < kParticleBlock; ++k)
        alive[k] = std::abs(xe[k]) <= bound_ ? alive[k] : 0.0;
    }
    if (living(alive) != stepped) weights_current_ = false;  // a particle died: its weight is now 0
    if (!weigh) continue;
    block_rate(t_end, b, rate_end_.data());
    weigh_block(b, dt);
  }
}

RandomStream ParticleReference::begin_run(std::uint64_t seed, std::uint64_t run, unsigned set) {
  RandomStream stream(seed, run, set == 0 ? substream::particle_reference : substream::second_particle_reference);
  scheme_->start_run(RandomStream::derive_key(seed, run,
                                              set == 0 ? substream::particle_refinement
                                                       : substream::second_particle_refinement),
                     run);
  scheme_->set_escape_bound(bound_);
  draw_prior(stream);
  return stream;
}

ParticleReferenceRun ParticleReference::stopped(ParticleReferenceRun result, double t) {
  result.stopped = true;
  result.stop_t = t;
  return result;
}

ParticleReferenceRun ParticleReference::run(const TimeGrid& grid, const ObservedRun& observed,
                                            std::ptrdiff_t truth_last, std::uint64_t seed, std::uint64_t run,
                                            Eigen::MatrixXd& mean, unsigned set) {
  if (truth_last < 0) return ParticleReferenceRun{};
  RandomStream stream = begin_run(seed, run, set);
  if (observation_.sampled()) {
    if (!observed.samples) throw std::invalid_argument("particle reference: the run's samples are missing");
    return run_samples(grid, *observed.samples, observed.sample_count, truth_last, stream, mean);
  }
  if (!observed.dy) throw std::invalid_argument("particle reference: the run's increments are missing");
  return run_increments(grid, *observed.dy, truth_last, stream, mean);
}

ParticleReferenceRun ParticleReference::run_increments(const TimeGrid& grid, const Eigen::MatrixXd& dy,
                                                       std::ptrdiff_t truth_last, RandomStream& stream,
                                                       Eigen::MatrixXd& mean) {
  ParticleReferenceRun result;
  const auto p = static_cast<Eigen::Index>(p_);

  // Every particle's rate at t0.
  for (std::size_t b = 0; b < blocks_; ++b) block_rate(grid.t0, b, block(rate_start_, p_, b));
  if (!weigh_and_resample(mean.col(0), stream, result.resamplings)) return stopped(result, grid.time(0));
  result.last = 0;

  for (std::size_t k = 0; static_cast<std::ptrdiff_t>(k) < truth_last; ++k) {
    const double t = grid.time(k), t_end = grid.time(k + 1);
    // R = B B^T at the step's left end, as the truth's noise term.
    const Eigen::MatrixXd& B = observation_.noise(t);
    const Eigen::LLT<Eigen::MatrixXd> R(B * B.transpose());
    if (R.info() != Eigen::Success) return stopped(result, t);
    R_inv_ = R.solve(Eigen::MatrixXd::Identity(p, p));
    R_inv_dy_.noalias() = R_inv_ * dy.col(static_cast<Eigen::Index>(k));
    propagate(t, grid.dt, t_end, stream, result, true);  // the rates at the step's right end
    if (!weigh_and_resample(mean.col(static_cast<Eigen::Index>(k + 1)), stream, result.resamplings))
      return stopped(result, t_end);
    result.last = static_cast<std::ptrdiff_t>(k + 1);
  }
  return result;
}

ParticleReferenceRun ParticleReference::run_samples(const TimeGrid& grid, const Eigen::MatrixXd& samples,
                                                    std::size_t count, std::ptrdiff_t truth_last, RandomStream& stream,
                                                    Eigen::MatrixXd& mean) {
  ParticleReferenceRun result;
  const std::size_t steps_per_sample = observation_.steps_per_sample(grid.dt), q = observation_.r();
  if (!weigh_and_resample(mean.col(0), stream, result.resamplings)) return stopped(result, grid.time(0));
  result.last = 0;

  for (std::size_t k = 0; static_cast<std::ptrdiff_t>(k) < truth_last; ++k) {
    propagate(grid.time(k), grid.dt, grid.time(k + 1), stream, result, false);
    const std::size_t sample = (k + 1) / steps_per_sample;
    if ((k + 1) % steps_per_sample == 0 && sample >= 1 && sample <= count) {
      // y_s ~ N(h(t_s, x), Uv Uv^T) at t_s = t0 + s T, the time draw_samples used; Uv row-major,
      // the product's operands as they have always been laid out.
      const double t_s = grid.t0 + static_cast<double>(sample) * observation_.period();
      const Eigen::MatrixXd& noise = observation_.noise(t_s);
      const auto p = static_cast<Eigen::Index>(p_);
      for (Eigen::Index a = 0; a < p; ++a)
        for (std::size_t j = 0; j < q; ++j) Uv_[static_cast<std::size_t>(a) * q + j] = noise(a, static_cast<Eigen::Index>(j));
      const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Uv(
          Uv_.data(), p, static_cast<Eigen::Index>(q));
      const Eigen::LLT<Eigen::MatrixXd> S(Uv * Uv.transpose());
      if (S.info() != Eigen::Success) return stopped(result, grid.time(k + 1));
      const auto y = samples.col(static_cast<Eigen::Index>(sample - 1));
      weights_current_ = false;
      for (std::size_t i = 0; i < N_; ++i) {
        if (!alive_[i]) continue;
        for (std::size_t e = 0; e < n_; ++e) x_[static_cast<Eigen::Index>(e)] = particles_[at(n_, i, e)];
        observation_.rate().value(t_s, x_.data(), predicted_.data());
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
