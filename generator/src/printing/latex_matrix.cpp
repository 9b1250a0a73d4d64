#include "pfgen/printing/latex_matrix.hpp"

#include <vector>

#include "pfgen/notation/latex_line_breaker.hpp"

namespace pfgen {

std::string bmatrix(const LatexPrinter& printer, const ExMatrix& m) {
  std::string out = "\\begin{bmatrix}";
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (std::size_t j = 0; j < m[i].size(); ++j) out += (j ? " & " : "") + printer.print(m[i][j]);
    out += i + 1 < m.size() ? " \\\\ " : "";
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
      lines.push_back(latex_align_lines(name + "_{" + index + "}", printer.print(m[i][j])));
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
