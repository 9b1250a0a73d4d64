#pragma once
// An output file written as it is made (a record's estimates can be far larger than memory), that
// a reader still never sees half done: the text goes to a unique temporary beside the target,
// renamed over it by finish(); a StreamedFile destroyed unfinished (an error part way) removes its
// temporary and leaves the target as it was. A target that exists and is not a regular file (a
// device, /dev/stdout) is written into directly.
#include <cstdio>
#include <string>

namespace pfgen::cli {

class StreamedFile {
 public:
  explicit StreamedFile(const std::string& path);  // CliValueError when it cannot be opened
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;
  ~StreamedFile();
  void write(const std::string& text);  // CliValueError on a failed write
  void finish();

 private:
  std::string path_, temporary_;  // temporary_ empty: writing into the target
  std::FILE* file_ = nullptr;
  bool finished_ = false;
};

}  // namespace pfgen::cli
