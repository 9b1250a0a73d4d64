#include "pfgen/printing/noise_report.hpp"

#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/text_printer.hpp"

namespace pfgen {
namespace {

bool stratonovich(const Model& model) { return model.noise == NoiseCalculus::Stratonovich; }

}  // namespace

std::string noise_text(const Model& model) {
  if (!stratonovich(model)) return "";
  TextPrinter printer;
  std::string out =
      "noise: stratonovich (dx = f dt + g o dW); the equations use the Ito drift f + c, "
      "c_i = 1/2 sum_jk g_jk d(g_ik)/d(x_j)\n";
  for (std::size_t i = 0; i < model.n(); ++i) {
    const std::string k = std::to_string(i + 1);
    out += "  f" + k + " = " + printer.print(model.stated_drift[i]) + ";  c" + k + " = " +
           printer.print(model.noise_correction[i]) + ";  f" + k + " + c" + k + " = " + printer.print(model.drift[i]) +
           "\n";
  }
  return out;
}

std::string noise_latex(const Model& model) {
  if (!stratonovich(model)) return "";
  LatexPrinter printer;
  std::string out =
      "\\noindent\\textbf{Noise:} Stratonovich, $dx = f\\,dt + g \\circ dW_1$; the equations use the It\\^o drift "
      "$f + c$, $c_i = \\tfrac{1}{2}\\sum_{j,k} g_{jk}\\,\\partial g_{ik}/\\partial x_j$.\n\\begin{align*}\n";
  for (std::size_t i = 0; i < model.n(); ++i) {
    const std::string k = std::to_string(i + 1);
    out += latex_align_lines("f_{" + k + "}", printer.print(model.stated_drift[i])) + " \\\\\n";
    out += latex_align_lines("c_{" + k + "}", printer.print(model.noise_correction[i])) + " \\\\\n";
    out += latex_align_lines("f_{" + k + "} + c_{" + k + "}", printer.print(model.drift[i])) +
           (i + 1 < model.n() ? " \\\\\n" : "\n");
  }
  return out + "\\end{align*}\n";
}

void add_noise_json(const Model& model, Json& out) {
  if (!stratonovich(model)) return;
  TextPrinter printer;
  auto column = [&](const ExVector& v) {
    Json a = Json::array();
    for (const auto& e : v) a.push(Json::string(printer.print(e)));
    return a;
  };
  Json noise = Json::object();
  noise.add("calculus", Json::string("stratonovich"));
  noise.add("drift_as_written", column(model.stated_drift));
  noise.add("correction", column(model.noise_correction));
  noise.add("ito_drift", column(model.drift));
  out.add("noise", noise);
}

}  // namespace pfgen
