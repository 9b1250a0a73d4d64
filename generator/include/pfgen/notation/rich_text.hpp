#pragma once
// Prose with mathematics, written once for every output: filter kind descriptions and exactness
// explanations. A math span `$plain|latex$` carries both spellings of one formula: the text
// outputs (derive's text and JSON) keep `plain`, LaTeX typesets `latex` as $latex$ and the prose
// around it escaped as text. In the prose and in `plain` a backslash takes the next character
// literally (`\$`, `\|`, `\\`); `latex` is raw LaTeX math up to the closing `$`.
//
//   "gain $P Phi*^T A^T R^-1|P \Phi^{*\top} A^{\top} R^{-1}$ ..."
//     text:  gain P Phi*^T A^T R^-1 ...
//     LaTeX: gain $P \Phi^{*\top} A^{\top} R^{-1}$ ...
#include <string>
#include <string_view>

namespace pfgen {

// The text spelling: prose and the plain side of each math span, unescaped.
std::string rich_text_plain(std::string_view rich);

// The LaTeX spelling: prose through latex_escape_text, each math span's LaTeX side in $...$.
std::string rich_text_latex(std::string_view rich);

// Text with no markup (a user's description, a state's name) as rich text that renders as written:
// rich_text_plain(rich_text_literal(t)) == t, and LaTeX escapes every character of t.
std::string rich_text_literal(std::string_view text);

}  // namespace pfgen
