#include "pfgen/notation/latex_line_breaker.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

namespace pfgen {
namespace {

// Commands that print nothing (spacing, delimiter sizes, structure) or whose arguments carry the
// width (\frac counts its wider argument, below). Any other command is one glyph (\alpha, \sin).
bool prints_nothing(const std::string& command) {
  return command == "left" || command == "right" || command == "Bigl" || command == "Bigr" || command == "," ||
         command == "mathrm" || command == "operatorname" || command == "frac" || command == "displaystyle";
}

class WidthEstimator {
 public:
  explicit WidthEstimator(const std::string& text) : text_(text) {}

  // Width of text_[from, to): scripts (after ^ or _) count 0.7, a \frac its wider argument.
  double width(std::size_t from, std::size_t to) {
    double total = 0;
    std::size_t i = from;
    while (i < to) {
      const char c = text_[i];
      if (c == '\\') {
        std::size_t j = i + 1;
        while (j < to && std::isalpha(static_cast<unsigned char>(text_[j]))) ++j;
        if (j == i + 1 && j < to) ++j;  // a one-character command: \, \{ \\ ...
        const std::string command = text_.substr(i + 1, j - i - 1);
        i = j;
        if (command == "frac") {
          const double numerator = group_width(i, to), denominator = group_width(i, to);
          total += std::max(numerator, denominator) + 0.5;
        } else if (command == "\\") {
          // A matrix's row break counts as one glyph, as before; its optional extra space ("\\[1ex]")
          // takes no width.
          total += 1;
          if (i < to && text_[i] == '[') {
            const std::size_t close = text_.find(']', i);
            if (close != std::string::npos && close < to) i = close + 1;
          }
        } else if (command == "quad") {
          total += 2;
        } else if (!prints_nothing(command)) {
          total += 1;
        }
        continue;
      }
      if (c == '^' || c == '_') {
        ++i;
        total += 0.7 * (i < to && text_[i] == '{' ? group_width(i, to) : (++i, 1.0));
        continue;
      }
      if (c == '{' || c == '}' || c == ' ' || c == '&') {
        ++i;
        continue;
      }
      // Operators and relations carry space on both sides.
      total += (c == '+' || c == '-' || c == '=') ? 1.8 : 1;
      ++i;
    }
    return total;
  }

 private:
  // The width of the {...} group at i (or of one character), moving i past it.
  double group_width(std::size_t& i, std::size_t to) {
    if (i >= to) return 0;
    if (text_[i] != '{') {
      ++i;
      return width(i - 1, i);
    }
    int depth = 0;
    const std::size_t open = i;
    for (; i < to; ++i) {
      if (text_[i] == '{') ++depth;
      if (text_[i] == '}' && --depth == 0) break;
    }
    const double inner = width(open + 1, i);
    if (i < to) ++i;
    return inner;
  }
  const std::string& text_;
};

// A place where the line may be cut: before the sign of " + " or " - " at brace depth 0.
struct Cut {
  std::size_t at;       // index of the space before the sign
  std::vector<std::size_t> open_lefts;  // \left( pairs enclosing it, by the index of their \left
};

std::vector<Cut> cut_candidates(const std::string& rhs) {
  std::vector<Cut> cuts;
  std::vector<std::size_t> lefts;  // open \left's, innermost last
  int braces = 0;
  for (std::size_t i = 0; i < rhs.size(); ++i) {
    if (rhs.compare(i, 5, "\\left") == 0 && (i + 5 >= rhs.size() || !std::isalpha(static_cast<unsigned char>(rhs[i + 5])))) {
      lefts.push_back(i);
      i += 4;
    } else if (rhs.compare(i, 6, "\\right") == 0) {
      if (!lefts.empty()) lefts.pop_back();
      i += 5;
    } else if (rhs[i] == '\\' && i + 1 < rhs.size()) {
      ++i;  // \{ and \} are not groups
    } else if (rhs[i] == '{') {
      ++braces;
    } else if (rhs[i] == '}') {
      --braces;
    } else if (braces == 0 && i > 0 && i + 2 < rhs.size() && rhs[i] == ' ' && (rhs[i + 1] == '+' || rhs[i + 1] == '-') &&
               rhs[i + 2] == ' ') {
      cuts.push_back(Cut{i, lefts});
    }
  }
  return cuts;
}

// The \right matching the \left at `left`.
std::size_t matching_right(const std::string& rhs, std::size_t left) {
  int depth = 0;
  for (std::size_t i = left; i < rhs.size(); ++i) {
    if (rhs.compare(i, 5, "\\left") == 0 && (i + 5 >= rhs.size() || !std::isalpha(static_cast<unsigned char>(rhs[i + 5])))) ++depth;
    if (rhs.compare(i, 6, "\\right") == 0 && --depth == 0) return i;
  }
  return std::string::npos;
}

}  // namespace

double latex_width(const std::string& math) { return WidthEstimator(math).width(0, math.size()); }

std::string latex_align_lines(const std::string& lhs, const std::string& rhs, double width) {
  WidthEstimator estimate(rhs);
  // align* sets every left-hand side in one column as wide as the widest of them, which a line
  // cannot see: allow for \frac{dP_{1,10}}{dt}, the widest pfgen writes, and the " = ".
  const double lhs_width = std::max(latex_width(lhs), 8.0) + 1.8;
  if (lhs_width + estimate.width(0, rhs.size()) <= width) return lhs + " &= " + rhs;

  // Greedy: the longest run of terms that fits each line; a term too wide alone gets a line.
  // Widths add up between cuts, which sit outside every brace group.
  const std::vector<Cut> candidates = cut_candidates(rhs);
  std::vector<const Cut*> chosen;
  double line = lhs_width;  // width of the current line so far
  std::size_t from = 0;
  const Cut* previous = nullptr;  // the last cut passed on the current line
  auto reach = [&](std::size_t boundary, const Cut* cut) {
    const double segment = estimate.width(from, boundary);
    if (previous && line + segment > width) {
      chosen.push_back(previous);
      line = lhs_width + 2;  // continuation lines start "&\quad"
    }
    line += segment;
    from = boundary;
    previous = cut;
  };
  for (const Cut& cut : candidates) reach(cut.at, &cut);
  reach(rhs.size(), nullptr);
  if (chosen.empty()) return lhs + " &= " + rhs;

  // Pairs of \left( \right) around a cut become \Bigl( \Bigr), which may span lines.
  std::string text = rhs;
  std::vector<std::size_t> resized;
  for (const Cut* cut : chosen)
    for (std::size_t left : cut->open_lefts)
      if (std::find(resized.begin(), resized.end(), left) == resized.end()) resized.push_back(left);
  // Same length replacements keep every index valid: "\left" -> "\Bigl", "\right" -> "\Bigr " ...
  // "\right" is one character longer than "\Bigr", so it becomes "\Bigr" plus a space.
  for (std::size_t left : resized) {
    const std::size_t right = matching_right(text, left);
    text.replace(left, 5, "\\Bigl");
    if (right != std::string::npos) text.replace(right, 6, "\\Bigr ");
  }
  std::string out = lhs + " &= ";
  std::size_t printed = 0;
  for (const Cut* cut : chosen) {
    out += text.substr(printed, cut->at - printed) + " \\\\\n&\\quad";
    printed = cut->at;
  }
  return out + text.substr(printed);
}

}  // namespace pfgen
