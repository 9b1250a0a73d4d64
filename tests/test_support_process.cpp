// Running programs (pfgen_support/process.hpp): argv verbatim without a shell, output captured
// (interleaved or apart) without deadlock however much is written, exit status and signal, and
// no descriptor of ours leaking into the child.
#include <catch2/catch.hpp>

#include <cerrno>
#include <csignal>
#include <set>
#include <sstream>
#include <string>

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include "pfgen_support/process.hpp"

using pfgen_support::ProcessError;
using pfgen_support::ProcessOptions;
using pfgen_support::ProcessResult;
using pfgen_support::run_program;

namespace {

ProcessResult shell(const std::string& script, bool separate_errors = false) {
  ProcessOptions options;
  options.separate_errors = separate_errors;
  return run_program({"/bin/sh", "-c", script}, options);
}

// This process's descriptors from 3 up that a child would inherit (not close-on-exec).
std::set<int> inheritable_descriptors() {
  std::set<int> fds;
  DIR* dir = ::opendir("/proc/self/fd");
  REQUIRE(dir != nullptr);
  const int own = ::dirfd(dir);
  while (const dirent* entry = ::readdir(dir)) {
    if (entry->d_name[0] == '.') continue;
    const int fd = std::stoi(entry->d_name);
    if (fd < 3 || fd == own) continue;
    const int flags = ::fcntl(fd, F_GETFD);
    if (flags >= 0 && !(flags & FD_CLOEXEC)) fds.insert(fd);
  }
  ::closedir(dir);
  return fds;
}

}  // namespace

TEST_CASE("support: run_program passes argv verbatim, with no shell", "[integration][support]") {
  const ProcessResult r = run_program({"printf", "%s|", "a b", "'q'", "$HOME", "*", ""});
  CHECK(r.exit_status == 0);
  CHECK(r.signal == 0);
  CHECK(r.succeeded());
  CHECK(r.output == "a b|'q'|$HOME|*||");
  CHECK(r.errors.empty());
}

TEST_CASE("support: run_program captures stdout and stderr, together or apart, and the exit status",
          "[integration][support]") {
  const ProcessResult together = shell("printf out1; printf err >&2; printf out2; exit 3");
  CHECK(together.exit_status == 3);
  CHECK_FALSE(together.succeeded());
  CHECK(together.output == "out1errout2");  // unbuffered printf: in the order written
  CHECK(together.errors.empty());

  const ProcessResult apart = shell("printf out1; printf err >&2; printf out2", true);
  CHECK(apart.exit_status == 0);
  CHECK(apart.output == "out1out2");
  CHECK(apart.errors == "err");

  // stdin is /dev/null: a program that reads it ends at once.
  CHECK(run_program({"cat"}).output.empty());
}

TEST_CASE("support: run_program reads both pipes at once, so no amount of output blocks", "[integration][support]") {
  // More than a pipe holds (64 KiB on Linux) on the stream written first: reading one stream to
  // its end before the other would wait forever.
  const std::string big = "head -c 300000 /dev/zero | tr '\\0' ";
  const ProcessResult err_first = shell(big + "e >&2; " + big + "o", true);
  CHECK(err_first.output == std::string(300000, 'o'));
  CHECK(err_first.errors == std::string(300000, 'e'));
  const ProcessResult out_first = shell(big + "o; " + big + "e >&2", true);
  CHECK(out_first.output == std::string(300000, 'o'));
  CHECK(out_first.errors == std::string(300000, 'e'));
}

TEST_CASE("support: run_program reports a signal and a program it cannot start", "[integration][support]") {
  const ProcessResult killed = shell("kill -TERM $$");
  CHECK(killed.exit_status == -1);
  CHECK(killed.signal == SIGTERM);
  CHECK_FALSE(killed.succeeded());

  try {
    run_program({"pfgen-no-such-program", "x"});
    FAIL("a missing program ran");
  } catch (const ProcessError& e) {
    CHECK(e.stage() == ProcessError::Stage::spawn);
    CHECK(e.error_number() == ENOENT);
    CHECK(std::string(e.what()) == "cannot run `pfgen-no-such-program`: No such file or directory");
  }
  CHECK_THROWS_AS(run_program({}), std::invalid_argument);
  CHECK_THROWS_AS(run_program({""}), std::invalid_argument);
  CHECK(pfgen_support::command_line({"c++", "-O2", "a b.cpp"}) == "c++ -O2 a b.cpp");
}

TEST_CASE("support: the child inherits none of run_program's descriptors", "[integration][support]") {
  // The child lists its descriptors from 3 up; the only ones allowed are those this process
  // itself leaves inheritable (none, normally). run_program's pipes are close-on-exec, so they
  // never appear, and the child's stdout and stderr are its only way back.
  const std::set<int> allowed = inheritable_descriptors();
  // find lists the shell's descriptors from outside it; "; true" keeps the shell from exec()ing
  // find, which would then list its own directory handle.
  const ProcessResult r = shell("find /proc/$$/fd -mindepth 1 -printf '%f %l\\n'; true", true);
  REQUIRE(r.exit_status == 0);
  std::istringstream lines(r.output);
  int fd = 0;
  std::string target;
  std::set<int> seen;
  while (lines >> fd && std::getline(lines, target)) {
    seen.insert(fd);
    INFO("child descriptor " << fd << " ->" << target);
    if (fd == 0) CHECK(target == " /dev/null");
    if (fd >= 3) CHECK(allowed.count(fd) == 1);
  }
  CHECK(seen.count(0) == 1);
  CHECK(seen.count(1) == 1);
  CHECK(seen.count(2) == 1);
}
