// With PFGEN_HUGE_PAGES=1, pfgen executes itself once with glibc's transparent-huge-page tunable
// (cli/program/huge_page_heap.hpp). What a user can rely on: the output does not change by a byte,
// nothing happens without the opt-in, a user's own GLIBC_TUNABLES are kept, and where the machine
// can give huge pages the tunable reaches the process (seen through the environment pfgen hands to
// the plugin compiler).
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include <gnu/libc-version.h>
#include <sys/stat.h>

#include "support/cli_helpers.hpp"
#include "support/test_paths.hpp"

using namespace pfgen_test;

namespace {

bool machine_gives_huge_pages_when_asked() {
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2) return false;
  if (major < 2 || (major == 2 && minor < 35)) return false;
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(mode, line) && line.find("[madvise]") != std::string::npos;
}

// The environment pfgen runs in, as seen by a "compiler" that writes it to a file and fails.
std::string environment_seen_by_compiler(const TempDir& dir, const std::string& env_prefix) {
  const std::string compiler = dir.file("print-env-cxx");
  const std::string seen = dir.file("env.txt");
  write_file(compiler, "#!/bin/sh\nenv > " + shell_quote(seen) + "\nexit 1\n");
  chmod(compiler.c_str(), 0755);
  std::remove(seen.c_str());
  const std::string command = "env -u GLIBC_TUNABLES -u PFGEN_HUGE_PAGES " + env_prefix + " " +
                              shell_quote(pfgen_executable()) + " simulate " +
                              shell_quote(example("basin2006_quadratic.yaml")) + " --runs 1 --compiler " +
                              shell_quote(compiler) + " --cache-dir " + shell_quote(dir.file("cache"));
  ProcessResult r = run_process(command);
  INFO(r.err);
  CHECK(r.exit_code != 0);  // the "compiler" fails on purpose
  return read_file(seen);
}

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

}  // namespace

TEST_CASE("huge page heap: opt-in, output identical with and without it, and a user's tunables kept", "[integration]") {
  const std::string derive = shell_quote(pfgen_executable()) + " derive " +
                             shell_quote(example("basin2006_quadratic.yaml")) + " --format json";
  ProcessResult plain = run_process("env -u GLIBC_TUNABLES -u PFGEN_HUGE_PAGES " + derive);
  ProcessResult opted_in = run_process("env -u GLIBC_TUNABLES PFGEN_HUGE_PAGES=1 " + derive);
  ProcessResult with_user_tunable =
      run_process("env GLIBC_TUNABLES=glibc.malloc.perturb=0 PFGEN_HUGE_PAGES=1 " + derive);
  REQUIRE(plain.exit_code == 0);
  REQUIRE(opted_in.exit_code == 0);
  REQUIRE(with_user_tunable.exit_code == 0);
  CHECK(plain.out == opted_in.out);
  CHECK(plain.out == with_user_tunable.out);
  CHECK(opted_in.err.empty());

  TempDir dir;
  // Without the opt-in (or with any other value) the heap is left as it is.
  for (const std::string& prefix : {std::string("PFGEN_HUGE_PAGES=0"), std::string("PFGEN_HUGE_PAGES=yes")}) {
    const std::string seen = environment_seen_by_compiler(dir, prefix);
    REQUIRE(has_line(seen, prefix));  // the script ran
    CHECK(seen.find("GLIBC_TUNABLES") == std::string::npos);
  }
  CHECK(environment_seen_by_compiler(dir, "").find("GLIBC_TUNABLES") == std::string::npos);
  if (!machine_gives_huge_pages_when_asked()) {
    WARN("this machine's glibc or kernel gives no huge pages on request: the tunable is not set");
    CHECK(environment_seen_by_compiler(dir, "PFGEN_HUGE_PAGES=1").find("GLIBC_TUNABLES") == std::string::npos);
    return;
  }
  CHECK(has_line(environment_seen_by_compiler(dir, "PFGEN_HUGE_PAGES=1"), "GLIBC_TUNABLES=glibc.malloc.hugetlb=1"));
  CHECK(has_line(environment_seen_by_compiler(dir, "PFGEN_HUGE_PAGES=1 GLIBC_TUNABLES=glibc.malloc.perturb=0"),
                 "GLIBC_TUNABLES=glibc.malloc.perturb=0:glibc.malloc.hugetlb=1"));
  // A user who sets the tunable (to 0, say) decides: pfgen neither adds it again nor executes twice.
  CHECK(has_line(environment_seen_by_compiler(dir, "PFGEN_HUGE_PAGES=1 GLIBC_TUNABLES=glibc.malloc.hugetlb=0"),
                 "GLIBC_TUNABLES=glibc.malloc.hugetlb=0"));
}
