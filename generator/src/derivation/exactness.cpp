#include "pfgen/derivation/exactness.hpp"

#include <set>

#include "pfgen/algebra/polynomial.hpp"

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

// Facts about the (possibly additive-diffusion) model a filter kind is derived for.
struct ModelFacts {
  const Model& model;
  const Diffusion& diffusion;
  std::vector<Polynomial> f;

  ModelFacts(const Model& m, FilterKind kind)
      : model(m), diffusion(uses_additive_diffusion(kind) ? *m.additive_diffusion : m.diffusion) {
    for (const auto& e : m.drift) f.push_back(Polynomial::from_ex(e, m.states));
  }

  std::string nonaffine_drift() const {
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f[i].degree() > 1) return "drift of " + model.state_names[i] + " has degree " + std::to_string(f[i].degree());
    return {};
  }
  std::string state_dependent_noise() const {
    for (const auto& row : diffusion.G)
      for (const auto& e : row)
        if (depends_on_states(model, e)) return "the diffusion depends on the state (multiplicative noise)";
    return {};
  }
  std::string nonaffine_noise() const {
    if (diffusion.g) {
      for (const auto& row : *diffusion.g)
        for (const auto& e : row)
          if (Polynomial::from_ex(e, model.states).degree() > 1) return "$g|g$ is not affine in the state";
      return {};
    }
    for (const auto& row : diffusion.G)
      for (const auto& e : row)
        if (Polynomial::from_ex(e, model.states).degree() > 2)
          return "$G = g g^T|G = g\\,g^{T}$ has degree above 2 ($g|g$ not affine)";
    return {};
  }
};

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
  if (determinant(model.observation.rate().A, all, all).is_zero()) return "$A|A$ is singular";
  return {};
}

// Basin & Skliar: x = (x1, x2) where x2 has its own linear dynamics independent of
// x1, x1 is measured through a square invertible block A1, A and B B^T are
// block-diagonal and the noise is additive. The split tried is the largest
// self-contained set of affine components (x2), the rest being x1.
std::string partially_measured_split(const ModelFacts& facts) {
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

  const ExMatrix& A = model.observation.rate().A;
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
  ExMatrix R = multiply_by_transpose(model.observation.rate().B);
  for (std::size_t a : rows1)
    for (std::size_t b : rows2)
      if (!R[a][b].is_zero()) return "observation noises of $y1|y_1$ and $y2|y_2$ are correlated ($B B^T|B B^{T}$ not block-diagonal)";
  return {};
}

// Sampled observations: the update is the Kalman update, optimal when x given the past samples
// is Gaussian. That holds when f is affine and g does not depend on x (the model sampled is then
// linear Gaussian); cd-euler is then the Kalman filter of the Euler-discretised model.
ExactnessReport sampled_exactness(const ModelFacts& facts, FilterKind kind) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  const std::string failure = !nonaffine.empty() ? nonaffine : multiplicative;
  if (failure.empty()) {
    report.exact = true;
    report.condition = uses_euler_map(kind) ? "Kalman (Euler model)" : "Kalman";
    report.explanation =
        uses_euler_map(kind)
            ? "exact for the Euler-discretised model: $f|f$ is affine and $g|g$ does not depend on $x|x$, so this "
              "is the Kalman filter of $x' = x + f dt + g sqrt(dt) xi|x' = x + f\\,dt + g \\sqrt{dt}\\,\\xi$ "
              "sampled every sub-step"
            : "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so this is the Kalman filter of the "
              "sampled linear system (up to the sub-steps' integration error)";
    return report;
  }
  report.condition = "none";
  if (uses_euler_map(kind) && nonaffine.empty())
    report.explanation = "linear minimum-variance filter (Allahyani & Date): with affine $f|f$ the predicted $m|m$ "
                         "and $P|P$ are the exact moments of the Euler-discretised model, but $x|x$ is not Gaussian, "
                         "so the update is the best linear one, not the optimal one";
  else if (is_extended_kalman(kind))
    report.explanation = "approximation: the extended Kalman filter linearises $f|f$ at $m|m$; it is exact only "
                         "in the linear Gaussian case";
  else
    report.explanation = "approximation: Gaussian assumed density between samples and a Kalman update at each";
  report.failed.push_back("Kalman: " + failure);
  return report;
}

ExactnessReport undelayed_exactness(const Model& model, FilterKind kind);

// Delayed observations (docs/theory.md §2.6). With h = 0 the delay kinds are their undelayed
// counterparts; with h > 0 no finite set of moments of x(t) is exact, and the filter of Basin,
// Rodriguez-Gonzalez & Martinez-Zuniga 2004
// makes two approximations on top of the Gaussian closure, which the report names.
ExactnessReport delayed_exactness(const ModelFacts& facts, FilterKind kind) {
  const Model& model = facts.model;
  const FilterKind counterpart = is_extended_kalman(kind) ? FilterKind::Ekf : FilterKind::Optimal;
  if (model.observation.delay().is_zero()) {
    ExactnessReport report = undelayed_exactness(model, counterpart);
    report.explanation += " ($h = 0|h = 0$: the delayed filter is the '" + filter_kind_name(counterpart) + "' filter)";
    return report;
  }
  ExactnessReport report;
  report.condition = "none";
  const std::string multiplicative = facts.state_dependent_noise();
  const std::string extension =
      multiplicative.empty() ? ""
                             : "; Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004 treat additive state noise "
                               "only, so with state-dependent $g|g$ these equations are a Gaussian-closure extension "
                               "of their filter";
  if (is_extended_kalman(kind))
    report.explanation = "approximation: the extended Kalman-Bucy filter linearises $f|f$ at $m|m$ and compares "
                         "$dy|dy$ with $A m(t - h)|A\\,m(t-h)$ under the undelayed gain";
  else if (uses_transition_gain(kind))
    report.explanation = "approximation (Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004): the innovation uses "
                         "$m(t - h)|m(t-h)$, the estimate made at $t - h|t-h$, for "
                         "$E[x(t - h) \\| Y(t)]|E[x(t-h) \\mid Y(t)]$, which the observations since $t - h|t-h$ also "
                         "inform, and $E[x(t) (x(t - h) - m(t - h))^T]|E\\bigl[x(t)\\,(x(t-h) - m(t-h))^{T}\\bigr]$ is "
                         "taken as $P Phi*^T|P\\,\\Phi^{*T}$, $Phi*|\\Phi^{*}$ from the noise-free solution $x*|x^{*}$ "
                         "started at $m0|m_0$ (Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004, eqs 3 and 5)" +
                         extension;
  else
    report.explanation = "approximation: the undelayed gain $P A^T R^-1|P A^{T} R^{-1}$ with the delayed innovation "
                         "(Basin, Rodriguez-Gonzalez & Martinez-Zuniga 2004, eqs 19-20, their comparator)" + extension;
  report.failed.push_back("delay: $h > 0|h > 0$; the conditional law of $x(t)|x(t)$ depends on the path over "
                          "$[t - h, t]|[t-h, t]$, so no filter of $m(t)|m(t)$ and $P(t)|P(t)$ alone is exact");
  return report;
}

// The risk-sensitive filter (docs/theory.md §2.7) is exact, as the risk-sensitive filter, when the
// quadratic form of its information state is: f affine (the LEQG filter). It never estimates the
// conditional mean, and says so.
ExactnessReport risk_sensitive_exactness(const ModelFacts& facts) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  if (nonaffine.empty()) {
    report.exact = true;
    report.condition = "LEQG";
    report.explanation = "exact: $f|f$ is affine and the noise additive, so the information state stays Gaussian "
                         "and this is the linear risk-sensitive (LEQG) filter for the criterion $J|J$; $m|m$ is its "
                         "estimate, not the conditional mean";
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation (the construction of Alcorta-Garcia et al. 2011): the equation of the "
                       "risk-sensitive information state's logarithm is expanded about $m|m$ to second order in "
                       "$x - m|x - m$; the terms of order 3 and above, which $f|f$'s degree above 1 brings, are "
                       "dropped";
  report.failed.push_back("LEQG: " + nonaffine);
  return report;
}

// The unscented kind (docs/theory.md §2.8) replaces E[f], E[(x-m) f^T] and E[g g^T] under N(m, P) by
// sigma-point sums; these equal the expectations when f is affine and g constant (Kalman-Bucy), and
// for polynomials of low enough degree along the sigma axes, which the report names as a
// condition only in the Kalman-Bucy case, where it is proven.
ExactnessReport unscented_exactness(const ModelFacts& facts) {
  ExactnessReport report;
  const std::string nonaffine = facts.nonaffine_drift();
  const std::string multiplicative = facts.state_dependent_noise();
  if (nonaffine.empty() && multiplicative.empty()) {
    report.exact = true;
    report.condition = "Kalman-Bucy";
    report.explanation = "exact: $f|f$ is affine and $g|g$ does not depend on $x|x$, so the sigma-point sums are "
                         "the Gaussian expectations and this is the Kalman-Bucy filter";
    return report;
  }
  report.condition = "none";
  report.explanation = "approximation (unscented, Sarkka 2007): $E[f]|E[f]$, $E[(x-m) f^T]|E[(x-m) f^{T}]$ and "
                       "$E[g g^T]|E[g\\,g^{T}]$ under $N(m, P)|N(m, P)$ are replaced by weighted sums over $2n+1|2n+1$ "
                       "sigma points; the sums equal those expectations when $f|f$ has degree $<= 2|\\le 2$ and $G|G$ "
                       "degree $<= 3|\\le 3$, and beyond that only for terms that move along one sigma axis "
                       "(docs/theory.md 2.8), on top of the Gaussian assumed density";
  report.failed.push_back("Kalman-Bucy: " + (!nonaffine.empty() ? nonaffine : multiplicative));
  return report;
}

}  // namespace

ExactnessReport assess_exactness(const Model& model, FilterKind kind) {
  ModelFacts facts(model, kind);
  if (is_risk_sensitive(kind)) return risk_sensitive_exactness(facts);
  if (uses_sigma_points(kind)) return unscented_exactness(facts);
  if (model.observation.is_sampled()) return sampled_exactness(facts, kind);
  if (model.observation.is_delayed()) return delayed_exactness(facts, kind);
  return undelayed_exactness(model, kind);
}

namespace {

ExactnessReport undelayed_exactness(const Model& model, FilterKind kind) {
  ModelFacts facts(model, kind);
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

}  // namespace

}  // namespace pfgen
