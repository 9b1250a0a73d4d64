#include "pfgen_runtime/record_reader.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>

namespace pfgen_runtime {
namespace {

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

std::string quoted(std::string_view cell) { return quoted_cell(std::string(cell)); }

bool is_missing(std::string_view cell) { return cell.empty() || cell == "NaN" || cell == "nan" || cell == "NA"; }

}  // namespace

RecordReader::RecordReader(const std::string& path, const std::string& time_column,
                           std::vector<std::string> observation_columns, std::size_t expected)
    : path_(path), time_name_(time_column), in_(path, std::ios::binary), buffer_(kMaxLineLength + 2) {
  if (!in_) fail("cannot open the file for reading");
  if (!read_line()) fail("the file is empty: a record needs a header line naming its columns");
  const RecordFail failing = [this](const std::string& what, std::size_t column) { fail(what, column); };
  const std::vector<std::string> header(fields_.begin(), fields_.end());
  check_record_header(header, failing);
  header_ = header;
  const RecordColumns chosen = choose_record_columns(header_, time_name_, std::move(observation_columns), expected, failing);
  time_index_ = chosen.time_index;
  indices_ = chosen.indices;
  names_ = chosen.names;
}

void RecordReader::fail(const std::string& what, std::size_t column) const {
  std::string place = path_;
  if (line_ > 0) place += ":" + std::to_string(line_);
  if (column > 0) {
    place += ": column " + std::to_string(column);
    if (column <= header_.size()) place += " (" + header_[column - 1] + ")";
  }
  pfgen_support::ErrorPlace where;
  where.file = path_;
  where.line = static_cast<int>(line_);
  where.column = static_cast<int>(column);
  throw RecordError(place + ": " + what, where);
}

bool RecordReader::read_line() {
  while (true) {
    in_.getline(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    const std::streamsize length = in_.gcount();
    if (in_.bad()) fail("read error");
    if (in_.fail() && !in_.eof()) {
      ++line_;
      fail("the line is longer than " + std::to_string(kMaxLineLength) + " bytes");
    }
    if (length == 0 && in_.eof()) return false;
    ++line_;
    // gcount counts the newline that getline consumed but did not store.
    std::string_view text(buffer_.data(), static_cast<std::size_t>(length) - (in_.eof() ? 0 : 1));
    if (in_.eof()) in_.clear(std::ios::eofbit);
    // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first column's name.
    if (line_ == 1 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    const std::string_view content = trimmed(text);
    if (content.empty() || content.front() == '#') {
      if (in_.eof()) return false;
      continue;
    }
    if (content.find('"') != std::string_view::npos) fail("quoted fields are not read: write the cell without quotes");
    fields_.clear();
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = content.find(',', start);
      fields_.push_back(trimmed(content.substr(start, comma == std::string_view::npos ? comma : comma - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return true;
  }
}

bool RecordReader::next(double& t, double* values) {
  if (in_.eof() || !read_line()) return false;
  if (fields_.size() != header_.size())
    fail("the row has " + std::to_string(fields_.size()) + " fields, the header " + std::to_string(header_.size()));
  auto number = [&](std::size_t k, double& out) {
    const std::string_view cell = fields_[k];
    const char* end = cell.data() + cell.size();
    const char* start = cell.data() + (!cell.empty() && cell.front() == '+' ? 1 : 0);
    const auto [ptr, error] = std::from_chars(start, end, out);
    if (error == std::errc::result_out_of_range) fail(quoted(cell) + " is beyond the range of a double", k + 1);
    if (error != std::errc() || ptr != end || cell.empty()) fail(quoted(cell) + " is not a number", k + 1);
    if (!std::isfinite(out)) fail(quoted(cell) + " is not a finite number", k + 1);
  };
  if (is_missing(fields_[time_index_])) fail("the time is missing", time_index_ + 1);
  number(time_index_, t);
  if (has_time_ && !(t > last_time_))
    fail("the time " + std::string(fields_[time_index_]) + " does not come after the previous row's (line " +
             std::to_string(last_line_) + "): times must increase",
         time_index_ + 1);
  has_time_ = true;
  last_time_ = t;
  last_line_ = line_;
  for (std::size_t i = 0; i < indices_.size(); ++i) {
    const std::size_t k = indices_[i];
    if (is_missing(fields_[k]))
      values[i] = std::numeric_limits<double>::quiet_NaN();
    else
      number(k, values[i]);
  }
  return true;
}

}  // namespace pfgen_runtime
