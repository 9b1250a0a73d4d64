#include "pfgen/observations/continuous/continuous_exactness.hpp"

#include <set>

#include "pfgen/derivation/exactness_facts.hpp"

namespace pfgen {
namespace {

// The published conditions' short labels (ExactnessReport::condition, and the prefix of a failed one).
constexpr const char* kBasinPerezSkliar = "Basin-Perez-Skliar 2006";
constexpr const char* kBasinPerezSkliarLinear = "Basin-Perez-Skliar 2006 linear case";
constexpr const char* kBasinSkliar = "Basin-Skliar";

std::string join_indices(const std::vector<std::size_t>& indices, const Model& model) {
  std::string out;
  for (std::size_t k = 0; k < indices.size(); ++k) out += (k ? ", " : "") + model.state_names[indices[k]];
  return out;
}

GiNaC::ex determinant(const ExMatrix& m, const std::vector<std::size_t>& rows,
                      const std::vector<std::size_t>& columns) {
  GiNaC::matrix sub(static_cast<unsigned>(rows.size()), static_cast<unsigned>(columns.size()));
  for (unsigned i = 0; i < rows.size(); ++i)
    for (unsigned j = 0; j < columns.size(); ++j) sub(i, j) = m[rows[i]][columns[j]];
  return sub.determinant().expand();
}

std::string square_invertible_A(const Model& model) {
  if (model.p() != model.n())
    return "$A|A$ is $" + std::to_string(model.p()) + " x " + std::to_string(model.n()) + "|" +
           std::to_string(model.p()) + " \\times " + std::to_string(model.n()) + "$, not square";
  std::vector<std::size_t> all(model.n());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (determinant(model.observation.rate().affine()->A, all, all).is_zero()) return "$A|A$ is singular";
  return {};
}

// Basin & Skliar: x = (x1, x2) where x2 has its own linear dynamics independent of
// x1, x1 is measured through a square invertible block A1, A and B B^T are
// block-diagonal and the noise is additive. The split tried is the largest
// self-contained set of affine components (x2), the rest being x1.
std::string partially_measured_split(const ExactnessFacts& facts) {
  const Model& model = facts.model;
  const std::size_t n = model.n();
  std::set<std::size_t> linear;
  for (std::size_t i = 0; i < n; ++i)
    if (facts.f[i].degree() <= 1) linear.insert(i);
  for (bool changed = true; changed;) {
    changed = false;
    for (auto it = linear.begin(); it != linear.end();) {
      bool leaves = false;
      for (const auto& term : facts.f[*it].terms())
        for (const auto& factor : term.first.factors())
          if (!linear.count(factor.first)) leaves = true;
      if (leaves) {
        it = linear.erase(it);
        changed = true;
      } else {
        ++it;
      }
    }
  }
  std::vector<std::size_t> x1, x2(linear.begin(), linear.end());
  for (std::size_t i = 0; i < n; ++i)
    if (!linear.count(i)) x1.push_back(i);
  if (x1.empty()) return "no nonlinear components";
  if (x2.empty()) return "no components with their own linear dynamics to leave unmeasured";
  if (std::string noise = facts.state_dependent_noise(); !noise.empty()) return noise;

  const ExMatrix& A = model.observation.rate().affine()->A;
  std::vector<std::size_t> rows1, rows2;
  for (std::size_t r = 0; r < model.p(); ++r) {
    bool sees_x1 = false, sees_x2 = false;
    for (std::size_t i : x1) sees_x1 = sees_x1 || !A[r][i].is_zero();
    for (std::size_t i : x2) sees_x2 = sees_x2 || !A[r][i].is_zero();
    if (sees_x1 && sees_x2)
      return "observation row " + std::to_string(r + 1) + " mixes nonlinear (" + join_indices(x1, model) +
             ") and linear (" + join_indices(x2, model) + ") components: $A|A$ is not block-diagonal";
    (sees_x1 ? rows1 : rows2).push_back(r);
  }
  if (rows1.size() != x1.size())
    return "the nonlinear components (" + join_indices(x1, model) + ") are seen by " + std::to_string(rows1.size()) +
           " observation rows, so $A1|A_1$ is not square";
  if (determinant(A, rows1, x1).is_zero()) return "the block $A1|A_1$ measuring (" + join_indices(x1, model) + ") is singular";
  ExMatrix R = multiply_by_transpose(model.observation.rate().affine()->B);
  for (std::size_t a : rows1)
    for (std::size_t b : rows2)
      if (!R[a][b].is_zero()) return "observation noises of $y1|y_1$ and $y2|y_2$ are correlated ($B B^T|B B^{T}$ not block-diagonal)";
  return {};
}

}  // namespace

ExactnessReport continuous_exactness(const Model& model, FilterKind kind) {
  ExactnessFacts facts(model, kind);
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  const std::string suffix =
      uses_additive_diffusion(kind) ? " (for the model with its additive diffusion in place of $g|g$)" : "";

  if (nonaffine.empty() && multiplicative.empty()) {
    report.exact = true;
    report.condition = "Kalman-Bucy";
    report.explanation =
        "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so this is the Kalman-Bucy filter" + suffix;
    return report;
  }
  std::string kalman_failure = !nonaffine.empty() ? nonaffine : multiplicative;
  if (is_extended_kalman(kind)) {
    report.condition = "none";
    report.explanation = "approximation: the extended Kalman-Bucy filter linearises $f|f$ at $m|m$; it is exact "
                         "only in the Kalman-Bucy case" + suffix;
    report.failed.push_back("Kalman-Bucy: " + kalman_failure);
    return report;
  }
  // Basin, Perez & Skliar 2006 and Basin & Skliar pass from their eq 5 to eq 6 by dropping the third
  // central moment, which needs x - m conditionally Gaussian. With state-
  // dependent noise that is the paper's claim rather than a proven fact.
  const std::string claim =
      multiplicative.empty() ? ""
                             : "; with state-dependent noise this is the paper's claim, not a proven fact (it drops "
                               "the third central moment of $x - m|x - m$)";
  const std::string square = square_invertible_A(model);
  if (square.empty()) {
    report.exact = true;
    report.condition = kBasinPerezSkliar;
    report.explanation = "exact: $A|A$ is square and invertible, so $x - m|x - m$ is conditionally Gaussian "
                         "(Basin, Perez & Skliar 2006)" + claim + suffix;
    return report;
  }
  const std::string linear_case = !nonaffine.empty() ? nonaffine : facts.nonaffine_noise();
  if (linear_case.empty()) {
    report.exact = true;
    report.condition = kBasinPerezSkliarLinear;
    report.explanation = "exact: $f|f$ and $g|g$ are affine in $x|x$ (Basin, Perez & Skliar 2006, eqs 10-11), for "
                         "any $A|A$" + claim + suffix;
    return report;
  }
  const std::string split = partially_measured_split(facts);
  if (split.empty()) {
    report.exact = true;
    report.condition = kBasinSkliar;
    report.explanation = "exact: the nonlinear components are measured through a square invertible block and "
                         "the rest follow their own linear dynamics, with additive noise "
                         "(Basin & Skliar)" + suffix;
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation: no published exactness condition holds, so this filter is a Gaussian "
                       "assumed-density approximation" + suffix;
  report.failed = {"Kalman-Bucy: " + kalman_failure, std::string(kBasinPerezSkliar) + ": " + square,
                   std::string(kBasinPerezSkliarLinear) + ": " + linear_case, std::string(kBasinSkliar) + ": " + split};
  return report;
}

}  // namespace pfgen
