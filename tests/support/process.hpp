#pragma once
// Runs a command line through the shell and captures stdout, stderr and the exit code.
#include <string>

namespace pfgen_test {

struct ProcessResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

ProcessResult run_process(const std::string& command_line);

// Quotes one argument for /bin/sh.
std::string shell_quote(const std::string& argument);

}  // namespace pfgen_test
