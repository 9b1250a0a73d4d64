#pragma once
// Runs a program for a test and captures stdout, stderr and the exit code, through the one
// spawning code (pfgen_support::run_program).
#include <string>
#include <vector>

namespace pfgen_test {

struct ProcessResult {
  int exit_code = -1;  // -1 when a signal ended the program
  std::string out;
  std::string err;
};

// argv as given, no shell.
ProcessResult run_program(const std::vector<std::string>& argv);

// A command line through /bin/sh -c, for tests that need the shell ("cd DIR && ...",
// "command -v NAME").
ProcessResult run_process(const std::string& command_line);

// Quotes one argument for /bin/sh.
std::string shell_quote(const std::string& argument);

}  // namespace pfgen_test
