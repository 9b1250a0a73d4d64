#include "pfgen/printing/definitions_report.hpp"

#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/text_printer.hpp"

namespace pfgen {

std::string definitions_text(const FilterEquations& eq) {
  if (eq.definitions.empty()) return "";
  TextPrinter printer;
  std::string out = "definitions (computed in this order before the equations):\n";
  for (const auto& d : eq.definitions) out += "  " + d.name.get_name() + " = " + printer.print(d.value) + "\n";
  return out + "\n";
}

std::vector<std::string> definitions_latex_lines(const FilterEquations& eq) {
  LatexPrinter printer;
  std::vector<std::string> lines;
  for (const auto& d : eq.definitions)
    lines.push_back(latex_align_lines(printer.name(d.name.get_name()), printer.print(d.value)));
  return lines;
}

void add_definitions_json(const FilterEquations& eq, Json& out) {
  if (eq.definitions.empty()) return;
  TextPrinter printer;
  Json definitions = Json::array();
  for (const auto& d : eq.definitions) {
    Json entry = Json::object();
    entry.add("name", Json::string(d.name.get_name()));
    entry.add("value", Json::string(printer.print(d.value)));
    definitions.push(entry);
  }
  out.add("definitions", definitions);
}

}  // namespace pfgen
