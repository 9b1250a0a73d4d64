#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "api_impl.hpp"
#include "cli_options.hpp"
#include "pfgen_support/quoted_text.hpp"
#include "pfgen_support/shortest_double.hpp"

namespace pfgen::api {
namespace {

// Guards the list of contents left to destroy, apart from the API's lock.
std::mutex& pending_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<std::function<void()>>& pending() {
  static std::vector<std::function<void()>> list;
  return list;
}

}  // namespace

std::recursive_mutex& api_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

void destroy_later(std::function<void()> destroy) {
  const std::lock_guard<std::mutex> lock(pending_mutex());
  pending().push_back(std::move(destroy));
}

void destroy_pending() {
  std::vector<std::function<void()>> due;
  {
    const std::lock_guard<std::mutex> lock(pending_mutex());
    due.swap(pending());
  }
  for (auto& destroy : due) destroy();
}

std::string number_text(double value) { return pfgen_support::shortest_double(value); }

void check_no_nul(const std::string& what, const std::string& text) {
  if (text.find('\0') != std::string::npos)
    throw Error(what + ": " + pfgen_support::quoted(text.substr(0, text.find('\0'))) +
                " is followed by a NUL character, which no file name or option can hold");
}

std::vector<std::string> assignment_texts(const std::map<std::string, double>& values, const std::string& option) {
  std::vector<std::string> texts;
  for (const auto& [name, value] : values) {
    check_no_nul(option, name);
    // The command splits NAME=VALUE at the first '=': a name holding one would be read as another name
    // with a value that is not a number.
    if (name.find('=') != std::string::npos)
      throw Error(option + ": " + pfgen_support::quoted(name) + " is not a name: it holds '='");
    texts.push_back(name + "=" + number_text(value));
  }
  return texts;
}

void check_number_option(const std::string& option, double value) {
  if (!std::isfinite(value) || (value != 0 && std::fabs(value) < DBL_MIN))
    throw cli::CliValueError(option + ": " + pfgen_support::quoted(number_text(value)) +
                             " is outside the range of a double (magnitudes from about 2.2e-308 to 1.8e308)");
}

std::vector<Vector> csv_series(const std::string& csv, std::size_t columns) {
  std::vector<Vector> out(columns);
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    std::size_t column = 0, start = 0;
    while (column < columns) {
      const std::size_t end = std::min(line.find(',', start), line.size());
      const std::string cell = line.substr(start, end - start);
      out[column++].push_back(cell.empty() ? std::nan("") : std::strtod(cell.c_str(), nullptr));
      start = end + 1;
    }
  }
  return out;
}

std::string version() { return PFGEN_VERSION; }

}  // namespace pfgen::api
