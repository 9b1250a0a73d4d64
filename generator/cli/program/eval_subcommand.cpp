// pfgen eval's command line.
#include <memory>

#include "commands.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {

Subcommand add_eval_subcommand(CLI::App& app, const OptionChecks&) {
  auto eval = std::make_shared<EvalOptions>();
  CLI::App* eval_cmd = app.add_subcommand("eval", "Evaluate a filter's m drift, gain and P drift at one point (JSON)");
  eval_cmd->add_option("MODEL", eval->model_path, "Model file (YAML)")->required();
  eval_cmd->add_option("--filter", eval->filter, one_filter_help())->required();
  eval_cmd->add_option("--t", eval->t, "Time")->capture_default_str();
  eval_cmd->add_option("--m", eval->m, "Estimate, comma-separated: --m=-1.5,2")->required();
  eval_cmd->add_option("--P", eval->P, "Covariance, rows separated by ';': --P '1,0;0,1'")->required();
  eval_cmd->add_option("--set", eval->assignments, "Parameter value, name=value (repeatable)");
  // Delayed observations: what the filter's history holds at t (docs/theory.md §2.6).
  eval_cmd->add_option("--m-delayed", eval->m_delayed,
                       "Delayed filters: the estimate m(t-h) the innovation uses (default: --m)");
  eval_cmd->add_option("--x-star", eval->x_star, "delay-optimal: the noise-free solution x*(t) (default: --m)");
  eval_cmd->add_option("--x-star-delayed", eval->x_star_delayed,
                       "delay-optimal: x*(t-h) (default: --x-star); phi_i = x*_i(t-h)/x*_i(t) for t >= h, "
                       "0 where x*_i(t) = 0, 0 for t < h (1 when h = 0)");
  eval_cmd->add_option("--phi", eval->phi,
                       "delay-optimal: the diagonal of Phi* itself, used as given (instead of --x-star-delayed)");
  eval_cmd->add_option("--moment", eval->moments,
                       "Moment filters (closure3, closure4): a central moment above P, NAME=VALUE (repeatable), e.g. "
                       "--moment M3_111=0.2; one not given takes its value under N(m, P)");
  return {eval_cmd, [eval] { return run_eval(*eval); }};
}

}  // namespace pfgen::cli
