// The continuous observation dy = (A0 + A x) dt + B dW2 in the reports: the rate form
// (rate_report.hpp) with the correction P A^T (B B^T)^-1 A P, and its lines in the standalone
// document and the coefficient form.
#include "pfgen/observations/continuous/continuous_report.hpp"

#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/printing/latex_matrix.hpp"
#include "pfgen/printing/rate_report.hpp"

namespace pfgen {
namespace {

class ContinuousReport final : public RateReport, public ObservationStatement {
 public:
  std::string equation_latex(const Model&) const override { return "dy = (A_0 + A x)\\,dt + B\\,dW_2"; }

  std::string matrices_latex(const Model& model) const override {
    return rate_matrices_latex(*model.observation.rate().affine(), std::nullopt);
  }

  std::string notation_latex() const override {
    return "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state, $P_{ij}$ the error covariance, "
           "$K$ the gain $P A^{T}(B B^{T})^{-1}$ and $dy_{r}$ the observation increments. Each $dP$ is written as "
           "$E[(x-m)f^{T}] + E[f(x-m)^{T}]$ ($J P + P J^{T}$, $J$ the Jacobian of $f$ at $m$, for the extended "
           "filters), then the diffusion term, then $-P A^{T}(B B^{T})^{-1} A P$, "
           "without merging like terms across the three parts.";
  }

  std::string coefficients_text(const Model&) const override {
    return "observation: dy = (E + E1 x) dt + B dW2; E = A0, E1 = A\n";
  }

  std::string coefficients_latex(const Model&) const override {
    return "The observation's rate is $E + E_{1} x$, $dy = (E + E_{1} x)\\,dt + B\\,dW_2$: $E = A_{0}$, $E_{1} = A$.";
  }

  CoefficientNames coefficient_names() const override { return {"E", "E1", "E", "E_{1}", "(E_{1})"}; }

  void add_coefficients_json(const Model&, Json&) const override {}

 protected:
  std::string correction_words_text(const FilterEquations&) const override { return "P A^T (B B^T)^-1 A P"; }
};

const ContinuousReport& continuous_part() {
  static const ContinuousReport part;
  return part;
}

}  // namespace

std::string rate_matrices_latex(const AffineRate& observation, const std::optional<GiNaC::numeric>& delay) {
  LatexPrinter printer;
  const std::string h = delay ? ", \\quad h = " + printer.print(*delay) : "";
  const std::string observation_line = bmatrix(printer, column(observation.A0)) + ", \\quad A = " +
                                       bmatrix(printer, observation.A) + ", \\quad B = " + bmatrix(printer, observation.B) +
                                       h;
  if (latex_width("A_0 = " + observation_line) <= kLatexLineWidth) return "A_0 &= " + observation_line;
  return matrix_lines(printer, "A_0", "A_0", column(observation.A0)) + " \\\\\n" +
         matrix_lines(printer, "A", "A", observation.A) + " \\\\\n" + matrix_lines(printer, "B", "B", observation.B) +
         (delay ? " \\\\\nh &= " + printer.print(*delay) : "");
}

const ObservationReport& continuous_observation_report() { return continuous_part(); }

const ObservationStatement& continuous_observation_statement() { return continuous_part(); }

}  // namespace pfgen
