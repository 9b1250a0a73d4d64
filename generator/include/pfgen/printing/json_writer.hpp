#pragma once
// A minimal JSON value with deterministic output: object members keep the
// order they were added in, numbers are printed as shortest round-trip text.
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pfgen {

class Json {
 public:
  static Json string(std::string value);
  static Json number(double value);  // throws std::domain_error on NaN or infinity
  static Json integer(std::uint64_t value);  // written in decimal digits ("10", not "1e+01")
  static Json boolean(bool value);
  static Json array(std::vector<Json> items = {});
  static Json object();

  Json& add(const std::string& key, Json value);  // objects only
  Json& push(Json value);                         // arrays only

  // Pretty-printed: one member per line; arrays of scalars stay on one line.
  std::string dump() const;
  // The same bytes written to `out` piece by piece, never holding the whole text (a dense cubic
  // n = 20 report is 120 MB).
  void dump(std::ostream& out) const;
  // On one line, for JSON Lines output (one object per line).
  std::string dump_line() const;

 private:
  enum class Kind { String, Number, Boolean, Array, Object };
  // indent < 0: compact. With `sink`, `out` is moved to it whenever it passes a megabyte.
  void write(std::string& out, int indent, std::ostream* sink = nullptr) const;
  bool is_scalar_array() const;
  Kind kind_ = Kind::Object;
  // Shared, not copied, when a value is copied: a report writes each of its long strings (a dense
  // cubic n = 20 P drift entry: 300 kB) in two places of the symmetric P matrix.
  std::shared_ptr<const std::string> scalar_;
  std::vector<Json> items_;
  std::vector<std::string> keys_;
};

std::string json_quote(const std::string& text);

}  // namespace pfgen
