#pragma once
// How a report lists a user filter's auxiliary names (`define:`, FilterEquations::definitions):
// before the equations, in the order they are computed, each as NAME = value. A filter without
// definitions gets nothing, so every other report is unchanged.
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// Text: "definitions (computed in this order before the equations):\n" and one
// "  NAME = value\n" line each, then "\n"; empty without definitions.
std::string definitions_text(const FilterEquations& eq);
// LaTeX: one align line "NAME &= value" each (latex_align_lines), in order.
std::vector<std::string> definitions_latex_lines(const FilterEquations& eq);
// JSON: adds "definitions": [{"name", "value"}, ...] when there are any.
void add_definitions_json(const FilterEquations& eq, Json& out);

}  // namespace pfgen
