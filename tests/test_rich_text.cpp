// Rich text (notation/rich_text.hpp): one string, two spellings. The text side is what derive's
// text and JSON print, byte for byte; the LaTeX side escapes the prose and typesets each math span.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "pfgen/derivation/exactness.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/rich_text.hpp"

using namespace pfgen;

TEST_CASE("rich text: the text side keeps the plain spelling, LaTeX typesets the math and escapes the prose",
          "[unit][latex]") {
  const std::string rich = "gain $P Phi*^T A^T R^-1|P\\,\\Phi^{*T} A^{T} R^{-1}$ (Basin & Skliar; 50% of $x_1|x_{1}$)";
  CHECK(rich_text_plain(rich) == "gain P Phi*^T A^T R^-1 (Basin & Skliar; 50% of x_1)");
  CHECK(rich_text_latex(rich) == "gain $P\\,\\Phi^{*T} A^{T} R^{-1}$ (Basin \\& Skliar; 50\\% of $x_{1}$)");
  // A literal '|' in the plain side, a '$' in prose.
  CHECK(rich_text_plain("$E[x \\| y]|E[x \\mid y]$ costs \\$1") == "E[x | y] costs $1");
  CHECK(rich_text_latex("$E[x \\| y]|E[x \\mid y]$ costs \\$1") == "$E[x \\mid y]$ costs \\$1");
  // No markup: unchanged in text.
  CHECK(rich_text_plain("no math here") == "no math here");
  CHECK(rich_text_latex("h > 0 | x <= y") == "h \\textgreater{} 0 \\textbar{} x \\textless{}= y");
}

TEST_CASE("rich text: a user's words go through rich_text_literal and print as written", "[unit][latex]") {
  for (const std::string& text : {std::string("plain"), std::string("costs $5 | $6 \\ or \"7\""),
                                 std::string("$a|b$"), std::string("\\"), std::string("")}) {
    INFO(text);
    CHECK(rich_text_plain(rich_text_literal(text)) == text);
    CHECK(rich_text_latex(rich_text_literal(text)) == latex_escape_text(text));
  }
}

TEST_CASE("rich text: malformed markup in a built-in string is a programming error", "[unit][latex]") {
  for (const char* bad : {"$x$", "$x|x", "trailing \\", "$|x$", "$x|$", "$x \\"}) {
    INFO(bad);
    CHECK_THROWS_AS(rich_text_plain(bad), std::logic_error);
    CHECK_THROWS_AS(rich_text_latex(bad), std::logic_error);
  }
}

TEST_CASE("rich text: every built-in description is well formed and names no paper by number", "[unit][latex][kinds]") {
  for (const FilterKindInfo& info : filter_kinds()) {
    INFO(info.name);
    const std::string plain = rich_text_plain(info.description);
    const std::string latex = rich_text_latex(info.description);
    CHECK(plain.find("paper 0") == std::string::npos);
    // The LaTeX side is balanced math: an even number of '$' outside escapes.
    std::size_t dollars = 0;
    for (std::size_t k = 0; k < latex.size(); ++k)
      if (latex[k] == '$' && (k == 0 || latex[k - 1] != '\\')) ++dollars;
    CHECK(dollars % 2 == 0);
  }
}
