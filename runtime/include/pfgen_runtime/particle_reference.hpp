#pragma once
// The particle reference (docs/theory.md §7.4): a bootstrap particle filter on one run's
// observation increments dy, whose weighted mean estimates the true conditional mean E[x_t | Y_t]
// for the filters' prior N(m0, P0). `pfgen simulate --reference particles:N` runs it beside the
// filters and reports how far each filter's m is from it.
//
// - Prior: N particles drawn from N(m0, P0) (P0's symmetric square root, so a singular P0 is fine).
// - Propagation: each particle by the truth's own scheme (a clone) over each grid step, with its
//   own Wiener increments.
// - Weights (continuous observation dy = h(t, x) dt + B dW, R = B B^T, h = A0 + A x or a
//   nonlinear rate): per grid step the Girsanov log-likelihood increment
//     log w_i += h_i^T R^-1 dy - 1/2 h_i^T R^-1 h_i dt,
//   with h_i = 1/2 [h(t, x_i(t)) + h(t + dt, x_i(t + dt))], the trapezoid the truth's dy uses
//   (Observation::increment), and R at the step's left end as its noise term. Normalised
//   with the largest log-weight subtracted.
// - Sampled observations y_k = C0 + C x(t_k) + Uv v_k (or c(x(t_k)) + Uv v_k) instead: the weights
//   change only at the samples, by log w_i += -1/2 (y_k - C0 - C x_i)^T (Uv Uv^T)^-1 (y_k - C0 - C x_i),
//   c(x_i) in place of C0 + C x_i.
// - Resampling: systematic (one uniform), when the effective sample size 1 / sum w^2 (w
//   normalised) falls below kResampleFraction N.
// - A particle whose state is non-finite or beyond the run's divergence bound, or whose step the
//   scheme could not finish, gets weight 0 and is no longer stepped; when every particle has, the
//   reference stops for the run.
//
// Layout: the particles are stepped in blocks of kParticleBlock, each block's states entry-major
// (structure of arrays), so that the truth scheme steps a block in one batched call
// (TruthScheme::step_batch) and the weights run over contiguous lanes. A lane computes exactly
// what a particle stepped alone would: the blocks change the speed, never a bit of the result.
//
// Random numbers: RandomStream(seed, run, substream::particle_reference), consumed in order (n
// normals per particle for the prior, then per grid step q normals per particle in particle
// order, dead ones included, and one uniform per resampling); an adaptive scheme's bridge draws
// come from substream::particle_refinement (a second set, `set` 1: substream::second_particle_*).
// So the reference depends on (seed, run, N) only, never on threads. Continuous undelayed or sampled observations and a truth with noise (q > 0) only:
// without process noise the particles never spread, and a delayed observation's likelihood
// depends on the path h back.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "pfgen_runtime/observation.hpp"
#include "pfgen_runtime/random.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_runtime/simulation.hpp"

namespace pfgen_runtime {

// Resample when the effective sample size falls below this fraction of N (the customary 1/2).
inline constexpr double kResampleFraction = 0.5;
// The largest N `pfgen simulate` accepts (N particles of n doubles each per thread).
inline constexpr std::size_t kMaxParticles = 1000000;
// Particles per block: enough lanes for any SIMD width and to spread a call over, few enough that
// a block's f and g stay in the L1 cache.
inline constexpr std::size_t kParticleBlock = 32;

struct ParticleReferenceOptions {
  std::size_t particles = 1000;  // N, 1 .. kMaxParticles
  Eigen::VectorXd m0;            // the filters' prior mean (n)
  Eigen::MatrixXd P0;            // and covariance (n x n, symmetric positive semi-definite)
};

// What one run of the reference did.
struct ParticleReferenceRun {
  std::ptrdiff_t last = -1;   // last grid index with a reference mean (-1: none)
  bool stopped = false;       // every particle diverged (or R was not positive definite) before the truth's end
  double stop_t = 0;          // the grid time it stopped at (when stopped)
  std::uint64_t resamplings = 0;
  std::uint64_t particle_steps = 0;  // scheme steps taken, for the timing line
};

// One run's observations as the truth made them: its increments dy (p x steps) for continuous
// observations, or its samples y_1 .. y_count (the columns of `samples`, draw_samples' noisy, y_s
// at grid index s steps_per_sample) for sampled ones. Only the observation's own kind is read.
struct ObservedRun {
  const Eigen::MatrixXd* dy = nullptr;
  const Eigen::MatrixXd* samples = nullptr;
  std::size_t sample_count = 0;
};

class ParticleReference {
 public:
  // std::invalid_argument: N outside 1 .. kMaxParticles, m0 or P0 not the truth's n, P0 not
  // symmetric positive semi-definite, an observation with a delay or of other n, or q == 0.
  // `bound`: the divergence bound of the truth (DivergenceGuard) that ends a particle.
  ParticleReference(const TruthScheme& scheme, const Observation& observation, const ParticleReferenceOptions& options,
                    double bound);

  // Runs the filter over run `run`'s observations up to grid index truth_last on `grid`, writing
  // the weighted mean at grid index j into mean.col(j) for j = 0 .. result.last (mean is
  // n x (grid.steps + 1), sized by the caller). truth_last < 0: nothing (last = -1).
  // `set` 1 draws a second particle set, independent of set 0's (substream::second_particle_*):
  // the spread of the two means estimates the Monte Carlo error of either.
  ParticleReferenceRun run(const TimeGrid& grid, const ObservedRun& observed, std::ptrdiff_t truth_last,
                           std::uint64_t seed, std::uint64_t run, Eigen::MatrixXd& mean, unsigned set = 0);
  // The same on continuous increments dy.col(0 .. truth_last - 1).
  ParticleReferenceRun run(const TimeGrid& grid, const Eigen::MatrixXd& dy, std::ptrdiff_t truth_last,
                           std::uint64_t seed, std::uint64_t run, Eigen::MatrixXd& mean, unsigned set = 0) {
    return this->run(grid, ObservedRun{&dy, nullptr, 0}, truth_last, seed, run, mean, set);
  }

  std::size_t particles() const { return N_; }

 private:
  void initialise(const ParticleReferenceOptions& options);
  // run()'s weighting by the timing: Girsanov's per grid step on increments, the Gaussian
  // likelihood at the samples.
  ParticleReferenceRun run_increments(const TimeGrid& grid, const Eigen::MatrixXd& dy, std::ptrdiff_t truth_last,
                                      RandomStream& stream, Eigen::MatrixXd& mean);
  ParticleReferenceRun run_samples(const TimeGrid& grid, const Eigen::MatrixXd& samples, std::size_t count,
                                   std::ptrdiff_t truth_last, RandomStream& stream, Eigen::MatrixXd& mean);
  // A run's start for both timings: the truth's scheme keyed for the run, the particles'
  // own stream, and the prior drawn from it.
  RandomStream begin_run(std::uint64_t seed, std::uint64_t run, unsigned set);
  // `result` marked as stopped at t (every weight 0, or a covariance that is not positive definite).
  static ParticleReferenceRun stopped(ParticleReferenceRun result, double t);
  void draw_prior(RandomStream& stream);
  // Every living particle over [t, t + dt], block by block; with continuous observations
  // (`weigh`) each block's weights then take the step's likelihood (R_inv_ and R_inv_dy_ already
  // set; the rates at t_end = the grid's t + dt).
  void propagate(double t, double dt, double t_end, RandomStream& stream, ParticleReferenceRun& result, bool weigh);
  // Block b's observation rate at t into `rate` (p x kParticleBlock, entry-major).
  void block_rate(double t, std::size_t b, double* rate);
  // Block b's log-weights for the grid step just taken: the trapezoid of its start and end rates.
  void weigh_block(std::size_t b, double dt);
  // Weighted mean into `out` and, when the ESS is low, systematic resampling. False when every
  // weight is 0 (or not finite).
  bool weigh_and_resample(Eigen::Ref<Eigen::VectorXd> out, RandomStream& stream, std::uint64_t& resamplings);
  // Particle i's entry e in a blocked array of `rows` entries per particle.
  static std::size_t at(std::size_t rows, std::size_t i, std::size_t e) {
    return (i / kParticleBlock) * rows * kParticleBlock + e * kParticleBlock + i % kParticleBlock;
  }
  double* block(std::vector<double>& values, std::size_t rows, std::size_t b) {
    return values.data() + b * rows * kParticleBlock;
  }

  std::unique_ptr<TruthScheme> scheme_;
  Observation observation_;
  std::size_t N_, n_, q_, p_;
  std::size_t blocks_;  // ceil(N / kParticleBlock); the last block's lanes beyond N are dead
  Eigen::VectorXd m0_;
  Eigen::MatrixXd root_;  // P0^(1/2)
  double bound_;
  std::vector<double> particles_, spare_;        // n per particle, blocked (spare_: the resampled set)
  std::vector<double> rate_start_, rate_spare_;  // p per particle: h(t, x_i) at the step's left end
  std::vector<double> rate_end_;                 // one block's h(t + dt, x_i)
  std::vector<double> dW_;                       // one block's increments, q per particle
  std::vector<double> noise_;                    // their standard normals, in drawing order
  std::vector<double> log_weight_, weight_, share_;  // share_: weight / their sum
  // weight_ (and its sum and sum of squares) is that of the present log-weights and living
  // particles; false after anything changes them.
  bool weights_current_ = false;
  double weight_sum_ = 0, weight_squares_ = 0;
  std::vector<LaneFlag> alive_, alive_spare_;    // blocks_ * kParticleBlock lanes
  Eigen::VectorXd x_, z_, R_inv_dy_, h_, R_inv_h_;
  Eigen::MatrixXd R_inv_;
  std::vector<double> Uv_;         // a sample's noise factor, row-major
  std::vector<double> predicted_;  // h(t_k, x_i)
  Eigen::VectorXd innovation_;
};

}  // namespace pfgen_runtime
