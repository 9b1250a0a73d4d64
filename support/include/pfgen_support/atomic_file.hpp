#pragma once
// Whole-file writes that readers never see half done: the contents go to a temporary file in the
// target's directory (so that rename() stays within one file system), which then replaces the
// target in one rename(). Every temporary name is unique: process id, a per-process random
// number and a counter, created with O_EXCL. So concurrent writers of one path, threads or
// processes, never share a temporary, and the target is always one writer's whole contents.
// Not fsync()ed: this guards against concurrent writers and failed writes, not power loss.
#include <stdexcept>
#include <string>

namespace pfgen_support {

class AtomicWriteError : public std::runtime_error {
 public:
  enum class Stage { write, rename };  // writing the temporary (creating it included), or renaming it
  AtomicWriteError(Stage stage, const std::string& path, const std::string& temporary, int error_number);
  Stage stage() const { return stage_; }
  const std::string& path() const { return path_; }
  const std::string& temporary() const { return temporary_; }  // already removed
  int error_number() const { return error_number_; }           // errno of the failed call

 private:
  Stage stage_;
  std::string path_, temporary_;
  int error_number_;
};

// A fresh name beside `target` ("<target>.tmp-<pid>-<random>-<counter>") that no other thread or
// process uses: for files made by someone else (a compiler's -o) that are then renamed into
// place. The file itself is not created.
std::string unique_temporary_path(const std::string& target);

// Writes `contents` to `path` through a unique temporary and rename(). On failure the temporary
// is removed, the target is left as it was, and AtomicWriteError names the path and the reason
// ("cannot write '<path>': <strerror>").
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace pfgen_support
