#include "streamed_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "cli_options.hpp"
#include "pfgen_support/atomic_file.hpp"

namespace pfgen::cli {

StreamedFile::StreamedFile(const std::string& path) : path_(path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  const bool write_into = !error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
  if (!write_into) temporary_ = pfgen_support::unique_temporary_path(path);
  file_ = std::fopen(write_into ? path.c_str() : temporary_.c_str(), write_into ? "w" : "wx");
  if (!file_) throw CliValueError("cannot write '" + path + "': " + std::strerror(errno));
}

StreamedFile::~StreamedFile() {
  if (file_) std::fclose(file_);
  if (!finished_ && !temporary_.empty()) std::remove(temporary_.c_str());
}

void StreamedFile::write(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw CliValueError("cannot write '" + path_ + "': " + std::strerror(errno));
}

void StreamedFile::finish() {
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int error = errno;
  std::fclose(file_);
  file_ = nullptr;
  if (!flushed) throw CliValueError("cannot write '" + path_ + "': " + std::strerror(error));
  if (!temporary_.empty() && std::rename(temporary_.c_str(), path_.c_str()) != 0)
    throw CliValueError("cannot write '" + path_ + "': " + std::strerror(errno));
  finished_ = true;
}

}  // namespace pfgen::cli
