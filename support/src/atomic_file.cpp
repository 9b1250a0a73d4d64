#include "pfgen_support/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>

#include <climits>
#include <cstdlib>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pfgen_support {
namespace {

std::string describe(AtomicWriteError::Stage stage, const std::string& path, const std::string& temporary,
                     int error_number) {
  const std::string reason = error_number ? std::strerror(error_number) : "unknown error";
  if (stage == AtomicWriteError::Stage::not_a_file)
    return "cannot write '" + path + "': it exists and is not a regular file";
  if (stage == AtomicWriteError::Stage::dangling_link)
    return "cannot write '" + path + "': it is a symbolic link to a file that does not exist";
  if (stage == AtomicWriteError::Stage::write_through && error_number == ENXIO)
    return "cannot write '" + path + "': no process is reading it (" + reason + ")";
  if (stage == AtomicWriteError::Stage::rename)
    return "cannot write '" + path + "': renaming '" + temporary + "' failed: " + reason;
  return "cannot write '" + path + "': " + reason;
}

// Drawn once per process. The pid alone does not separate processes in different pid namespaces
// that share a directory (containers), nor a child forked after the counter has moved.
std::uint64_t process_salt() {
  static const std::uint64_t salt = [] {
    std::uint64_t value = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    try {
      std::random_device device;
      value ^= (static_cast<std::uint64_t>(device()) << 32) ^ device();
    } catch (...) {  // no entropy source: the clock and O_EXCL still keep names apart
    }
    return value;
  }();
  return salt;
}

std::string hex(std::uint64_t value) {
  static const char digits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int k = 15; k >= 0; --k, value >>= 4) out[static_cast<std::size_t>(k)] = digits[value & 15];
  return out;
}

// Writes all of `contents`, retrying short writes and EINTR; errno on failure, else 0.
int write_all(int fd, const std::string& contents) {
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  return 0;
}

}  // namespace

AtomicWriteError::AtomicWriteError(Stage stage, const std::string& path, const std::string& temporary,
                                   int error_number)
    : Error(describe(stage, path, temporary, error_number), ErrorPlace{path}),
      stage_(stage),
      path_(path),
      temporary_(temporary),
      error_number_(error_number) {}

std::string unique_temporary_path(const std::string& target) {
  static std::atomic<std::uint64_t> counter{0};
  // The pid is read on every call, so a forked child never repeats its parent's names.
  return target + ".tmp-" + std::to_string(::getpid()) + "-" + hex(process_salt()) + "-" +
         std::to_string(counter.fetch_add(1));
}

namespace {

// Writes `contents` to a new unique temporary beside `path` and returns its name; on failure the
// temporary is removed and AtomicWriteError thrown.
std::string write_temporary(const std::string& path, const std::string& contents) {
  std::string temporary;
  int fd = -1;
  // O_EXCL: an existing file (a name reused against all odds) is never written into; take
  // another name. Mode 0666 as for any new file: the umask applies, as with std::ofstream.
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    temporary = unique_temporary_path(path);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST && errno != EINTR)
      throw AtomicWriteError(AtomicWriteError::Stage::write, path, temporary, errno);
  }
  if (fd < 0) throw AtomicWriteError(AtomicWriteError::Stage::write, path, temporary, EEXIST);
  int error = write_all(fd, contents);
  if (::close(fd) != 0 && error == 0) error = errno;  // NFS reports write errors at close
  if (error == 0) return temporary;
  ::unlink(temporary.c_str());
  throw AtomicWriteError(AtomicWriteError::Stage::write, path, temporary, error);
}

void rename_into_place(const std::string& temporary, const std::string& path) {
  if (::rename(temporary.c_str(), path.c_str()) == 0) return;
  const int error = errno;
  ::unlink(temporary.c_str());
  throw AtomicWriteError(AtomicWriteError::Stage::rename, path, temporary, error);
}

// A whole-file replacement through a unique temporary and rename() (the header says why).
void replace_file(const std::string& path, const std::string& contents) {
  rename_into_place(write_temporary(path, contents), path);
}

// A device, FIFO or socket (or a link to one) is written into, never replaced: rename() over
// /dev/null would make it a regular file for every process of the machine. O_NONBLOCK only for
// the open, so that a FIFO nobody reads is an error (ENXIO) instead of a wait without end.
void write_through(const std::string& path, const std::string& contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw AtomicWriteError(AtomicWriteError::Stage::write_through, path, "", errno);
  const int flags = ::fcntl(fd, F_GETFL);
  int error = (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0) ? errno : 0;
  if (error == 0) error = write_all(fd, contents);  // /dev/full: ENOSPC, reported
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) throw AtomicWriteError(AtomicWriteError::Stage::write_through, path, "", error);
}

}  // namespace

namespace {

enum class Target { replace, write_through, standard_output, standard_error };

// Whether `target` is the file open as descriptor fd.
bool is_open_as(const struct stat& target, int fd) {
  struct stat open {};
  return ::fstat(fd, &open) == 0 && open.st_dev == target.st_dev && open.st_ino == target.st_ino;
}

// Writes into this process's standard output or error where it stands, after whatever the process
// printed there (flushed first, so that the order is the order of the calls).
void write_into_stream(const std::string& path, int fd, const std::string& contents) {
  std::fflush(fd == 1 ? stdout : stderr);
  if (const int error = write_all(fd, contents))
    throw AtomicWriteError(AtomicWriteError::Stage::write_through, path, "", error);
}

// How `path` is written, and the name to replace: a link to a regular file is resolved, so the
// link stays.
Target classify(std::string& path) {
  struct stat target {};
  if (::stat(path.c_str(), &target) == 0) {  // what the path names, links followed
    if (is_open_as(target, 1)) return Target::standard_output;
    if (is_open_as(target, 2)) return Target::standard_error;
    if (!S_ISREG(target.st_mode) && !S_ISDIR(target.st_mode)) return Target::write_through;
    struct stat entry {};
    if (S_ISREG(target.st_mode) && ::lstat(path.c_str(), &entry) == 0 && S_ISLNK(entry.st_mode)) {
      char resolved[PATH_MAX];
      if (::realpath(path.c_str(), resolved) == nullptr)
        throw AtomicWriteError(AtomicWriteError::Stage::write, path, "", errno);
      path = resolved;
    }
  } else if (errno == ENOENT) {
    struct stat entry {};
    if (::lstat(path.c_str(), &entry) == 0 && S_ISLNK(entry.st_mode))
      throw AtomicWriteError(AtomicWriteError::Stage::dangling_link, path, "", ENOENT);
  }
  return Target::replace;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& contents) {
  std::string target = path;
  switch (classify(target)) {
    case Target::write_through: return write_through(path, contents);
    case Target::standard_output: return write_into_stream(path, 1, contents);
    case Target::standard_error: return write_into_stream(path, 2, contents);
    case Target::replace: return replace_file(target, contents);
  }
}

void write_files_together(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<std::string> targets;
  for (const auto& [path, contents] : files) {
    std::string target = path;
    struct stat info {};
    if (classify(target) != Target::replace || (::stat(target.c_str(), &info) == 0 && S_ISDIR(info.st_mode)))
      throw AtomicWriteError(AtomicWriteError::Stage::not_a_file, path, "", 0);
    targets.push_back(target);
  }
  std::vector<std::string> temporaries;
  try {
    for (std::size_t k = 0; k < files.size(); ++k) temporaries.push_back(write_temporary(targets[k], files[k].second));
  } catch (...) {
    for (const auto& temporary : temporaries) ::unlink(temporary.c_str());
    throw;
  }
  for (std::size_t k = 0; k < files.size(); ++k) {
    try {
      rename_into_place(temporaries[k], targets[k]);
    } catch (...) {
      for (std::size_t j = k + 1; j < files.size(); ++j) ::unlink(temporaries[j].c_str());
      throw;
    }
  }
}

}  // namespace pfgen_support
