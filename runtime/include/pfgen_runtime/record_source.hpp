#pragma once
// Where a record's rows come from: a CSV file read row by row (record_reader.hpp) or arrays in
// memory (record_arrays.hpp). Both name their columns by a header, choose the time and the
// observation columns from it by name (choose_record_columns, so the two take the same options
// with the same messages) and check each row the same way: the time finite and strictly
// increasing, an observation a finite number or missing (NaN).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "pfgen_support/error.hpp"

namespace pfgen_runtime {

class RecordError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

// A row as messages place it: "nile.csv:12" for a file's line, "<data> row 3" for the arrays' row (`line_word`
// "line" or "row", as RecordSource::line_word).
inline std::string record_place(const std::string& name, const std::string& line_word, std::size_t line) {
  return line_word == "line" ? name + ":" + std::to_string(line) : name + " " + line_word + " " + std::to_string(line);
}

class RecordSource {
 public:
  virtual ~RecordSource() = default;
  // The next row: its time and observation values (NaN where missing). false after the last row.
  virtual bool next(double& t, double* values) = 0;
  // The row next() read last: its line in the file, or its 1-based number among the arrays' rows.
  virtual std::size_t line() const = 0;
  // What line() counts, in messages: "line" or "row".
  virtual const char* line_word() const = 0;
  // The record's name in messages and reports: the file's path, or the arrays' name.
  virtual const std::string& path() const = 0;
  // The row next() read last as a message places it: "nile.csv:12", "<data> row 3".
  virtual std::string place() const = 0;
  virtual const std::vector<std::string>& observation_columns() const = 0;
  virtual const std::string& time_column() const = 0;
};

// A header's time and observation columns, by name. `observation_columns`: in the model's order,
// or empty for every column but the time, in the header's order (then there must be `expected`
// of them; 0: any number). `fail(message, column)` reports a problem (column: 1-based, or 0) and
// does not return.
struct RecordColumns {
  std::size_t time_index = 0;
  std::vector<std::size_t> indices;  // of the observation columns in the header
  std::vector<std::string> names;    // the observation columns
};
using RecordFail = std::function<void(const std::string& message, std::size_t column)>;
RecordColumns choose_record_columns(const std::vector<std::string>& header, const std::string& time_column,
                                    std::vector<std::string> observation_columns, std::size_t expected,
                                    const RecordFail& fail);

// Checks a header's names (none empty, none twice) before they are kept; `fail` as above.
void check_record_header(const std::vector<std::string>& names, const RecordFail& fail);

// A cell quoted in a message, cut short so that the message stays one line.
std::string quoted_cell(const std::string& cell);

}  // namespace pfgen_runtime
