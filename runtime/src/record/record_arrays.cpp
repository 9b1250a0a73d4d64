#include "pfgen_runtime/record_arrays.hpp"

#include <cmath>

#include "pfgen_support/shortest_double.hpp"

namespace pfgen_runtime {

RecordArrays::RecordArrays(std::string name, std::vector<std::string> header, const std::vector<std::vector<double>>& rows,
                           const std::string& time_column, std::vector<std::string> observation_columns,
                           std::size_t expected)
    : name_(std::move(name)), rows_(rows) {
  const RecordFail failing = [this](const std::string& what, std::size_t column) { fail(what, column); };
  if (header.empty()) fail("the header names no columns: a record needs a time column");
  check_record_header(header, failing);
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k].find_first_of(",\"\r\n") != std::string::npos)
      fail("the column name " + quoted_cell(header[k]) + " holds a comma, quote or line break, which a CSV header cannot",
           k + 1);
  header_ = std::move(header);
  columns_ = choose_record_columns(header_, time_column, std::move(observation_columns), expected, failing);
}

void RecordArrays::fail(const std::string& what, std::size_t column) const {
  std::string place = row_ > 0 ? this->place() : name_;
  if (column > 0) place += ": column " + quoted_cell(column <= header_.size() ? header_[column - 1] : std::to_string(column));
  pfgen_support::ErrorPlace where;
  where.file = name_;
  where.line = static_cast<int>(row_);
  where.column = static_cast<int>(column);
  throw RecordError(place + ": " + what, where);
}

bool RecordArrays::next(double& t, double* values) {
  if (row_ == rows_.size()) return false;
  const std::vector<double>& row = rows_[row_++];
  if (row.size() != header_.size())
    fail("the row has " + std::to_string(row.size()) + " values, the header " + std::to_string(header_.size()));
  const std::size_t time = columns_.time_index;
  if (std::isnan(row[time])) fail("the time is missing", time + 1);
  if (!std::isfinite(row[time])) fail("the time " + pfgen_support::shortest_chars(row[time]) + " is not finite", time + 1);
  if (row_ > 1 && !(row[time] > last_time_))
    fail("the time " + pfgen_support::shortest_chars(row[time]) + " does not come after the previous row's (" +
             pfgen_support::shortest_chars(last_time_) + "): times must increase",
         time + 1);
  t = last_time_ = row[time];
  for (std::size_t i = 0; i < columns_.indices.size(); ++i) {
    const double value = row[columns_.indices[i]];
    if (std::isinf(value)) fail(pfgen_support::shortest_chars(value) + " is not a finite number", columns_.indices[i] + 1);
    values[i] = value;
  }
  return true;
}

}  // namespace pfgen_runtime
