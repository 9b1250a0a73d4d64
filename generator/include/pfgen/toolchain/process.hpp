#pragma once
// Runs an external program (the C++ compiler) without a shell: argv goes to the program as
// given, so no quoting or injection issues, and a missing program is an error of its own.
#include <stdexcept>
#include <string>
#include <vector>

namespace pfgen::toolchain {

class ToolchainError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ProcessResult {
  int exit_status = -1;  // the exit code, or -1 when a signal ended the program
  int signal = 0;        // the signal that ended it, or 0
  std::string output;    // stdout and stderr, interleaved as written
  bool succeeded() const { return exit_status == 0; }
};

// Runs argv[0] (looked up in PATH when it has no '/') with stdin from /dev/null and waits for
// it. Throws ToolchainError when it cannot be started at all (not found, not executable).
ProcessResult run_program(const std::vector<std::string>& argv);

// argv joined with spaces, for messages and logs.
std::string command_line(const std::vector<std::string>& argv);

}  // namespace pfgen::toolchain
