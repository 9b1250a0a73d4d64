#pragma once
// A record held in memory: a header naming the columns and the rows, a value per column (the
// API's and the Python module's data without a file). Columns are chosen as a file's are
// (record_source.hpp) and rows checked the same way; a message names the record and the row
// ("<data> row 3: column 'y': ..."). The rows are read in place: they must outlive the source.
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen_runtime/record_source.hpp"

namespace pfgen_runtime {

class RecordArrays : public RecordSource {
 public:
  // name: the record in messages and reports; header: a name per column (none empty, none twice,
  // none with a comma, quote or line break, since they head estimate's CSV); rows: a value per
  // header column each, NaN where missing. time_column, observation_columns, expected: as
  // RecordReader's.
  RecordArrays(std::string name, std::vector<std::string> header, const std::vector<std::vector<double>>& rows,
               const std::string& time_column, std::vector<std::string> observation_columns, std::size_t expected);
  bool next(double& t, double* values) override;
  std::size_t line() const override { return row_; }
  const char* line_word() const override { return "row"; }
  const std::string& path() const override { return name_; }
  std::string place() const override { return record_place(name_, line_word(), row_); }
  const std::vector<std::string>& observation_columns() const override { return columns_.names; }
  const std::string& time_column() const override { return header_[columns_.time_index]; }

 private:
  [[noreturn]] void fail(const std::string& what, std::size_t column = 0) const;
  std::string name_;
  std::vector<std::string> header_;
  const std::vector<std::vector<double>>& rows_;
  RecordColumns columns_;
  std::size_t row_ = 0;  // 1-based: the row next() read last
  double last_time_ = 0;
};

}  // namespace pfgen_runtime
