#pragma once
// The report of a sampled-observation filter (cd-optimal, cd-ekf, cd-euler): its prediction
// between samples and its update at each sample, shown separately, as text, LaTeX and JSON.
// equation_report.hpp's functions hand sampled filters to these.
#include <string>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

std::string sampled_equations_text(const Model& model, const FilterEquations& eq);
std::string sampled_equations_latex(const FilterEquations& eq);
Json sampled_equations_json(const Model& model, const FilterEquations& eq);

}  // namespace pfgen
