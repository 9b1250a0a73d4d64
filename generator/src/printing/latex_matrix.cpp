#include "pfgen/printing/latex_matrix.hpp"

#include <vector>

#include "pfgen/notation/latex_line_breaker.hpp"

namespace pfgen {

std::string bmatrix(const LatexPrinter& printer, const ExMatrix& m) {
  std::vector<std::vector<std::string>> cells;
  bool fractions = false;
  for (const auto& row : m) {
    cells.emplace_back();
    for (const auto& e : row) {
      cells.back().push_back(printer.print(e));
      fractions = fractions || cells.back().back().find("\\frac") != std::string::npos;
    }
  }
  // A matrix's cells are set in text style, where \frac{1}{3} shrinks to script-size digits and
  // rows crowd each other: a cell with a fraction is set in display style, and the rows of such a
  // matrix 1ex apart. A matrix without fractions is written as before.
  std::string out = "\\begin{bmatrix}";
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = 0; j < cells[i].size(); ++j) {
      const bool fraction = cells[i][j].find("\\frac") != std::string::npos;
      out += (j ? " & " : "") + std::string(fraction ? "\\displaystyle " : "") + cells[i][j];
    }
    out += i + 1 < cells.size() ? (fractions ? " \\\\[1ex] " : " \\\\ ") : "";
  }
  return out + "\\end{bmatrix}";
}

std::string matrix_lines(const LatexPrinter& printer, const std::string& label, const std::string& name,
                         const ExMatrix& m) {
  const std::string whole = bmatrix(printer, m);
  if (latex_width(label) + 1.8 + latex_width(whole) <= kLatexLineWidth) return label + " &= " + whole;
  const bool vector = !m.empty() && m[0].size() == 1;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < m.size(); ++i)
    for (std::size_t j = 0; j < m[i].size(); ++j) {
      if (m[i][j].is_zero()) continue;
      const std::string index = vector ? std::to_string(i + 1) : std::to_string(i + 1) + "," + std::to_string(j + 1);
      // A name with its own subscript (U_v) is braced, so that the entry's is not a second one.
      const std::string base = name.find('_') == std::string::npos ? name : "{" + name + "}";
      lines.push_back(latex_align_lines(base + "_{" + index + "}", printer.print(m[i][j])));
    }
  if (lines.empty()) return name + " &= 0";
  std::string out;
  for (std::size_t k = 0; k < lines.size(); ++k) out += lines[k] + (k + 1 < lines.size() ? " \\\\\n" : "");
  if (lines.size() < m.size() * m[0].size()) out += " \\\\\n&\\text{(other entries of $" + name + "$ are 0)}";
  return out;
}

ExMatrix column(const ExVector& v) {
  ExMatrix out;
  for (const auto& e : v) out.push_back({e});
  return out;
}

}  // namespace pfgen
