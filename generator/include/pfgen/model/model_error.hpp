#pragma once
// A user-facing error about a model: names the file, the field, the matrix
// entry and what is wrong, so that the command line can print it as one line.
#include <optional>
#include <stdexcept>
#include <string>

#include "pfgen_support/error.hpp"

namespace pfgen {

struct SourceLocation {
  int line = 0;    // 1-based line in the model file; 0 when unknown
  int column = 0;  // 1-based column in the model file; 0 when unknown
};

class ModelError : public pfgen_support::Error {
 public:
  ModelError(std::string field, std::string message, std::optional<int> row = std::nullopt,
             std::optional<int> column = std::nullopt);

  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }
  std::optional<int> row() const { return row_; }
  std::optional<int> column() const { return column_; }
  const std::string& file() const { return file_; }
  const SourceLocation& location() const { return location_; }

  // The loader fills these in once it knows where the field sits in the file.
  void set_file(std::string file) { file_ = std::move(file); rebuild(); }
  void set_location(SourceLocation location) { location_ = location; rebuild(); }

 private:
  void rebuild();
  std::string field_;
  std::string message_;
  std::optional<int> row_;
  std::optional<int> column_;
  std::string file_;
  SourceLocation location_;
  std::string what_;

 public:
  const char* what() const noexcept override { return what_.c_str(); }
  // what() already says "<file>:<line>:<column>: error: field ...".
  std::string report() const override { return what_; }
};

// A count (of terms, digits, steps) as a message gives it: whole below 1e15 ("501501"), else in
// two significant digits ("1.2e+30"), "more than 1e308" when infinite.
std::string count_text(double count);

}  // namespace pfgen
