// pfgen: derive, print and evaluate optimal filters for polynomial stochastic systems.
// main() assembles the subcommands (subcommands.hpp: each declares its options and runs its
// command), parses, and reports every error on one line from its single catch.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "huge_page_heap.hpp"
#include "pfgen_support/error.hpp"
#include "pfgen_support/quoted_text.hpp"
#include "subcommands.hpp"

namespace {

// Every error is reported on exactly one line of stderr.
using pfgen_support::one_line;

// A report that did not reach standard output (`pfgen derive m.yaml > /dev/full`: ENOSPC) is a
// failure, not a success with nothing printed.
void check_standard_output_written() {
  std::cout.flush();
  // errno as the failed write left it (a later successful call does not reset it).
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout))
    throw std::runtime_error(std::string("cannot write standard output: ") +
                             (errno ? std::strerror(errno) : "write error"));
}

// CLI11 reads "--filter=" (nothing after '=') as "--filter" without its value and takes the next
// argument as the value: `eval --filter= --m 0.5` reported "--m is required". A long option
// written with '=' and nothing after it is refused here, named, before CLI11 parses.
void refuse_empty_equals_values(int argc, char** argv) {
  for (int k = 1; k < argc; ++k) {
    const std::string argument = argv[k];
    if (argument == "--") return;  // what follows is positional
    if (argument.size() > 3 && argument.compare(0, 2, "--") == 0 && argument.back() == '=' &&
        argument.find('=') == argument.size() - 1)
      throw std::runtime_error(argument.substr(0, argument.size() - 1) + ": no value after '='");
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pfgen::cli;
  use_huge_page_heap(argv);  // first: it may execute pfgen again (huge_page_heap.hpp)
  CLI::App app{"pfgen " PFGEN_VERSION ": optimal filters for polynomial stochastic systems"};
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "pfgen: error: " + one_line(e.what()) + " (see pfgen --help)\n";
  });
  app.set_version_flag("--version", "pfgen " PFGEN_VERSION);

  const OptionChecks checks;
  const Subcommand subcommands[] = {
      add_derive_subcommand(app, checks),  add_latex_subcommand(app, checks),
      add_eval_subcommand(app, checks),    add_codegen_subcommand(app, checks),
      add_simulate_subcommand(app, checks, argc, argv), add_estimate_subcommand(app, checks),
      add_fit_subcommand(app, checks)};

  try {
    refuse_empty_equals_values(argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with status 0. A parse error exits 1, as every other error
    // does (docs/guide/commands.md), not with CLI11's own codes (105 for a value a check refuses,
    // 106 for a missing option, 109 for an unknown one).
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "pfgen: error: " << one_line(e.what()) << " (see pfgen --help)\n";
    return 1;
  }
  try {
    int status = 1;
    for (const Subcommand& subcommand : subcommands)
      if (*subcommand.command) status = subcommand.run();
    check_standard_output_written();
    return status;
  } catch (const pfgen_support::Error& e) {
    // Every error pfgen reports (pfgen_support/error.hpp) says its one line itself; an empty one
    // means another process of the job failed and said why (FailedElsewhere).
    const std::string line = e.report();
    if (!line.empty()) std::cerr << "pfgen: " << one_line(line) << "\n";
  } catch (const std::exception& e) {
    // Not one of pfgen's: out of memory, or a library's error no room turned into its own.
    std::cerr << "pfgen: error: " << one_line(e.what()) << "\n";
  }
  return 1;
}
