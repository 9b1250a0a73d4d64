#pragma once
// What one Monte Carlo run leaves behind for the statistics: no paths, only values at the plan's
// points and the run's own sums. The worker that made the run writes it into the slot of the
// run's number; the aggregation reads all slots in run order once every run has finished, which
// is what makes the result independent of the thread count.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pfgen_runtime::monte_carlo_detail {

// Marks what a run did not reach (the writers print it as '-' or an empty cell).
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct FilterRunResult {
  std::ptrdiff_t last = -1;  // last grid index with a stored filter state; -1: none
  bool diverged = false, psd_lost = false;
  bool too_stiff = false;  // diverged because a grid step needed more sub-steps than allowed
  bool undefined = false;  // diverged because its equations were not finite at its own state
  bool unrealisable = false;  // a moment filter stopped where its moments left the realisable set (diverged)
  double divergence_t = nan, psd_t = nan;
  std::vector<double> mean_square;   // (1 + windows) x n, the horizon first; NaN unless reached
  std::vector<double> report_error;  // reports x n; NaN where not alive
  std::vector<double> peak;          // n: max |e| over the stored states
  std::uint64_t refined_steps = 0;   // grid steps the FilterStepper split
  std::vector<double> error_record;  // records x n
  std::vector<double> m_record, P_record;  // records x n, the shown run only
  // Sampled observations: per measurement component i, sample_sums[4 i + (0, 1, 2, 3)] are the
  // sums over the samples absorbed of (Y - Yhat)^2 and |Y - Yhat| / |Y| with Y the noise-free
  // C0 + C x(t_k) (0, 2) and the sample y_k (1, 3); Yhat = C0 + C m(t_k|t_k).
  std::vector<double> sample_sums;
  std::size_t samples = 0;     // samples absorbed
  bool update_failed = false;  // an update met C P C^T + Uv Uv^T not positive definite (diverged)
  // The criterion's I = int L dt by the trapezoid rule over the grid points visited so far (the
  // whole horizon when last == steps); 0 unless MonteCarloOptions::criterion is set.
  double integral = 0;
  // With the particle reference (else empty): (m - m_ref)^2 averaged over the horizon's grid
  // points (n; NaN unless the filter and the reference reached T), and m - m_ref at the record
  // points (records x n; NaN where either had stopped).
  std::vector<double> reference_square;
  std::vector<double> reference_record;
  // The normalised estimation error squared e^T P^-1 e (NaN where the filter had stopped or P was
  // not positive definite): at the record points (records), and at the report times and T
  // (reports + 1, T last).
  std::vector<double> nees_record;
  std::vector<double> nees;
};

// The particle reference's run (MonteCarloOptions::reference).
struct ReferenceRunResult {
  std::ptrdiff_t last = -1;  // last grid index with a reference mean; -1: none
  bool stopped = false;      // every particle diverged before the truth's end
  double stop_t = nan;
  std::uint64_t resamplings = 0;
  std::vector<double> mean_square;   // n: (x - m_ref)^2 over the horizon's grid points; NaN unless last == steps
  std::vector<double> error_record;  // records x n: x - m_ref; NaN where not reached
  std::vector<double> m_record;      // records x n, the shown run only
  // n: (m_ref - m_ref')^2 over the horizon's grid points, m_ref' the mean of a second, independent
  // particle set; NaN unless both reached T.
  std::vector<double> spread_square;
};

struct RunResult {
  std::ptrdiff_t truth_last = -1;  // last grid index with a stored truth state; -1: none
  bool truth_diverged = false;
  bool truth_covariance_indefinite = false;  // stopped because G lost definiteness
  double truth_divergence_t = nan;
  std::vector<double> truth_record;  // records x n
  std::vector<double> truth_report;  // reports x n; NaN where the truth had stopped
  std::vector<FilterRunResult> filters;
  ReferenceRunResult reference;
};

}  // namespace pfgen_runtime::monte_carlo_detail
