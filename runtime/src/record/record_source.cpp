#include "pfgen_runtime/record_source.hpp"

namespace pfgen_runtime {

std::string quoted_cell(const std::string& cell) {
  std::string out(cell.substr(0, 40));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  return "'" + out + (cell.size() > 40 ? "...'" : "'");
}

void check_record_header(const std::vector<std::string>& names, const RecordFail& fail) {
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k].empty()) fail("the header's column " + std::to_string(k + 1) + " has no name", k + 1);
    for (std::size_t j = 0; j < k; ++j)
      if (names[j] == names[k]) fail("the header names " + quoted_cell(names[k]) + " twice", k + 1);
  }
}

RecordColumns choose_record_columns(const std::vector<std::string>& header, const std::string& time_column,
                                    std::vector<std::string> observation_columns, std::size_t expected,
                                    const RecordFail& fail) {
  auto column_of = [&](const std::string& name, const char* role) {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    std::string known;
    for (const auto& h : header) known += (known.empty() ? "" : ", ") + h;
    fail(std::string("the header has no ") + role + " column " + quoted_cell(name) + " (its columns: " + known + ")", 0);
    return header.size();  // not reached: fail does not return
  };
  RecordColumns out;
  out.time_index = column_of(time_column, "time");
  if (observation_columns.empty()) {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (k != out.time_index) observation_columns.push_back(header[k]);
    if (expected > 0 && observation_columns.size() != expected)
      fail("the header has " + std::to_string(observation_columns.size()) + " columns besides the time " +
               quoted_cell(time_column) + ", the model observes " + std::to_string(expected) +
               "; name the observation columns in the model's order",
           0);
  } else if (expected > 0 && observation_columns.size() != expected) {
    fail(std::to_string(observation_columns.size()) + " observation columns named, the model observes " +
             std::to_string(expected),
         0);
  }
  for (const auto& name : observation_columns) {
    const std::size_t k = column_of(name, "observation");
    if (k == out.time_index) fail("the column " + quoted_cell(name) + " is the time, not an observation", k + 1);
    out.indices.push_back(k);
  }
  out.names = std::move(observation_columns);
  return out;
}

}  // namespace pfgen_runtime
