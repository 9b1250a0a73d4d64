#include "pfgen/printing/report_parts.hpp"

#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/rich_text.hpp"

namespace pfgen {

void append_parts(std::string& out, PolynomialWriter& writer, const std::vector<ReportPart>& parts) {
  bool empty = true;
  for (const ReportPart& part : parts) {
    if (part.polynomial->is_zero()) continue;
    // After the first part, its first sign joins the sum (" - 0.5*m1", not " + -0.5*m1").
    writer.append(out, *part.polynomial, part.negated, !empty);
    empty = false;
  }
  if (empty) out += "0";
}

std::string join_parts(PolynomialWriter& writer, const std::vector<ReportPart>& parts) {
  std::string out;
  append_parts(out, writer, parts);
  return out;
}

std::string moment_terms_text(const FilterEquations& eq) {
  if (eq.kind && is_extended_kalman(*eq.kind)) return "J P + P J^T, J = df/dx at m";
  return "E[(x-m)f^T] + E[f(x-m)^T]";
}

std::string exactness_text(const ExactnessReport& report) {
  std::string out = rich_text_plain(report.explanation);
  for (const auto& failed : report.failed) out += "\n  failed: " + rich_text_plain(failed);
  return out;
}

std::string exactness_latex(const ExactnessReport& report) {
  std::string out = "\\noindent\\textbf{Exactness:} " + rich_text_latex(report.explanation) + ".\n";
  if (!report.failed.empty()) {
    out += "\\begin{itemize}\n";
    for (const auto& f : report.failed) out += "\\item " + rich_text_latex(f) + "\n";
    out += "\\end{itemize}\n";
  }
  return out;
}

Json exactness_json(const ExactnessReport& report) {
  Json exactness = Json::object();
  exactness.add("exact", Json::boolean(report.exact));
  exactness.add("condition", Json::string(report.condition));
  exactness.add("explanation", Json::string(rich_text_plain(report.explanation)));
  Json failed = Json::array();
  for (const auto& f : report.failed) failed.push(Json::string(rich_text_plain(f)));
  exactness.add("failed", failed);
  return exactness;
}

std::string latex_variable_name(const FilterVariables& vars, std::uint32_t variable) {
  const std::string& name = vars.latex_name(variable);
  return variable < vars.count() ? name : "{" + name + "}";
}

}  // namespace pfgen
