#pragma once
// A record of observations as a CSV file, read one row at a time (a file of any length streams
// through): a header naming the columns, then one row per data time. One column is the time,
// strictly increasing; the observation columns hold numbers, or nothing ("", NaN or NA) for a
// missing value. Fields are separated by commas and may be padded with spaces; blank lines and
// lines starting with '#' are skipped. Every error names the file, the line and the column.
#include <cstddef>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "pfgen_runtime/record_source.hpp"

namespace pfgen_runtime {

class RecordReader : public RecordSource {
 public:
  // time_column: the header's name of the time; observation_columns: the observation's columns
  // in the model's order, or empty for every other column in the file's order (then there must be
  // `expected` of them, the model's observations; 0: any number).
  RecordReader(const std::string& path, const std::string& time_column, std::vector<std::string> observation_columns,
               std::size_t expected);
  // The next row: its time and observation values (NaN where missing). false at the end of the file.
  bool next(double& t, double* values) override;
  // 1-based line of the row next() read last.
  std::size_t line() const override { return line_; }
  const char* line_word() const override { return "line"; }
  const std::string& path() const override { return path_; }
  std::string place() const override { return record_place(path_, line_word(), line_); }
  const std::vector<std::string>& observation_columns() const override { return names_; }
  const std::string& time_column() const override { return time_name_; }

  static constexpr std::size_t kMaxLineLength = 1 << 20;

 private:
  [[noreturn]] void fail(const std::string& what, std::size_t column = 0) const;
  bool read_line();  // the next non-blank, non-comment line into fields_; false at the end
  std::string path_, time_name_;
  std::ifstream in_;
  std::vector<char> buffer_;
  std::vector<std::string_view> fields_;
  std::vector<std::string> header_, names_;
  std::size_t time_index_ = 0;
  std::vector<std::size_t> indices_;  // of the observation columns in a row
  std::size_t line_ = 0;
  bool has_time_ = false;
  double last_time_ = 0;
  std::size_t last_line_ = 0;
};

}  // namespace pfgen_runtime
