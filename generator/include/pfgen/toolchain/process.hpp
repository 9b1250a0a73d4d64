#pragma once
// Runs an external program (the C++ compiler) without a shell, through the support library's
// run_program (pfgen_support/process.hpp): argv goes to the program as given, so no quoting or
// injection issues, and a missing program is an error of its own. Here its errors are
// ToolchainErrors, the toolchain's one exception type.
#include <stdexcept>
#include <string>
#include <vector>

#include "pfgen_support/error.hpp"
#include "pfgen_support/process.hpp"

namespace pfgen::toolchain {

class ToolchainError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

using pfgen_support::command_line;  // argv joined with spaces, for messages and logs
using pfgen_support::ProcessResult;

// pfgen_support::run_program(argv) (stdin from /dev/null, stdout and stderr interleaved in
// `output`). Throws ToolchainError when the program cannot be started at all (not found, not
// executable), with the support library's message.
ProcessResult run_program(const std::vector<std::string>& argv);

}  // namespace pfgen::toolchain
