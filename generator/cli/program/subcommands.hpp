#pragma once
// The pfgen program's subcommands: each declares its CLI11 options on the program's App and
// returns how to run itself once the command line is parsed (main.cpp runs the one given).
// The commands themselves are the library's (commands.hpp, simulate_command.hpp, ...); this is
// only their command line.
#include <functional>

#include <CLI/CLI.hpp>

namespace pfgen::cli {

struct Subcommand {
  CLI::App* command;         // parsed when the user named it
  std::function<int()> run;  // the command with the parsed options; its exit status
};

// The checks several subcommands' options share (option_checks.cpp).
struct OptionChecks {
  OptionChecks();
  CLI::Validator double_number;  // a finite double, checked on the text before CLI11 converts it
  CLI::Validator whole_number;   // plain digits that fit in 64 bits
  CLI::Validator named_file;     // a file name that is not empty
  CLI::Validator named_filters;  // a filter list that is not empty
};

// --filter's text where one filter is named: the built-in kinds, then the model's own.
std::string one_filter_help();

// In the order `pfgen --help` lists them.
Subcommand add_derive_subcommand(CLI::App& app, const OptionChecks& checks);
Subcommand add_latex_subcommand(CLI::App& app, const OptionChecks& checks);
Subcommand add_eval_subcommand(CLI::App& app, const OptionChecks& checks);
Subcommand add_codegen_subcommand(CLI::App& app, const OptionChecks& checks);
// argc and argv: an MPI job's ranks (built with PFGEN_WITH_MPI) start from the whole command line.
Subcommand add_simulate_subcommand(CLI::App& app, const OptionChecks& checks, int argc, char** argv);
Subcommand add_estimate_subcommand(CLI::App& app, const OptionChecks& checks);
Subcommand add_fit_subcommand(CLI::App& app, const OptionChecks& checks);

}  // namespace pfgen::cli
