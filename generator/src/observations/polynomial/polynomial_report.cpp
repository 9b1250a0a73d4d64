// The polynomial observation dy = h(x, t) dt + B dW2 in the reports: a nonlinear h's filters in the
// rate form (rate_report.hpp), whose dP lines carry the covariance's own innovation term
// L (dy - E[h] dt), with the correction P E[J]^T (B B^T)^-1 E[J] P (a linear h's filters are the
// continuous module's report); and rows h as written in the standalone document and (for a linear
// h) the coefficient form.
#include "pfgen/notation/latex_line_breaker.hpp"
#include "pfgen/notation/latex_printer.hpp"
#include "pfgen/printing/latex_matrix.hpp"
#include "pfgen/printing/rate_report.hpp"

namespace pfgen {
namespace {

class PolynomialReport final : public RateReport, public ObservationStatement {
 public:
  std::string equation_latex(const Model&) const override { return "dy = h(x, t)\\,dt + B\\,dW_2"; }

  std::string matrices_latex(const Model& model) const override {
    const ObservationRate& rate = model.observation.rate();
    LatexPrinter printer;
    const std::string line = bmatrix(printer, column(rate.rows())) + ", \\quad B = " + bmatrix(printer, rate.noise());
    if (latex_width("h = " + line) <= kLatexLineWidth) return "h &= " + line;
    return matrix_lines(printer, "h", "h", column(rate.rows())) + " \\\\\n" +
           matrix_lines(printer, "B", "B", rate.noise());
  }

  std::string notation_latex() const override {
    return "\\paragraph{Notation.} $m_{i}$ is the estimate of the $i$-th state, $P_{ij}$ the error covariance, "
           "$K$ the gain $P E[J_h]^{T}(B B^{T})^{-1}$ ($J_h$ the Jacobian of $h$; at $m$ for the extended filter), "
           "$dy_{r}$ the observation increments and $L_{ij,r}$ the coefficient of $dy_{r} - E[h_{r}]\\,dt$ in "
           "$dP_{ij}$, $\\sum_k (P E[H_k] P)_{ij} (B B^{T})^{-1}_{kr}$ with $H_k$ the Hessian of $h_k$. Each $dP$ "
           "is written as $E[(x-m)f^{T}] + E[f(x-m)^{T}]$ ($J P + P J^{T}$, $J$ the Jacobian of $f$ at $m$, for "
           "the extended filters), then the diffusion term, then "
           "$-P E[J_h]^{T}(B B^{T})^{-1} E[J_h] P$, without merging like terms across the three parts.";
  }

  // Reached for a linear h only: the derivation refuses the coefficient form of a nonlinear one.
  std::string coefficients_text(const Model&) const override {
    return "observation: dy = (E + E1 x) dt + B dW2; h = E + E1 x\n";
  }

  std::string coefficients_latex(const Model&) const override {
    return "The observation's rate is $h = E + E_{1} x$, $dy = (E + E_{1} x)\\,dt + B\\,dW_2$.";
  }

  CoefficientNames coefficient_names() const override { return {"E", "E1", "E", "E_{1}", "(E_{1})"}; }

  void add_coefficients_json(const Model&, Json&) const override {}

 protected:
  // A nonlinear h's only: a linear h's filters are the continuous module's report (observation_report).
  std::string correction_words_text(const FilterEquations& eq) const override {
    if (eq.kind && uses_sigma_points(*eq.kind)) return "C (B B^T)^-1 C^T, C = sum_i w_i (X_i-m) h(X_i)^T";
    return eq.kind && is_extended_kalman(*eq.kind) ? "P J_h(m)^T (B B^T)^-1 J_h(m) P"
                                                   : "P E[J_h]^T (B B^T)^-1 E[J_h] P";
  }

  std::string sigma_point_correction_latex(const FilterEquations&) const override {
    return "C (B B^T)^{-1} C^T$ with $C = \\sum_i w_i (X_i - m) h(X_i)^T";
  }
};

const PolynomialReport& polynomial_part() {
  static const PolynomialReport part;
  return part;
}

}  // namespace

const ObservationReport& polynomial_observation_report() { return polynomial_part(); }

const ObservationStatement& polynomial_observation_statement() { return polynomial_part(); }

}  // namespace pfgen
