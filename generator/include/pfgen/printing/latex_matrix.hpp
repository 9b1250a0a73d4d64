#pragma once
// Matrices and vectors of expressions in LaTeX math, shared by the reports that show a model's
// matrices (latex_document's model section, coefficient_report).
#include <string>

#include "pfgen/model/expression_matrix.hpp"
#include "pfgen/notation/latex_printer.hpp"

namespace pfgen {

// \begin{bmatrix} a & b \\ c & d \end{bmatrix}
std::string bmatrix(const LatexPrinter& printer, const ExMatrix& m);

// "label &= [matrix]" when it fits the page, else one aligned line per nonzero entry (cut in turn
// when long), so that every term of a dense model's f and g is on the page.
// `label` heads the whole matrix ("G = g g^{T}"), `name` its entries (G_{1,2}).
std::string matrix_lines(const LatexPrinter& printer, const std::string& label, const std::string& name,
                         const ExMatrix& m);

// A vector as an n x 1 matrix.
ExMatrix column(const ExVector& v);

}  // namespace pfgen
