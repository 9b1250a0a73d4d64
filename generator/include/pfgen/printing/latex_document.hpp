#pragma once
// A standalone LaTeX document for `pfgen latex`: the model, then each filter's
// equations with its exactness diagnostic. Compiles with plain pdflatex
// (article class, amsmath only). `coefficients`: a section with the model's coefficient form
// (coefficient_report.hpp) after the model's; ModelError for a drift of degree above 3.
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen {

std::string latex_document(const Model& model, const std::vector<FilterEquations>& filters,
                           bool coefficients = false);

}  // namespace pfgen
