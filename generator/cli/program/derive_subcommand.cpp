// pfgen derive's command line.
#include <memory>

#include "commands.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {

Subcommand add_derive_subcommand(CLI::App& app, const OptionChecks& checks) {
  auto derive = std::make_shared<DeriveOptions>();
  CLI::App* derive_cmd = app.add_subcommand("derive", "Print the closed filter equations of a model");
  derive_cmd->add_option("MODEL", derive->model_path, "Model file (YAML)")->required();
  derive_cmd->add_option("--filter", derive->filter,
                         one_filter_help() + " (default: the model's first, optimal for continuous observations)")
      ->check(checks.named_filters);
  derive_cmd->add_option("--format", derive->format, "text | latex | json")
      ->check(CLI::IsMember({"text", "latex", "json"}))
      ->capture_default_str();
  derive_cmd->add_flag("--coefficients", derive->coefficients,
                       "Print the model's coefficient form instead of a filter: f = A + A1 x + A2 x x + A3 x x x, "
                       "observation rate E + E1 x (drift of degree <= 3)");
  derive_cmd->add_option("--timing", derive->timing_path,
                         "Write the seconds spent reading the model, deriving and printing as JSON to FILE")
      ->check(checks.named_file);
  return {derive_cmd, [derive] { return run_derive(*derive); }};
}

}  // namespace pfgen::cli
