#include "pfgen_support/process.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pfgen_support {
namespace {

std::string describe(ProcessError::Stage stage, const std::string& program, int error_number) {
  const std::string reason = std::strerror(error_number);
  switch (stage) {
    case ProcessError::Stage::pipe: return "cannot create a pipe: " + reason;
    case ProcessError::Stage::spawn: return "cannot run `" + program + "`: " + reason;
    case ProcessError::Stage::wait: break;
  }
  return "cannot wait for `" + program + "`: " + reason;
}

// A pipe whose ends are close-on-exec and are closed however the function leaves.
struct Pipe {
  int fd[2] = {-1, -1};
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
  void close(int k) {
    ::close(fd[k]);
    fd[k] = -1;
  }
};

struct SpawnActions {
  posix_spawn_file_actions_t actions;
  SpawnActions() { posix_spawn_file_actions_init(&actions); }
  ~SpawnActions() { posix_spawn_file_actions_destroy(&actions); }
};

// Reads both pipes (or one; fd -1 is skipped) to end of file. Both at once: a program that
// fills the pipe we are not reading would otherwise block, and so would we.
void drain(int out_fd, std::string& out, int err_fd, std::string& err) {
  pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
  std::string* sinks[2] = {&out, &err};
  char buffer[4096];
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const ssize_t got = ::read(fds[k].fd, buffer, sizeof buffer);
      if (got > 0)
        sinks[k]->append(buffer, static_cast<std::size_t>(got));
      else if (got == 0 || errno != EINTR)
        fds[k].fd = -1;  // end of file (or an error: nothing more will come)
    }
  }
}

}  // namespace

ProcessError::ProcessError(Stage stage, const std::string& program, int error_number)
    : Error(describe(stage, program, error_number)), stage_(stage), error_number_(error_number) {}

std::string command_line(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) out += (out.empty() ? "" : " ") + a;
  return out;
}

ProcessResult run_program(const std::vector<std::string>& argv, const ProcessOptions& options) {
  if (argv.empty() || argv[0].empty()) throw std::invalid_argument("no program to run");
  Pipe out, err;
  if (::pipe2(out.fd, O_CLOEXEC) != 0) throw ProcessError(ProcessError::Stage::pipe, argv[0], errno);
  if (options.separate_errors && ::pipe2(err.fd, O_CLOEXEC) != 0)
    throw ProcessError(ProcessError::Stage::pipe, argv[0], errno);
  // The child's dup2() copies are not close-on-exec; the originals close at exec.
  SpawnActions spawn;
  posix_spawn_file_actions_addopen(&spawn.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&spawn.actions, out.fd[1], 1);
  posix_spawn_file_actions_adddup2(&spawn.actions, options.separate_errors ? err.fd[1] : out.fd[1], 2);

  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, args[0], &spawn.actions, nullptr, args.data(), environ);
  if (error != 0) throw ProcessError(ProcessError::Stage::spawn, argv[0], error);
  out.close(1);
  if (options.separate_errors) err.close(1);

  ProcessResult result;
  drain(out.fd[0], result.output, err.fd[0], result.errors);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw ProcessError(ProcessError::Stage::wait, argv[0], errno);
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

}  // namespace pfgen_support
