#include "support/process.hpp"

#include "pfgen_support/process.hpp"

namespace pfgen_test {

std::string shell_quote(const std::string& argument) {
  std::string out = "'";
  for (char c : argument) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

ProcessResult run_program(const std::vector<std::string>& argv) {
  pfgen_support::ProcessOptions options;
  options.separate_errors = true;
  const pfgen_support::ProcessResult ran = pfgen_support::run_program(argv, options);
  return ProcessResult{ran.exit_status, ran.output, ran.errors};
}

ProcessResult run_process(const std::string& command_line) { return run_program({"/bin/sh", "-c", command_line}); }

}  // namespace pfgen_test
