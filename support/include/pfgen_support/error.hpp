#pragma once
// The one base of the errors pfgen reports to a user: a bad model file, a bad option, a filter
// that cannot be evaluated or generated, a compiler or plugin that fails, a file that cannot be
// written. The command line prints any of them as one line (generator/cli/program/main.cpp has one catch
// for them); a program using pfgen as a library catches this one type. Each error says what is
// wrong and, where it has one, where: the file and its line and column, the model file's field and
// the row and column of a matrix entry.
#include <optional>
#include <stdexcept>
#include <string>

namespace pfgen_support {

struct ErrorPlace {
  std::string file;             // empty when unknown
  int line = 0;                 // 1-based in the file; 0 when unknown
  int column = 0;               // 1-based in the line; 0 when unknown
  std::string field;            // the model file's field ("drift", "observation.B"); empty when none
  std::optional<int> row;       // of a matrix entry, 1-based
  std::optional<int> entry;     // its column, 1-based
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, ErrorPlace place = {})
      : std::runtime_error(message), place_(std::move(place)) {}
  const ErrorPlace& place() const { return place_; }
  // The line the command line prints after "pfgen: ": "error: " and the message; an error whose
  // message already names its place and severity (ModelError: "m.yaml:4:15: error: ...") overrides it.
  virtual std::string report() const { return std::string("error: ") + what(); }

 protected:
  ErrorPlace place_;
};

// An error's text on one line, as the command line prints it: line breaks become spaces, and
// trailing ones and spaces go.
inline std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace pfgen_support
