#pragma once
// Whole-file writes that readers never see half done: the contents go to a temporary file in the
// target's directory (so that rename() stays within one file system), which then replaces the
// target in one rename(). Every temporary name is unique: process id, a per-process random
// number and a counter, created with O_EXCL. So concurrent writers of one path, threads or
// processes, never share a temporary, and the target is always one writer's whole contents.
// Not fsync()ed: this guards against concurrent writers and failed writes, not power loss.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pfgen_support/error.hpp"

namespace pfgen_support {

class AtomicWriteError : public Error {
 public:
  // writing the temporary (creating it included), renaming it, writing into a device, FIFO or
  // socket, a symbolic link whose target does not exist, or (write_files_together) a target that
  // exists and is not a regular file
  enum class Stage { write, rename, write_through, dangling_link, not_a_file };
  AtomicWriteError(Stage stage, const std::string& path, const std::string& temporary, int error_number);
  Stage stage() const { return stage_; }
  const std::string& path() const { return path_; }
  const std::string& temporary() const { return temporary_; }  // already removed; empty if none
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

// Writes `contents` to `path` through a unique temporary and rename() when `path` is a regular
// file or does not exist yet; a symbolic link to a regular file keeps the link, and its target is
// replaced. Anything else that exists (a device such as /dev/null or /dev/stdout, a FIFO, a
// socket, or a link to one) is opened and written into, never replaced; a write that fails there
// (ENOSPC on /dev/full, a FIFO without a reader) is an error too. The process's own standard
// output or error (the same file as descriptor 1 or 2: `-o /dev/stdout`, or a link to
// /proc/self/fd/1, with the output redirected to a file) is written at that stream's position
// after what the process has printed there, never replaced: a rename over the file standard output
// goes to lost what was printed before and everything printed after. On failure the temporary is
// removed, a replaced target is left as it was, and AtomicWriteError names the path and the
// reason ("cannot write '<path>': <strerror>").
void write_file_atomically(const std::string& path, const std::string& contents);

// Several files as one output (a codegen's headers): all or nothing. Every target must be a
// regular file or not exist (else Stage::not_a_file, before anything is written); all the
// temporaries are written first, so a failed write (a full disk) replaces none of the targets,
// then each is renamed into place.
void write_files_together(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace pfgen_support
