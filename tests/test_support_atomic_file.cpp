// Atomic whole-file writes (pfgen_support/atomic_file.hpp): concurrent writers of one path,
// threads or processes, each use their own temporary, so the file is always one writer's whole
// contents and no temporary is left behind; a failed write leaves the target as it was.
#include <catch2/catch.hpp>

#include <atomic>
#include <cerrno>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pfgen_support/atomic_file.hpp"
#include "support/cli_helpers.hpp"

using pfgen_support::AtomicWriteError;
using pfgen_support::write_file_atomically;
using pfgen_test::read_file;
using pfgen_test::TempDir;

namespace {

// Writer w's k-th contents: a header naming both, then a body of one letter, so that a reader
// can tell a whole file from a torn or mixed one.
std::string contents_of(int writer, int k) {
  const std::string header = std::to_string(writer) + " " + std::to_string(k) + "\n";
  return header + std::string(20000, static_cast<char>('a' + writer));
}

bool is_whole(const std::string& text) {
  const auto newline = text.find('\n');
  if (newline == std::string::npos) return false;
  const int writer = std::stoi(text.substr(0, text.find(' ')));
  const int k = std::stoi(text.substr(text.find(' ') + 1, newline));
  return text == contents_of(writer, k);
}

// Reads `path` until `done`, counting the reads that were not some writer's whole contents.
void watch(const std::string& path, const std::atomic<bool>& done, int& torn, int& reads) {
  while (!done) {
    const std::string text = read_file(path);
    ++reads;
    if (!text.empty() && !is_whole(text)) ++torn;
  }
}

}  // namespace

TEST_CASE("support: write_file_atomically writes and replaces, leaving no temporary", "[unit][support]") {
  TempDir dir;
  const std::string path = dir.file("out.txt");
  write_file_atomically(path, "first\n");
  CHECK(read_file(path) == "first\n");
  write_file_atomically(path, std::string("second\0with a NUL\n", 18));
  CHECK(read_file(path) == std::string("second\0with a NUL\n", 18));
  write_file_atomically(path, "");
  CHECK(read_file(path).empty());
  CHECK(dir.entries() == std::vector<std::string>{"out.txt"});
  // A new file gets the usual permissions (0666 less the umask), not a temporary's 0600.
  const mode_t mask = ::umask(022);
  ::umask(mask);
  struct stat info {};
  REQUIRE(::stat(path.c_str(), &info) == 0);
  CHECK((info.st_mode & 0777) == (0666 & ~mask));
}

TEST_CASE("support: a failed atomic write names the path and leaves nothing behind", "[unit][support]") {
  TempDir dir;
  const std::string missing = dir.file("no-such-dir/out.txt");
  try {
    write_file_atomically(missing, "x");
    FAIL("writing into a missing directory succeeded");
  } catch (const AtomicWriteError& e) {
    CHECK(e.stage() == AtomicWriteError::Stage::write);
    CHECK(e.path() == missing);
    CHECK(e.error_number() == ENOENT);
    CHECK(std::string(e.what()) == "cannot write '" + missing + "': No such file or directory");
  }
  // rename() cannot replace a non-empty directory: the temporary was written and must go.
  const std::string occupied = dir.file("occupied");
  REQUIRE(::mkdir(occupied.c_str(), 0777) == 0);
  pfgen_test::write_file(occupied + "/inside", "keep");
  try {
    write_file_atomically(occupied, "x");
    FAIL("replacing a non-empty directory succeeded");
  } catch (const AtomicWriteError& e) {
    CHECK(e.stage() == AtomicWriteError::Stage::rename);
    CHECK(e.path() == occupied);
    CHECK(e.temporary().rfind(occupied + ".tmp-", 0) == 0);
    CHECK(std::string(e.what()).rfind("cannot write '" + occupied + "': renaming '" + e.temporary() + "' failed: ", 0) == 0);
  }
  CHECK(dir.entries() == std::vector<std::string>{"occupied"});
  CHECK(read_file(occupied + "/inside") == "keep");
}

TEST_CASE("support: temporary names are unique and beside their target", "[unit][support]") {
  std::set<std::string> names;
  for (int k = 0; k < 1000; ++k) {
    const std::string name = pfgen_support::unique_temporary_path("/some/dir/file.csv");
    CHECK(name.rfind("/some/dir/file.csv.tmp-" + std::to_string(::getpid()) + "-", 0) == 0);
    names.insert(name);
  }
  CHECK(names.size() == 1000);
}

TEST_CASE("support: threads writing one path concurrently leave one whole file", "[unit][support]") {
  TempDir dir;
  const std::string path = dir.file("shared.txt");
  const int writers = 4, writes = 150;
  std::atomic<bool> done{false};
  int torn = 0, reads = 0;
  std::thread reader(watch, std::cref(path), std::cref(done), std::ref(torn), std::ref(reads));
  std::vector<std::thread> threads;
  std::atomic<int> failures{0};
  for (int w = 0; w < writers; ++w)
    threads.emplace_back([&, w] {
      for (int k = 0; k < writes; ++k) {
        try {
          write_file_atomically(path, contents_of(w, k));
        } catch (const std::exception&) {
          ++failures;
        }
      }
    });
  for (auto& t : threads) t.join();
  done = true;
  reader.join();
  INFO(reads << " concurrent reads");
  CHECK(failures == 0);
  CHECK(torn == 0);
  CHECK(is_whole(read_file(path)));
  CHECK(dir.entries() == std::vector<std::string>{"shared.txt"});
}

TEST_CASE("support: processes writing one path concurrently leave one whole file", "[integration][support]") {
  TempDir dir;
  const std::string path = dir.file("shared.txt");
  const int writers = 3, writes = 200;
  std::vector<pid_t> children;
  for (int w = 0; w < writers; ++w) {
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {  // the child: write, then leave at once (no Catch2, no destructors)
      int status = 0;
      for (int k = 0; k < writes; ++k) {
        try {
          write_file_atomically(path, contents_of(w, k));
        } catch (...) {
          status = 1;
        }
      }
      ::_exit(status);
    }
    children.push_back(pid);
  }
  std::atomic<bool> done{false};
  int torn = 0, reads = 0;
  std::thread reader(watch, std::cref(path), std::cref(done), std::ref(torn), std::ref(reads));
  int failed = 0;
  for (pid_t pid : children) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failed;
  }
  done = true;
  reader.join();
  INFO(reads << " concurrent reads");
  CHECK(failed == 0);
  CHECK(torn == 0);
  CHECK(is_whole(read_file(path)));
  CHECK(dir.entries() == std::vector<std::string>{"shared.txt"});
}

// What exists at a path and is not a regular file is written into, never replaced: rename()
// over a link to /dev/null replaced the link, and as root over /dev/null itself the device.
TEST_CASE("support: a device, a FIFO or a link to one is written through, never replaced", "[unit][support]") {
  TempDir dir;
  struct stat info {};
  // A link to /dev/null: the write succeeds and the link stays a link to the device.
  const std::string to_null = dir.file("null-link");
  REQUIRE(::symlink("/dev/null", to_null.c_str()) == 0);
  write_file_atomically(to_null, "into the device\n");
  REQUIRE(::lstat(to_null.c_str(), &info) == 0);
  CHECK(S_ISLNK(info.st_mode));
  REQUIRE(::stat("/dev/null", &info) == 0);
  CHECK(S_ISCHR(info.st_mode));
  // A link to /dev/full: ENOSPC is the command's failure, not a success.
  const std::string to_full = dir.file("full-link");
  REQUIRE(::symlink("/dev/full", to_full.c_str()) == 0);
  try {
    write_file_atomically(to_full, "nowhere to go\n");
    FAIL("writing into /dev/full succeeded");
  } catch (const AtomicWriteError& e) {
    CHECK(e.stage() == AtomicWriteError::Stage::write_through);
    CHECK(e.error_number() == ENOSPC);
    CHECK(std::string(e.what()) == "cannot write '" + to_full + "': No space left on device");
  }
  REQUIRE(::lstat(to_full.c_str(), &info) == 0);
  CHECK(S_ISLNK(info.st_mode));
  // A FIFO with a reader gets the bytes and stays a FIFO; one without a reader is an error at once
  // (O_NONBLOCK on the open), not a wait without end.
  const std::string fifo = dir.file("fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  try {
    write_file_atomically(fifo, "x");
    FAIL("writing into a FIFO without a reader succeeded");
  } catch (const AtomicWriteError& e) {
    CHECK(e.error_number() == ENXIO);
    CHECK(std::string(e.what()).find("no process is reading it") != std::string::npos);
  }
  std::string received;
  std::thread reader([&] { received = read_file(fifo); });
  const std::string sent(100000, 'f');  // beyond a pipe's buffer: the writer blocks until read
  for (int attempt = 0;; ++attempt) {   // until the reader has opened its end
    try {
      write_file_atomically(fifo, sent);
      break;
    } catch (const AtomicWriteError& e) {
      REQUIRE(e.error_number() == ENXIO);
      REQUIRE(attempt < 5000);
      ::usleep(1000);
    }
  }
  reader.join();
  CHECK(received == sent);
  REQUIRE(::lstat(fifo.c_str(), &info) == 0);
  CHECK(S_ISFIFO(info.st_mode));
  CHECK(dir.entries() == std::vector<std::string>{"fifo", "full-link", "null-link"});
}

TEST_CASE("support: a link to a regular file keeps the link and replaces its target; a dangling link is refused",
          "[unit][support]") {
  TempDir dir;
  const std::string target = dir.file("target.txt"), link = dir.file("link.txt");
  pfgen_test::write_file(target, "old\n");
  REQUIRE(::symlink("target.txt", link.c_str()) == 0);
  write_file_atomically(link, "new\n");
  struct stat info {};
  REQUIRE(::lstat(link.c_str(), &info) == 0);
  CHECK(S_ISLNK(info.st_mode));
  CHECK(read_file(target) == "new\n");
  const std::string dangling = dir.file("dangling");
  REQUIRE(::symlink("missing/nothing", dangling.c_str()) == 0);
  try {
    write_file_atomically(dangling, "x");
    FAIL("writing through a dangling link succeeded");
  } catch (const AtomicWriteError& e) {
    CHECK(e.stage() == AtomicWriteError::Stage::dangling_link);
    CHECK(std::string(e.what()) ==
          "cannot write '" + dangling + "': it is a symbolic link to a file that does not exist");
  }
  CHECK(dir.entries() == std::vector<std::string>{"dangling", "link.txt", "target.txt"});
}

TEST_CASE("support: write_files_together writes all or none", "[unit][support]") {
  TempDir dir;
  const std::string a = dir.file("a.hpp"), b = dir.file("b.hpp"), c = dir.file("c.hpp");
  pfgen_test::write_file(a, "old a\n");
  REQUIRE(::mkdir(b.c_str(), 0777) == 0);  // a directory in the way of the second
  try {
    pfgen_support::write_files_together({{a, "new a\n"}, {b, "new b\n"}, {c, "new c\n"}});
    FAIL("a directory in the way was replaced");
  } catch (const AtomicWriteError& e) {
    CHECK(e.stage() == AtomicWriteError::Stage::not_a_file);
    CHECK(std::string(e.what()) == "cannot write '" + b + "': it exists and is not a regular file");
  }
  CHECK(read_file(a) == "old a\n");
  CHECK(dir.entries() == std::vector<std::string>{"a.hpp", "b.hpp"});
  // A failed temporary (its directory missing) replaces none of the targets either.
  CHECK_THROWS_AS(pfgen_support::write_files_together({{a, "new a\n"}, {dir.file("missing/d.hpp"), "d\n"}}),
                  AtomicWriteError);
  CHECK(read_file(a) == "old a\n");
  CHECK(dir.entries() == std::vector<std::string>{"a.hpp", "b.hpp"});
  ::rmdir(b.c_str());
  pfgen_support::write_files_together({{a, "new a\n"}, {b, "new b\n"}, {c, "new c\n"}});
  CHECK(read_file(a) == "new a\n");
  CHECK(read_file(b) == "new b\n");
  CHECK(read_file(c) == "new c\n");
  CHECK(dir.entries() == std::vector<std::string>{"a.hpp", "b.hpp", "c.hpp"});
}
