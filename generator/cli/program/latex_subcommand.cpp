// pfgen latex's command line.
#include <memory>

#include "commands.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {

Subcommand add_latex_subcommand(CLI::App& app, const OptionChecks& checks) {
  auto latex = std::make_shared<LatexOptions>();
  CLI::App* latex_cmd = app.add_subcommand("latex", "Write a standalone LaTeX document of the model and its filters");
  latex_cmd->add_option("MODEL", latex->model_path, "Model file (YAML)")->required();
  latex_cmd->add_option("-o,--output", latex->output_path, "Output .tex file")->required()->check(checks.named_file);
  latex_cmd->add_option("--filter", latex->filters, "Comma-separated filters: built-in kinds or the model's own (default: every kind the model supports except the opt-in ukf, then its own)")
      ->check(checks.named_filters);
  latex_cmd->add_flag("--coefficients", latex->coefficients,
                      "Add a section with the model's coefficient form A..A3, E, E1 (drift of degree <= 3)");
  return {latex_cmd, [latex] { return run_latex(*latex); }};
}

}  // namespace pfgen::cli
