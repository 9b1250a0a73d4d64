#include "pfgen/toolchain/process.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pfgen::toolchain {
namespace {

std::string system_error(const std::string& what, int error) { return what + ": " + std::strerror(error); }

// Closes its descriptors however the function leaves.
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

}  // namespace

std::string command_line(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) out += (out.empty() ? "" : " ") + a;
  return out;
}

ProcessResult run_program(const std::vector<std::string>& argv) {
  if (argv.empty() || argv[0].empty()) throw ToolchainError("no program to run");
  // O_CLOEXEC: a program started concurrently by another thread must not inherit the pipe,
  // or our read would wait for it to end too.
  Pipe pipe;
  if (::pipe2(pipe.fd, O_CLOEXEC) != 0) throw ToolchainError(system_error("cannot create a pipe", errno));
  SpawnActions spawn;
  posix_spawn_file_actions_addopen(&spawn.actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&spawn.actions, pipe.fd[1], 1);
  posix_spawn_file_actions_adddup2(&spawn.actions, pipe.fd[1], 2);

  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, args[0], &spawn.actions, nullptr, args.data(), environ);
  if (error != 0) throw ToolchainError(system_error("cannot run `" + argv[0] + "`", error));
  pipe.close(1);

  ProcessResult result;
  char buffer[4096];
  while (true) {
    const ssize_t got = ::read(pipe.fd[0], buffer, sizeof buffer);
    if (got > 0) {
      result.output.append(buffer, static_cast<std::size_t>(got));
    } else if (got == 0 || errno != EINTR) {
      break;
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw ToolchainError(system_error("cannot wait for `" + argv[0] + "`", errno));
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  // glibc's posix_spawnp reports a failed exec through its return value, other C libraries
  // through exit status 127 of the child.
  return result;
}

}  // namespace pfgen::toolchain
