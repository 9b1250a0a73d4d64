#pragma once
// A standalone LaTeX document for `pfgen latex`: the model, then each filter's
// equations with its exactness diagnostic. Compiles with plain pdflatex
// (article class, amsmath only).
#include <string>
#include <vector>

#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen {

std::string latex_document(const Model& model, const std::vector<FilterEquations>& filters);

}  // namespace pfgen
