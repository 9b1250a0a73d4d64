// Long equations stay on the page: latex_line_breaker cuts right-hand sides at top-level signs
// only, and a dense 6-state model's document (every filter kind) compiles with no overfull line
// and, rendered to pixels by pdftoppm, has ink only inside the text block on every page.
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "pfgen/notation/latex_line_breaker.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen_test;
using pfgen::kLatexLineWidth;
using pfgen::latex_align_lines;
using pfgen::latex_width;

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

// A binary PGM (P5, maxval 255) as pdftoppm -gray writes it.
struct Image {
  int width = 0, height = 0;
  std::string pixels;
};

Image read_pgm(const std::string& path) {
  const std::string data = read_file(path);
  std::istringstream in(data);
  std::string magic;
  int maxval = 0;
  Image image;
  in >> magic >> image.width >> image.height >> maxval;
  in.get();  // the single whitespace before the raster
  REQUIRE(magic == "P5");
  REQUIRE(maxval == 255);
  image.pixels = data.substr(static_cast<std::size_t>(in.tellg()));
  REQUIRE(image.pixels.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  return image;
}

}  // namespace

TEST_CASE("latex_align_lines leaves a line that fits and cuts a long one at top-level signs", "[latex][unit]") {
  CHECK(latex_align_lines("dm_{1}", "\\left(0.1\\,m_{1}^{2}\\right)dt") == "dm_{1} &= \\left(0.1\\,m_{1}^{2}\\right)dt");

  std::string sum = "\\frac{1}{3}\\,m_{1}^{2}";
  for (int k = 2; k <= 60; ++k) sum += " - \\frac{" + std::to_string(k) + "}{7}\\,m_{1}\\,P_{1" + std::to_string(k % 9 + 1) + "}";
  const std::string rhs = "\\left(" + sum + "\\right)dt + K_{1,1}\\left(dy_{1} - m_{1}\\,dt\\right)";
  const std::string cut = latex_align_lines("dm_{1}", rhs);
  const std::vector<std::string> lines = split_lines(cut);
  REQUIRE(lines.size() > 3);
  // Every line fits; each continuation starts with "&\quad" and a sign; each but the last ends in \\.
  for (std::size_t k = 0; k < lines.size(); ++k) {
    INFO(lines[k]);
    CHECK(latex_width(lines[k]) <= kLatexLineWidth);
    if (k > 0) CHECK(std::regex_search(lines[k], std::regex("^&\\\\quad [+-] ")));
    if (k + 1 < lines.size()) CHECK(lines[k].substr(lines[k].size() - 3) == " \\\\");
  }
  // The parentheses around the cut sum may span lines; the gain's own, on one line, stay \left.
  CHECK(cut.find("\\Bigl(\\frac{1}{3}") != std::string::npos);
  CHECK(cut.find("\\Bigr )dt") != std::string::npos);
  CHECK(cut.find("K_{1,1}\\left(dy_{1} - m_{1}\\,dt\\right)") != std::string::npos);
  // Nothing lost: joining the lines back gives the terms in order.
  std::string joined = std::regex_replace(cut, std::regex(" \\\\\\\\\\n&\\\\quad"), "");
  joined = std::regex_replace(joined, std::regex("\\\\Bigl"), "\\left");
  joined = std::regex_replace(joined, std::regex("\\\\Bigr "), "\\right");
  CHECK(joined == "dm_{1} &= " + rhs);
  // Never inside braces: a long exponent or fraction is one unbreakable term.
  std::string exponent;
  for (int k = 0; k < 80; ++k) exponent += " + a_{" + std::to_string(k) + "}";
  CHECK(latex_align_lines("K_{1,1}", "x^{1" + exponent + "}") == "K_{1,1} &= x^{1" + exponent + "}");
}

TEST_CASE("a dense 6-state model's LaTeX document stays inside the page, checked by rendering it",
          "[latex][pdflatex][compiler]") {
  REQUIRE(run_process("command -v pdflatex").exit_code == 0);
  REQUIRE(run_process("command -v pdftoppm").exit_code == 0);  // poppler-utils
  TempDir dir;
  const std::string tex = dir.file("dense6.tex");
  const ProcessResult written = run_pfgen({"latex", test_data_dir() + "/dense6_layout.yaml", "-o", tex});
  INFO(written.err);
  REQUIRE(written.exit_code == 0);
  const ProcessResult compiled = run_process("cd " + shell_quote(dir.path()) +
                                             " && pdflatex -interaction=nonstopmode -halt-on-error dense6.tex </dev/null");
  const std::string log = read_file(dir.file("dense6.log"));
  REQUIRE(compiled.exit_code == 0);
  // TeX's own judgement: no line wider than the text block.
  CHECK(log.find("Overfull \\hbox") == std::string::npos);

  // And the pixels': 2 cm margins are 31.5 pixels at 40 dpi; ink may come no nearer the edge
  // than 25 pixels on the left or right of any page.
  REQUIRE(run_process("cd " + shell_quote(dir.path()) + " && pdftoppm -r 40 -gray dense6.pdf page").exit_code == 0);
  int pages = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    if (entry.path().extension() != ".pgm") continue;
    ++pages;
    const Image page = read_pgm(entry.path().string());
    int outside = 0;
    for (int y = 0; y < page.height; ++y)
      for (int x = 0; x < page.width; ++x)
        if ((x < 25 || x >= page.width - 25) &&
            static_cast<unsigned char>(page.pixels[static_cast<std::size_t>(y * page.width + x)]) < 160)
          ++outside;
    INFO(entry.path().filename().string());
    CHECK(outside == 0);
  }
  // The document has the model and all four filter kinds of the model: many pages.
  CHECK(pages > 20);
}
