#pragma once
// Long right-hand sides over several lines of an align* environment.
//
// A dense model's equations have thousands of terms; printed on one line they ran thousands of
// points off the page. A line is cut before a top-level + or - (never inside braces, so never
// inside a \frac or an exponent) once its estimated width would pass the page's, and the cut
// lines continue aligned under the first one's right-hand side. \left( ... \right) cannot span
// lines in TeX, so a pair that encloses a cut becomes \Bigl( ... \Bigr).
//
// Widths are estimated from the LaTeX text in "characters" of an average math glyph; the default
// fits the 17 cm text width of `pfgen latex` documents (10pt, 2 cm margins) with room to spare,
// checked by rendering (tests/test_latex_layout.cpp).
#include <string>

namespace pfgen {

inline constexpr double kLatexLineWidth = 72;

// The estimated printed width of LaTeX math text, in average glyphs.
double latex_width(const std::string& math);

// "lhs &= rhs" for an align* environment, cut into lines of at most `width` (each but the last
// ending in \\ and a newline; continuation lines start "&\quad "). Unchanged when it fits.
std::string latex_align_lines(const std::string& lhs, const std::string& rhs, double width = kLatexLineWidth);

}  // namespace pfgen
