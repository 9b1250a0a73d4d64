#include "pfgen_support/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <random>

#include <fcntl.h>
#include <unistd.h>

namespace pfgen_support {
namespace {

std::string describe(AtomicWriteError::Stage stage, const std::string& path, const std::string& temporary,
                     int error_number) {
  const std::string reason = error_number ? std::strerror(error_number) : "unknown error";
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
    : std::runtime_error(describe(stage, path, temporary, error_number)),
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

void write_file_atomically(const std::string& path, const std::string& contents) {
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
  if (error == 0 && ::rename(temporary.c_str(), path.c_str()) == 0) return;
  const AtomicWriteError::Stage stage = error ? AtomicWriteError::Stage::write : AtomicWriteError::Stage::rename;
  if (error == 0) error = errno;
  ::unlink(temporary.c_str());
  throw AtomicWriteError(stage, path, temporary, error);
}

}  // namespace pfgen_support
