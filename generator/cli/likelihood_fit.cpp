#include "likelihood_fit.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <Eigen/Dense>

#include "cli_options.hpp"

namespace pfgen::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kZ95 = 1.959963984540054;      // the normal law's 0.975-quantile
constexpr double kChi95Half = 1.920729410347062;  // half the chi-square(1) law's 0.95-quantile

// The parameters are optimised in units of their start's magnitude (u = theta / scale), so that
// variances of 10^4 and rates of 10^-1 are equally well conditioned for L-BFGS and the differences.
struct Scaled {
  const LogLikelihood& f;
  std::vector<double> scale;
  std::size_t evaluations = 0;
  std::string why;
  double value(const double* u) {
    std::vector<double> theta(scale.size());
    for (std::size_t i = 0; i < scale.size(); ++i) theta[i] = u[i] * scale[i];
    ++evaluations;
    return f(theta, why);
  }
};

std::string result_words(nlopt_result result) {
  switch (result) {
    case NLOPT_SUCCESS: return "converged";
    case NLOPT_STOPVAL_REACHED: return "converged (stop value)";
    case NLOPT_FTOL_REACHED: return "converged (relative change of the log-likelihood below 1e-12)";
    case NLOPT_XTOL_REACHED: return "converged (relative change of the parameters below 1e-9)";
    case NLOPT_MAXEVAL_REACHED: return "stopped at the evaluation limit without converging";
    case NLOPT_MAXTIME_REACHED: return "stopped at the time limit without converging";
    case NLOPT_ROUNDOFF_LIMITED: return "stopped by rounding errors";
    case NLOPT_FORCED_STOP: return "stopped";
    case NLOPT_OUT_OF_MEMORY: return "out of memory";
    case NLOPT_INVALID_ARGS: return "invalid arguments";
    default: return "failed";
  }
}

struct Run {
  std::vector<double> u;
  double value = -std::numeric_limits<double>::infinity();
  nlopt_result result = NLOPT_FAILURE;
  bool polished = false;  // BOBYQA finished what L-BFGS could not
};

// One L-BFGS search from u0 in the scaled box, over the coordinates `free` (the others held).
Run search(Scaled& scaled, std::vector<double> u0, const std::vector<double>& lower, const std::vector<double>& upper,
           std::size_t max_evaluations, const std::vector<std::size_t>& free) {
  const std::size_t k = free.size();
  std::vector<double> x(k), lo(k), hi(k);
  for (std::size_t i = 0; i < k; ++i) x[i] = u0[free[i]], lo[i] = lower[free[i]], hi[i] = upper[free[i]];
  // The objective over the free coordinates, the others held at u0's.
  struct Sub {
    Scaled* scaled;
    std::vector<double> full;
    const std::vector<std::size_t>* free;
    std::vector<double> lo, hi;
    double value(const double* y) {
      for (std::size_t i = 0; i < free->size(); ++i) full[(*free)[i]] = y[i];
      return scaled->value(full.data());
    }
  } sub{&scaled, u0, &free, lo, hi};
  auto sub_objective = [](unsigned n, const double* y, double* gradient, void* data) -> double {
    Sub& s = *static_cast<Sub*>(data);
    const double f = s.value(y);
    if (!std::isfinite(f)) {
      if (gradient) std::fill(gradient, gradient + n, 0.0);
      return -1e300;
    }
    if (gradient) {
      std::vector<double> z(y, y + n);
      for (unsigned i = 0; i < n; ++i) {
        const double h = 1e-6 * std::max(1.0, std::abs(y[i]));
        const double up = std::min(y[i] + h, s.hi[i]), down = std::max(y[i] - h, s.lo[i]);
        z[i] = up;
        const double fu = s.value(z.data());
        z[i] = down;
        const double fd = s.value(z.data());
        z[i] = y[i];
        gradient[i] = std::isfinite(fu) && std::isfinite(fd) && up > down ? (fu - fd) / (up - down) : 0.0;
      }
    }
    return f;
  };
  Run run;
  if (k == 0) {
    run.u = u0;
    run.value = scaled.value(u0.data());
    run.result = NLOPT_SUCCESS;
    return run;
  }
  // Either algorithm within the box, maximising, to the same tolerances.
  auto optimiser = [&](nlopt_algorithm algorithm) {
    nlopt_opt opt = nlopt_create(algorithm, static_cast<unsigned>(k));
    nlopt_set_lower_bounds(opt, lo.data());
    nlopt_set_upper_bounds(opt, hi.data());
    nlopt_set_max_objective(opt, sub_objective, &sub);
    nlopt_set_ftol_rel(opt, 1e-12);
    nlopt_set_xtol_rel(opt, 1e-9);
    return opt;
  };
  nlopt_opt opt = optimiser(NLOPT_LD_LBFGS);
  // Each evaluation of the objective with its gradient costs 1 + 2k log-likelihoods.
  nlopt_set_maxeval(opt, static_cast<int>(std::max<std::size_t>(1, max_evaluations / (1 + 2 * k))));
  double value = 0;
  run.result = nlopt_optimize(opt, x.data(), &value);
  nlopt_destroy(opt);
  // L-BFGS's line search can fail near the maximum, where the differences' rounding makes the
  // gradient disagree with the function (NLopt's generic failure, or rounding-limited). Then
  // BOBYQA, which needs no gradient, polishes from where it stopped; its own convergence decides.
  if (run.result == NLOPT_FAILURE || run.result == NLOPT_ROUNDOFF_LIMITED) {
    nlopt_opt polish = optimiser(NLOPT_LN_BOBYQA);
    std::vector<double> step(k);
    for (std::size_t i = 0; i < k; ++i)
      step[i] = std::max(1e-12, std::min(1e-3 * std::max(1.0, std::abs(x[i])), 0.5 * (hi[i] - lo[i])));
    nlopt_set_initial_step(polish, step.data());
    nlopt_set_maxeval(polish, static_cast<int>(std::max<std::size_t>(1, max_evaluations)));
    run.result = nlopt_optimize(polish, x.data(), &value);
    nlopt_destroy(polish);
    run.polished = true;
  }
  run.u = u0;
  for (std::size_t i = 0; i < k; ++i) run.u[free[i]] = x[i];
  run.value = scaled.value(run.u.data());
  return run;
}

}  // namespace

FitResult maximise_likelihood(const FitProblem& problem, const LogLikelihood& log_likelihood) {
  const std::size_t k = problem.names.size();
  Scaled scaled{log_likelihood, std::vector<double>(k), 0, ""};
  std::vector<double> lower(k), upper(k), u0(k);
  for (std::size_t i = 0; i < k; ++i) {
    scaled.scale[i] = problem.start[i] != 0 ? std::abs(problem.start[i]) : 1.0;
    lower[i] = problem.lower[i] / scaled.scale[i];
    upper[i] = problem.upper[i] / scaled.scale[i];
    u0[i] = problem.start[i] / scaled.scale[i];
  }
  if (!std::isfinite(scaled.value(u0.data())))
    throw CliValueError("the log-likelihood is not finite at the start: " + scaled.why);

  std::vector<std::size_t> all(k);
  for (std::size_t i = 0; i < k; ++i) all[i] = i;
  // Further starts uniform in the bounds, from a seeded generator read bit by bit (the same on
  // every platform: std::uniform_real_distribution is not).
  std::mt19937_64 generator(problem.seed);
  FitResult out;
  Run best;
  for (std::size_t s = 0; s < std::max<std::size_t>(1, problem.starts); ++s) {
    std::vector<double> start = u0;
    if (s > 0)
      for (std::size_t i = 0; i < k; ++i) {
        const double unit = static_cast<double>(generator() >> 11) * 0x1.0p-53;
        start[i] = lower[i] + unit * (upper[i] - lower[i]);
      }
    Run run = search(scaled, start, lower, upper, problem.max_evaluations, all);
    if (s == 0 || run.value > best.value) {
      best = run;
      out.best_start = s;
    }
  }
  out.log_likelihood = best.value;
  out.stop_reason = result_words(best.result) + (best.polished ? " (by BOBYQA after L-BFGS's line search failed)" : "");
  out.converged = best.result >= NLOPT_SUCCESS && best.result <= NLOPT_XTOL_REACHED && std::isfinite(best.value);

  // The observed information -H in u, by central differences (step 1e-4 of each scaled value).
  Eigen::MatrixXd H(k, k);
  std::vector<double> h(k);
  for (std::size_t i = 0; i < k; ++i) h[i] = 1e-4 * std::max(1.0, std::abs(best.u[i]));
  std::string edge;  // the first neighbour where the filter fails, and why
  auto f_at = [&](std::size_t i, double di, std::size_t j, double dj) {
    std::vector<double> x = best.u;
    x[i] += di;
    x[j] += dj;
    const double value = scaled.value(x.data());
    if (std::isfinite(value) || !edge.empty()) return value;
    // A neighbour beyond a bound is the bound's business (at_bound), not an edge of the filter's.
    bool within = true;
    for (std::size_t q = 0; q < k; ++q) within = within && x[q] >= lower[q] && x[q] <= upper[q];
    if (within) {
      for (std::size_t q = 0; q < k; ++q) {
        char value_text[32];
        std::snprintf(value_text, sizeof value_text, "%.6g", x[q] * scaled.scale[q]);
        edge += (q ? ", " : "") + problem.names[q] + " = " + value_text;
      }
      edge += " (" + scaled.why + ")";
    }
    return value;
  };
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i; j < k; ++j) {
      if (i == j)
        H(i, i) = (f_at(i, h[i], i, 0) - 2 * best.value + f_at(i, -h[i], i, 0)) / (h[i] * h[i]);
      else
        H(i, j) = H(j, i) = (f_at(i, h[i], j, h[j]) - f_at(i, h[i], j, -h[j]) - f_at(i, -h[i], j, h[j]) +
                             f_at(i, -h[i], j, -h[j])) /
                            (4 * h[i] * h[j]);
    }
  const Eigen::MatrixXd information = -H;
  Eigen::LLT<Eigen::MatrixXd> llt(information);
  out.at_edge = !edge.empty();
  const bool has_errors = !out.at_edge && information.allFinite() && llt.info() == Eigen::Success;
  Eigen::MatrixXd covariance;
  if (has_errors)
    covariance = llt.solve(Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)));
  else if (out.at_edge)
    out.information_note = "the estimate is at the edge of where the filter runs, not at a maximum: the log-likelihood "
                           "cannot be evaluated next to it, at " + edge + "; no standard errors";
  else
    out.information_note = "the observed information is not positive definite at the estimate: no standard errors";
  for (std::size_t i = 0; i < k; ++i) {
    FittedParameter p;
    p.name = problem.names[i];
    p.estimate = best.u[i] * scaled.scale[i];
    p.at_bound = best.u[i] <= lower[i] || best.u[i] >= upper[i];
    p.std_error = has_errors ? std::sqrt(covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i))) *
                                   scaled.scale[i]
                             : kNaN;
    p.wald_low = p.estimate - kZ95 * p.std_error;
    p.wald_high = p.estimate + kZ95 * p.std_error;
    p.profile_low = p.profile_high = kNaN;
    out.parameters.push_back(p);
  }
  out.evaluations = scaled.evaluations;
  if (!problem.profile || !out.converged) return out;

  // Profile intervals: where 2 (l_max - l_p(theta_i)) = chi2_{0.95}(1), l_p maximised over the
  // others, found on each side by stepping out (from the Wald half-width, or 10 % of the estimate)
  // and then bisecting.
  for (std::size_t i = 0; i < k; ++i) {
    std::vector<std::size_t> others;
    for (std::size_t j = 0; j < k; ++j)
      if (j != i) others.push_back(j);
    // > 0 beyond the interval's end; NaN where the filter fails (no likelihood, so not inside).
    // The others start at the estimate's values; where the filter fails there (an estimate at the
    // edge of where it runs), at the last inside point's, then at each other moved by a factor, so
    // that a value is only called failing where no start tried runs.
    std::vector<double> last_inside = best.u;
    auto deficit = [&](double ui) {
      std::vector<double> x = best.u;
      x[i] = ui;
      Run run = search(scaled, x, lower, upper, problem.max_evaluations, others);
      if (!std::isfinite(run.value)) {
        std::vector<std::vector<double>> starts{last_inside};
        for (std::size_t j : others)
          for (double factor : {1.1, 0.9, 1.5, 0.5, 2.0}) {
            std::vector<double> moved = best.u;
            moved[j] = std::clamp(moved[j] * factor, lower[j], upper[j]);
            starts.push_back(moved);
          }
        for (std::vector<double>& start : starts) {
          start[i] = ui;
          if (!std::isfinite(scaled.value(start.data()))) continue;
          run = search(scaled, start, lower, upper, problem.max_evaluations, others);
          if (std::isfinite(run.value)) break;
        }
      }
      if (!std::isfinite(run.value)) return kNaN;
      const double d = best.value - run.value - kChi95Half;
      if (d <= 0) last_inside = run.u;
      return d;
    };
    const double width = std::isfinite(out.parameters[i].std_error) ? out.parameters[i].std_error / scaled.scale[i]
                                                                      : 0.1 * std::max(1.0, std::abs(best.u[i]));
    for (int side : {-1, 1}) {
      double inside = best.u[i], outside = best.u[i];
      bool found = false, fails = false;  // fails: `outside` is a value where the filter fails
      double step = width;
      for (int tries = 0; tries < 30; ++tries) {
        outside = std::clamp(best.u[i] + side * step, lower[i], upper[i]);
        // A moment filter's likelihood can fail between two values where it runs: a step must not
        // pass over such a hole, so points between the last inside value and this one are probed
        // first, nearest first (where the filter cannot stop, nothing is probed, as before). A hole
        // found is the step's outside value, its deficit NaN already.
        double d = kNaN;
        bool hole = false;
        if (problem.filter_can_stop) {
          for (double fraction : {1.0 / 16, 1.0 / 8, 1.0 / 4, 1.0 / 2}) {
            const double between = inside + fraction * (outside - inside);
            if (std::isnan(deficit(between))) {
              outside = between;
              hole = true;
              break;
            }
          }
        }
        if (!hole) d = deficit(outside);
        if (!(d <= 0)) {
          found = true;
          fails = std::isnan(d);
          break;
        }
        inside = outside;
        if (outside == lower[i] || outside == upper[i]) break;
        step *= 2;
      }
      if (!found) {  // the interval reaches the bound (NaN when that is infinite)
        const double bound = (side < 0 ? lower[i] : upper[i]) * scaled.scale[i];
        if (std::isfinite(bound)) {
          (side < 0 ? out.parameters[i].profile_low : out.parameters[i].profile_high) = bound;
          (side < 0 ? out.parameters[i].profile_low_is_bound : out.parameters[i].profile_high_is_bound) = true;
        }
        continue;
      }
      // Bisect to the crossing of the chi-square level or to the edge of where the filter runs,
      // whichever the last value beyond the end is.
      for (int b = 0; b < 40; ++b) {
        const double mid = 0.5 * (inside + outside);
        const double d = deficit(mid);
        if (d <= 0) {
          inside = mid;
        } else {
          outside = mid;
          fails = std::isnan(d);
        }
      }
      (side < 0 ? out.parameters[i].profile_low : out.parameters[i].profile_high) =
          (fails ? inside : 0.5 * (inside + outside)) * scaled.scale[i];
      (side < 0 ? out.parameters[i].profile_low_is_edge : out.parameters[i].profile_high_is_edge) = fails;
    }
  }
  out.evaluations = scaled.evaluations;
  return out;
}

}  // namespace pfgen::cli
