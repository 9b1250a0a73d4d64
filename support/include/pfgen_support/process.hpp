#pragma once
// Runs a program without a shell: argv goes to it as given (no quoting, no injection), argv[0]
// is looked up in PATH when it has no '/', stdin is /dev/null, and the call waits for the
// program to end, collecting what it writes. Every descriptor opened here is close-on-exec, so
// a program started at the same time by another thread never inherits one of our pipes (our
// read would otherwise wait for that program to end too).
#include <stdexcept>
#include <string>
#include <vector>

#include "pfgen_support/error.hpp"

namespace pfgen_support {

class ProcessError : public Error {
 public:
  enum class Stage { pipe, spawn, wait };  // creating a pipe, starting the program, waiting for it
  ProcessError(Stage stage, const std::string& program, int error_number);
  Stage stage() const { return stage_; }
  int error_number() const { return error_number_; }  // errno (or posix_spawn's error) of the failed call

 private:
  Stage stage_;
  int error_number_;
};

struct ProcessOptions {
  // false: stderr goes into ProcessResult::output, interleaved with stdout as written;
  // true: it goes into ProcessResult::errors.
  bool separate_errors = false;
};

struct ProcessResult {
  int exit_status = -1;  // the exit code, or -1 when a signal ended the program
  int signal = 0;        // the signal that ended it, or 0
  std::string output;    // stdout (and stderr unless ProcessOptions::separate_errors)
  std::string errors;    // stderr with ProcessOptions::separate_errors
  bool succeeded() const { return exit_status == 0; }
};

// Throws std::invalid_argument for an empty argv or program name, and ProcessError when the
// program cannot be started (glibc reports a program that is not found or not executable here;
// other C libraries through exit status 127) or waited for. Messages:
// "cannot create a pipe: <reason>", "cannot run `<argv[0]>`: <reason>",
// "cannot wait for `<argv[0]>`: <reason>".
ProcessResult run_program(const std::vector<std::string>& argv, const ProcessOptions& options = {});

// argv joined with spaces, for messages and logs.
std::string command_line(const std::vector<std::string>& argv);

}  // namespace pfgen_support
