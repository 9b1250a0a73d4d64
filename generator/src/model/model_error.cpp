#include "pfgen/model/model_error.hpp"

#include <cmath>
#include <cstdio>

namespace pfgen {

ModelError::ModelError(std::string field, std::string message, std::optional<int> row,
                       std::optional<int> column)
    : pfgen_support::Error(message), field_(std::move(field)), message_(std::move(message)),
      row_(row), column_(column) {
  rebuild();
}

void ModelError::rebuild() {
  place_ = pfgen_support::ErrorPlace{file_, location_.line, location_.column, field_, row_, column_};
  std::string text = file_.empty() ? std::string("<model>") : file_;
  if (location_.line > 0) {
    text += ":" + std::to_string(location_.line);
    if (location_.column > 0) text += ":" + std::to_string(location_.column);
  }
  text += ": error:";
  if (!field_.empty()) text += " field '" + field_ + "'";
  if (row_) text += ", row " + std::to_string(*row_);
  if (column_) text += ", column " + std::to_string(*column_);
  text += (field_.empty() && !row_ && !column_) ? " " : ": ";
  text += message_;
  what_ = text;
}

std::string count_text(double count) {
  if (count < 1e15) return std::to_string(static_cast<long long>(std::round(count)));
  if (!std::isfinite(count)) return "more than 1e308";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2g", count);
  return buffer;
}

}  // namespace pfgen
