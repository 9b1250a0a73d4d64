#include "pfgen/printing/report_parts.hpp"

#include "pfgen/notation/latex_printer.hpp"

namespace pfgen {

std::string join_parts(const ExpressionPrinter& printer, const std::vector<Polynomial>& parts,
                       const ExpressionPrinter::VariableNamer& name) {
  std::string out;
  for (const auto& part : parts) {
    if (part.is_zero()) continue;
    std::string text = printer.print(part, name);
    if (out.empty()) {
      out = text;
    } else if (text[0] == '-') {
      out += " - " + text.substr(1);
    } else {
      out += " + " + text;
    }
  }
  return out.empty() ? "0" : out;
}

std::string exactness_text(const ExactnessReport& report) {
  std::string out = report.explanation;
  for (const auto& failed : report.failed) out += "\n  failed: " + failed;
  return out;
}

std::string exactness_latex(const ExactnessReport& report) {
  std::string out = "\\noindent\\textbf{Exactness:} " + latex_escape_text(report.explanation) + ".\n";
  if (!report.failed.empty()) {
    out += "\\begin{itemize}\n";
    for (const auto& f : report.failed) out += "\\item " + latex_escape_text(f) + "\n";
    out += "\\end{itemize}\n";
  }
  return out;
}

Json exactness_json(const ExactnessReport& report) {
  Json exactness = Json::object();
  exactness.add("exact", Json::boolean(report.exact));
  exactness.add("condition", Json::string(report.condition));
  exactness.add("explanation", Json::string(report.explanation));
  Json failed = Json::array();
  for (const auto& f : report.failed) failed.push(Json::string(f));
  exactness.add("failed", failed);
  return exactness;
}

}  // namespace pfgen
