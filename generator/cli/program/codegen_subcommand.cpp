// pfgen codegen's command line.
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "pfgen/codegen/backend.hpp"
#include "subcommands.hpp"

namespace pfgen::cli {

Subcommand add_codegen_subcommand(CLI::App& app, const OptionChecks& checks) {
  auto codegen = std::make_shared<CodegenCliOptions>();
  CLI::App* codegen_cmd = app.add_subcommand("codegen", "Write a model's filters as C++ headers or C99 .h/.c pairs");
  codegen_cmd->add_option("MODEL", codegen->model_path, "Model file (YAML)")->required();
  codegen_cmd->add_option("-o,--output", codegen->output_dir, "Output directory; files go to DIR/<model>/<filter>.hpp (C: .h and .c)")
      ->check(checks.named_file);
  codegen_cmd->add_option("--filter", codegen->filters, "Comma-separated filters: built-in kinds or the model's own (default: every kind the model supports except the opt-in ukf, then its own)")
      ->check(checks.named_filters);
  // --language's names and help from the registry of backends: "cpp | c: header-only C++, or C99 .h/.c pairs".
  std::vector<std::string> language_names;
  std::string language_names_text, language_summaries;
  const auto& backends = pfgen::codegen::backends();
  for (std::size_t k = 0; k < backends.size(); ++k) {
    language_names.push_back(backends[k]->name());
    language_names_text += (k ? " | " : "") + backends[k]->name();
    language_summaries += std::string(k == 0 ? "" : k + 1 < backends.size() ? ", " : ", or ") + backends[k]->summary();
  }
  codegen_cmd->add_option("--language", codegen->language, language_names_text + ": " + language_summaries)
      ->check(CLI::IsMember(language_names))
      ->capture_default_str();
  CLI::Option* scalar_option = codegen_cmd->add_option("--scalar", codegen->scalar, "float | double | template (C: float | double, default double)")
      ->check(CLI::IsMember({"float", "double", "template"}))
      ->capture_default_str();
  codegen_cmd->add_option("--namespace", codegen->name_space, "Outer C++ namespace (C: the names' prefix, :: written _)")
      ->capture_default_str();
  codegen_cmd->add_flag("--stats", codegen->stats, "Print operation counts as JSON, one line per filter kind");
  codegen_cmd->add_flag("--eigen", codegen->eigen,
                        "Also write DIR/<model>/<filter>_eigen.hpp: wrappers taking m and P as Eigen matrices");
  codegen_cmd->add_option("--dt", codegen->dt,
                          "Delayed observations: the grid step of the filters, a divisor of the delay (default: "
                          "simulation.dt)")
      ->check(checks.double_number);
  codegen_cmd->add_flag("--no-cse", codegen->no_cse, "Emit without common-subexpression elimination (benchmark baseline)");
  codegen_cmd->add_option("--max-function-ops", codegen->max_function_ops,
                          "Write a function of more operations (after CSE) in parts of at most this many, each its "
                          "own function, to bound compile time (default 500; 0: never split)")
      ->check(checks.whole_number);
  return {codegen_cmd, [codegen, scalar_option] {
            codegen->scalar_given = scalar_option->count() > 0;
            return run_codegen(*codegen);
          }};
}

}  // namespace pfgen::cli
