// The delayed observation dy = (A0 + A x(t-h)) dt + B dW2 in the reports (docs/theory.md §2.6): the
// rate form (rate_report.hpp) with what a delayed filter adds to it, the delay h and the
// observation of x(t-h), what the delayed inputs md_i = m_i(t-h) mean (m0 for t < h), and for the
// kinds with the Phi* gain the definition of phi_i = Phi*_ii and the auxiliary ODE
// dxs = f(xs, t) dt, xs(0) = m0; and its lines in the standalone document and the coefficient form.
#include <functional>

#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/notation/text_printer.hpp"
#include "pfgen/observations/continuous/continuous_report.hpp"
#include "pfgen/printing/rate_report.hpp"
#include "pfgen/printing/report_parts.hpp"

namespace pfgen {
namespace {

std::string index(std::size_t i) { return std::to_string(i + 1); }

// "md1 = m1(t-h), md2 = m2(t-h)" or the LaTeX names, for every state.
std::string list(std::size_t n, const std::function<std::string(std::size_t)>& item) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + item(i);
  return out;
}

// The correction term's words; Phi* = diag(phi) is diagonal, so Phi*^T = Phi*.
std::string correction_words(const FilterEquations& eq) {
  return eq.uses_x_star() ? "P Phi* A^T (B B^T)^-1 A Phi* P" : "P A^T (B B^T)^-1 A P";
}

std::string delayed_header_text(const FilterEquations& eq) {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  std::string out = "observation: delayed by h = " + printer.print(eq.delay) +
                    ", dy = (A0 + A x(t-h)) dt + B dW2 (before t = h the sensor sees x(0))\n";
  out += "delayed inputs: " + list(n, [&](std::size_t i) {
           return vars.text_name(vars.m_delayed(i)) + " = " + vars.text_name(vars.m(i)) + "(t-h)";
         });
  out += std::string(n == 1 ? ", the filter's own estimate" : ", the filter's own estimates") +
         " h earlier (m0 for t < h)\n";
  if (eq.uses_x_star()) {
    out += "Phi* = diag(" + list(n, [&](std::size_t i) { return vars.text_name(vars.phi(i)); }) +
           "): phi_i = xs_i(t-h)/xs_i(t) for t >= h, 0 where xs_i(t) = 0, and 0 for t < h;\n";
    out += "  xs = x*, the noise-free solution of dxs = f(xs, t) dt from xs(0) = m0 (last equations)\n";
  }
  return out;
}

std::string x_star_equations_text(const FilterEquations& eq) {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  std::string out;
  for (std::size_t i = 0; i < eq.x_star_drift.size(); ++i)
    out += "d" + vars.text_name(vars.x_star(i)) + " = (" + printer.print(eq.x_star_drift[i], name) + ") dt\n";
  return out;
}

std::string delayed_paragraph_latex(const FilterEquations& eq) {
  LatexPrinter printer;
  const FilterVariables& vars = eq.variables;
  const std::size_t n = eq.n();
  std::string out = "\\paragraph{Delayed observation.} $dy = (A_0 + A x(t-h))\\,dt + B\\,dW_2$ with $h = " +
                    printer.print(eq.delay) + "$ (before $t = h$ the sensor sees $x(0)$). ";
  out += "$m_{i}(t-h)$ is the filter's own estimate $m_{i}$ at time $t - h$, and $m_{i}(0)$ for $t < h$.";
  if (eq.uses_x_star()) {
    out += " The gain is $P \\Phi^{*} A^{T}(B B^{T})^{-1}$ with $\\Phi^{*} = \\mathrm{diag}(" +
           list(n, [&](std::size_t i) { return latex_variable_name(vars, vars.phi(i)); }) + ")$, ";
    out += "$\\Phi^*_{i} = x^*_{i}(t-h) / x^*_{i}(t)$ for $t \\ge h$, $0$ where $x^*_{i}(t) = 0$, and $0$ for $t < h$; "
           "$x^{*}$ is the noise-free solution of $dx^{*} = f(x^{*}, t)\\,dt$ from $x^{*}(0) = m_0$ "
           "(the last equations below).";
  }
  return out + "\n";
}

std::vector<std::string> x_star_lines_latex(const FilterEquations& eq) {
  LatexPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return latex_variable_name(vars, v); };
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < eq.x_star_drift.size(); ++i)
    lines.push_back(latex_align_lines("\\frac{d" + name(vars.x_star(i)) + "}{dt}", printer.print(eq.x_star_drift[i], name)));
  return lines;
}

void add_delayed_json(const FilterEquations& eq, Json& out) {
  TextPrinter printer;
  const FilterVariables& vars = eq.variables;
  auto name = [&](std::uint32_t v) { return vars.text_name(v); };
  const std::size_t n = eq.n();
  out.add("delay", Json::string(printer.print(eq.delay)));
  Json delayed = Json::object();
  for (std::size_t i = 0; i < n; ++i) {
    const std::string m = vars.text_name(vars.m(i));
    delayed.add(vars.text_name(vars.m_delayed(i)), Json::string(m + "(t-h), and " + m + "(0) for t < h"));
  }
  if (eq.uses_x_star()) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::string xs = vars.text_name(vars.x_star(i));
      delayed.add(vars.text_name(vars.phi(i)),
                  Json::string(xs + "(t-h)/" + xs + "(t) for t >= h, 0 where " + xs + "(t) = 0, and 0 for t < h"));
    }
    for (std::size_t i = 0; i < n; ++i)
      delayed.add(vars.text_name(vars.x_star(i)),
                  Json::string("x*_" + index(i) + ": d" + vars.text_name(vars.x_star(i)) + " = x_star_drift[" + index(i) +
                               "] dt from " + vars.text_name(vars.x_star(i)) + "(0) = " + vars.text_name(vars.m(i)) +
                               "(0)"));
  }
  out.add("delayed_variables", delayed);
  if (eq.uses_x_star()) {
    Json drift = Json::array();
    for (const auto& p : eq.x_star_drift) drift.push(Json::string(printer.print(p, name)));
    out.add("x_star_drift", drift);
  }
}

class DelayedReport final : public RateReport, public ObservationStatement {
 public:
  std::string equation_latex(const Model&) const override { return "dy = (A_0 + A x(t-h))\\,dt + B\\,dW_2"; }

  std::string matrices_latex(const Model& model) const override {
    return rate_matrices_latex(*model.observation.rate().affine(), model.observation.delay_h());
  }

  std::string notation_latex() const override {
    return "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state, $P_{ij}$ the error covariance, "
           "$K$ the gain and $dy_{r}$ the observation increments; the innovation compares $dy$ with the estimate "
           "$m(t-h)$ of the delayed state. Each $dP$ is written as $E[(x-m)f^{T}] + E[f(x-m)^{T}]$ "
           "($J P + P J^{T}$, $J$ the Jacobian of $f$ at $m$, for the extended filters), then the "
           "diffusion term, then the correction $-K A \\Phi^{*} P$ (with $\\Phi^{*} = I$ for the filters without "
           "$\\Phi^{*}$), without merging like terms across the three parts.";
  }

  std::string coefficients_text(const Model& model) const override {
    TextPrinter printer;
    return "observation: dy = (E + E1 x(t-h)) dt + B dW2 with h = " + printer.print(model.observation.delay()) +
           "; E = A0, E1 = A\n";
  }

  std::string coefficients_latex(const Model& model) const override {
    LatexPrinter printer;
    return "The observation's rate is $E + E_{1} x(t-h)$, $dy = (E + E_{1} x(t-h))\\,dt + B\\,dW_2$ with $h = " +
           printer.print(model.observation.delay()) + "$: $E = A_{0}$, $E_{1} = A$.";
  }

  CoefficientNames coefficient_names() const override { return {"E", "E1", "E", "E_{1}", "(E_{1})"}; }

  void add_coefficients_json(const Model& model, Json& observation) const override {
    TextPrinter printer;
    observation.add("delay", Json::string(printer.print(model.observation.delay())));
  }

 protected:
  std::string correction_words_text(const FilterEquations& eq) const override { return correction_words(eq); }
  std::string header_text(const FilterEquations& eq) const override { return delayed_header_text(eq); }
  std::string trailing_text(const FilterEquations& eq) const override { return x_star_equations_text(eq); }
  std::string paragraph_latex(const FilterEquations& eq) const override { return delayed_paragraph_latex(eq); }
  std::vector<std::string> trailing_latex(const FilterEquations& eq) const override { return x_star_lines_latex(eq); }
  void add_json(const FilterEquations& eq, Json& out) const override { add_delayed_json(eq, out); }
};

const DelayedReport& delayed_part() {
  static const DelayedReport part;
  return part;
}

}  // namespace

const ObservationReport& delayed_observation_report() { return delayed_part(); }

const ObservationStatement& delayed_observation_statement() { return delayed_part(); }

}  // namespace pfgen
