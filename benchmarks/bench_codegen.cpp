// ns per derivatives() call of pfgen's generated optimal filter, measured in
// one run against
//   (a) the same equations emitted without common-subexpression elimination
//       (`pfgen codegen --no-cse`), and
//   (b) a generic runtime, what a user without pfgen would write: the same
//       m_drift = E[f] and P_drift = E[(x-m) f^T] + E[f (x-m)^T] + E[g g^T]
//       - P A^T (B B^T)^-1 A P computed numerically with tensor-product
//       Gauss-Hermite quadrature of just-sufficient order (exact for the
//       polynomial degree).
//
// The quadrature runtime (GaussHermiteFilter below) evaluates the drift f and
// the diffusion g at each node in three ways, times each, and counts the
// fastest, so that the baseline gets its best shot:
//   rows     the model file's polynomials as generic sparse polynomials over a
//            shared monomial basis (each monomial one product from a shorter
//            one), each polynomial a dot product with the monomial values;
//   columns  the same with a dense coefficient matrix applied column by column
//            (vectorised over the components);
//   typed    f and g typed as plain C++ functions, as one writes a model by
//            hand (written at build time by model_to_cpp from the model file).
// With x = m + L z (P = L L^T, computed per call) and a tensor
// grid of k nodes per dimension, exact up to total degree 2k - 1:
//   - E[f] (degree d_f) and E[(x-m) f^T] (degree d_f + 1) on one grid with
//     k_f = ceil((d_f + 2) / 2) nodes per dimension: the f values the cross
//     term needs give E[f] for free, cheaper than a second, smaller grid;
//   - E[g g^T] (degree 2 d_g) on a grid with k_g = d_g + 1 nodes.
// The grids' nodes and weights and A^T (B B^T)^-1 A are computed once at setup,
// as a user would; no allocation happens per call.
//
// Before timing, every case checks on every test state that the quadrature (in
// all three evaluations) and the no-CSE code agree with the generated code to
// 1e-9 relative (in the max norm of the whole output): all compute the same thing.
//
// Timing: ns per call, each method cycling over the same fixed set of random
// valid states (P positive definite), every call out of line through a pointer
// with a compiler memory barrier after it; the methods' repetitions are
// interleaved, the table gives medians of the ns and of the per-repetition ratios.
//
// Usage: bench_codegen [--repeats 7] [--min-time-ms 100] [--states 64]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_cases.hpp"
#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

namespace pfgen_bench {
namespace {

using Clock = std::chrono::steady_clock;

// Keeps the compiler from assuming anything about memory across this point.
inline void clobber_memory() { asm volatile("" : : : "memory"); }

double to_double(const GiNaC::ex& e, const std::string& what) {
  if (!GiNaC::is_exactly_a<GiNaC::numeric>(e))
    throw std::runtime_error(what + ": the quadrature baseline needs numeric coefficients");
  return GiNaC::ex_to<GiNaC::numeric>(e).to_double();
}

// ---------------------------------------------------------------------------
// Generic polynomials over one shared monomial basis, evaluated in one of two
// layouts (the filter keeps whichever is faster for the model, see below):
//   Rows:    each polynomial a sparse dot product over its own terms;
//   Columns: a dense coefficient matrix applied column by column
//            (values += column j * monomial j), which the compiler vectorises
//            over the polynomials without reassociating any sum.
enum class Layout { Rows, Columns, Typed };  // Typed: not a PolynomialSet layout (see the filter)

class PolynomialSet {
 public:
  PolynomialSet(const std::vector<GiNaC::ex>& polynomials, const std::vector<GiNaC::symbol>& states) {
    std::map<pfgen::Monomial, std::size_t> index;
    // Every monomial and each of its prefixes (it minus one factor of its last
    // variable), so that each basis entry is one product from an earlier one.
    std::vector<pfgen::Monomial> pending{pfgen::Monomial()};
    std::vector<std::vector<std::pair<pfgen::Monomial, double>>> rows;
    for (const auto& e : polynomials) {
      pfgen::Polynomial p = pfgen::Polynomial::from_ex(GiNaC::expand(e), states);
      degree_ = std::max<std::size_t>(degree_, p.degree());
      rows.emplace_back();
      for (const auto& [m, c] : p.terms()) {
        rows.back().emplace_back(m, to_double(c, "coefficient"));
        for (pfgen::Monomial q = m; !q.is_one(); q = q.without_one(q.factors().back().first)) pending.push_back(q);
      }
    }
    std::sort(pending.begin(), pending.end(), [](const pfgen::Monomial& a, const pfgen::Monomial& b) {
      return a.degree() != b.degree() ? a.degree() < b.degree() : a < b;
    });
    pending.erase(std::unique(pending.begin(), pending.end()), pending.end());
    for (const auto& m : pending) {
      index.emplace(m, basis_parent_.size());
      std::uint32_t v = m.is_one() ? 0 : m.factors().back().first;
      basis_parent_.push_back(m.is_one() ? 0 : index.at(m.without_one(v)));
      basis_variable_.push_back(v);
    }
    rows_ = rows.size();
    row_start_.push_back(0);
    columns_.assign(basis_parent_.size() * rows_, 0.0);
    for (std::size_t r = 0; r < rows_; ++r) {
      for (const auto& [m, c] : rows[r]) {
        term_monomial_.push_back(index.at(m));
        term_coefficient_.push_back(c);
        columns_[index.at(m) * rows_ + r] = c;
      }
      row_start_.push_back(term_monomial_.size());
    }
  }

  std::size_t size() const { return rows_; }
  std::size_t basis_size() const { return basis_parent_.size(); }
  std::size_t degree() const { return degree_; }
  void use(Layout layout) { layout_ = layout == Layout::Columns ? Layout::Columns : Layout::Rows; }

  // values[r] = polynomial r at x; monomials has basis_size() entries of scratch.
  void evaluate(const double* x, double* monomials, double* values) const {
    const std::size_t basis = basis_parent_.size();
    monomials[0] = 1.0;  // the basis is sorted by degree: entry 0 is the monomial 1
    for (std::size_t j = 1; j < basis; ++j) monomials[j] = monomials[basis_parent_[j]] * x[basis_variable_[j]];
    if (layout_ == Layout::Rows) {
      for (std::size_t r = 0; r < rows_; ++r) {
        double sum = 0.0;
        for (std::size_t t = row_start_[r]; t < row_start_[r + 1]; ++t)
          sum += term_coefficient_[t] * monomials[term_monomial_[t]];
        values[r] = sum;
      }
    } else {
      for (std::size_t r = 0; r < rows_; ++r) values[r] = 0.0;
      const double* column = columns_.data();
      for (std::size_t j = 0; j < basis; ++j, column += rows_) {
        const double v = monomials[j];
        for (std::size_t r = 0; r < rows_; ++r) values[r] += column[r] * v;
      }
    }
  }

 private:
  std::size_t degree_ = 0;
  std::size_t rows_ = 0;
  Layout layout_ = Layout::Rows;
  std::vector<std::size_t> basis_parent_;
  std::vector<std::uint32_t> basis_variable_;
  std::vector<std::size_t> row_start_;       // Rows: terms of polynomial r are [row_start_[r], row_start_[r+1])
  std::vector<std::size_t> term_monomial_;
  std::vector<double> term_coefficient_;
  std::vector<double> columns_;              // Columns: basis_size() x size()
};

// ---------------------------------------------------------------------------
// Gauss-Hermite rule for the standard normal weight with k nodes (exact up to degree 2k - 1).
void gauss_hermite(std::size_t k, std::vector<double>& nodes, std::vector<double>& weights) {
  // Probabilists' Hermite polynomials He_j; roots by Newton from Golub-Welsch-like starting points.
  nodes.assign(k, 0.0);
  weights.assign(k, 0.0);
  auto hermite = [](std::size_t j, double x, double& previous) {
    double a = 1.0, b = x;  // He_0, He_1
    if (j == 0) { previous = 0.0; return 1.0; }
    for (std::size_t i = 1; i < j; ++i) {
      double c = x * b - static_cast<double>(i) * a;
      a = b;
      b = c;
    }
    previous = a;  // He_{j-1}
    return b;
  };
  double factorial = 1.0;
  for (std::size_t i = 2; i <= k; ++i) factorial *= static_cast<double>(i);
  for (std::size_t r = 0; r < k; ++r) {
    // Roots of He_k are symmetric and lie in (-2 sqrt(k), 2 sqrt(k)); start from the
    // asymptotic guess and polish by Newton with deflation against the found roots.
    double x = std::sqrt(4.0 * k + 2.0) * std::cos(3.14159265358979323846 * (r + 0.75) / (k + 0.5));
    for (int it = 0; it < 100; ++it) {
      double previous;
      double value = hermite(k, x, previous);
      double derivative = static_cast<double>(k) * previous;  // He_k' = k He_{k-1}
      double deflation = 0.0;
      for (std::size_t s = 0; s < r; ++s) deflation += 1.0 / (x - nodes[s]);
      double step = value / (derivative - value * deflation);
      x -= step;
      if (std::abs(step) < 1e-15 * std::max(1.0, std::abs(x))) break;
    }
    double previous;
    (void)hermite(k, x, previous);
    nodes[r] = x;
    weights[r] = factorial / (static_cast<double>(k * k) * previous * previous);  // k! / (k^2 He_{k-1}(x)^2)
  }
}

struct TensorGrid {
  std::size_t points = 0;
  std::vector<double> z;       // points x n, standard normal nodes
  std::vector<double> weight;  // points

  TensorGrid(std::size_t n, std::size_t k) {
    std::vector<double> nodes, weights;
    gauss_hermite(k, nodes, weights);
    points = 1;
    for (std::size_t i = 0; i < n; ++i) points *= k;
    std::vector<std::size_t> digit(n, 0);
    for (std::size_t q = 0; q < points; ++q) {
      double w = 1.0;
      for (std::size_t i = 0; i < n; ++i) {
        z.push_back(nodes[digit[i]]);
        w *= weights[digit[i]];
      }
      weight.push_back(w);
      for (std::size_t i = 0; i < n && ++digit[i] == k; ++i) digit[i] = 0;
    }
  }
};

// ---------------------------------------------------------------------------
// The generic runtime: the optimal filter's m_drift and P_drift by quadrature.
class GaussHermiteFilter {
 public:
  // typed_f and typed_g: the model's f and g as plain C++ functions (Layout::Typed).
  GaussHermiteFilter(const pfgen::Model& model, PolynomialFunction typed_f, PolynomialFunction typed_g)
      : n_(model.n()),
        typed_f_(typed_f),
        typed_g_(typed_g),
        drift_(model.drift, model.states),
        diffusion_(flatten_diffusion(model), model.states),
        q_(model.diffusion.g ? model.diffusion.g->front().size() : 0),
        k_f_((drift_.degree() + 2 + 1) / 2),  // ceil((d_f + 2) / 2)
        k_g_(diffusion_.degree() + 1),        // ceil((2 d_g + 1) / 2)
        grid_f_(n_, k_f_),
        grid_g_(n_, k_g_) {
    const std::size_t p = model.p();
    std::vector<double> A(p * n_), R(p * p, 0.0);
    for (std::size_t r = 0; r < p; ++r)
      for (std::size_t i = 0; i < n_; ++i) A[r * n_ + i] = to_double(model.observation.rate().A[r][i], "A");
    const std::size_t cols = model.observation.rate().B.front().size();
    for (std::size_t r = 0; r < p; ++r)
      for (std::size_t s = 0; s < p; ++s)
        for (std::size_t c = 0; c < cols; ++c)
          R[r * p + s] += to_double(model.observation.rate().B[r][c], "B") * to_double(model.observation.rate().B[s][c], "B");
    std::vector<double> Rinv_A = solve(R, A, p, n_);  // (B B^T)^-1 A, p x n
    observation_.assign(n_ * n_, 0.0);                  // A^T (B B^T)^-1 A
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t j = 0; j < n_; ++j)
        for (std::size_t r = 0; r < p; ++r) observation_[i * n_ + j] += A[r * n_ + i] * Rinv_A[r * n_ + j];
    monomials_.resize(std::max(drift_.basis_size(), diffusion_.basis_size()));
    P_.resize(n_ * n_);
    L_.resize(n_ * n_);
    dx_.resize(n_);
    x_.resize(n_);
    f_.resize(n_);
    g_.resize(n_ * std::max<std::size_t>(q_, 1));
    Ef_.resize(n_);
    cross_.resize(n_ * n_);
    gg_.resize(n_ * n_);
    PC_.resize(n_ * n_);
  }

  std::size_t points() const { return grid_f_.points + grid_g_.points; }
  void use(Layout layout) {
    typed_ = layout == Layout::Typed;
    drift_.use(layout);
    diffusion_.use(layout);
  }

  __attribute__((noinline)) void derivatives(const double* state, double* out) {
    const double* m = state;
    for (std::size_t i = 0, u = n_; i < n_; ++i)
      for (std::size_t j = i; j < n_; ++j, ++u) P_[i * n_ + j] = P_[j * n_ + i] = state[u];
    cholesky();

    // E[f] and E[(x-m) f^T].
    std::fill(Ef_.begin(), Ef_.end(), 0.0);
    std::fill(cross_.begin(), cross_.end(), 0.0);
    for (std::size_t q = 0; q < grid_f_.points; ++q) {
      point(m, &grid_f_.z[q * n_]);
      if (typed_) typed_f_(x_.data(), f_.data());
      else drift_.evaluate(x_.data(), monomials_.data(), f_.data());
      const double w = grid_f_.weight[q];
      for (std::size_t j = 0; j < n_; ++j) f_[j] *= w;
      for (std::size_t j = 0; j < n_; ++j) Ef_[j] += f_[j];
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t j = 0; j < n_; ++j) cross_[i * n_ + j] += dx_[i] * f_[j];
    }

    // E[g g^T], upper triangle.
    std::fill(gg_.begin(), gg_.end(), 0.0);
    if (q_ > 0) {
      for (std::size_t q = 0; q < grid_g_.points; ++q) {
        point(m, &grid_g_.z[q * n_]);
        if (typed_) typed_g_(x_.data(), g_.data());
        else diffusion_.evaluate(x_.data(), monomials_.data(), g_.data());
        const double w = grid_g_.weight[q];
        for (std::size_t i = 0; i < n_; ++i)
          for (std::size_t j = i; j < n_; ++j) {
            double s = 0.0;
            for (std::size_t c = 0; c < q_; ++c) s += g_[i * q_ + c] * g_[j * q_ + c];
            gg_[i * n_ + j] += w * s;
          }
      }
    }

    // P A^T (B B^T)^-1 A P.
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t j = 0; j < n_; ++j) {
        double s = 0.0;
        for (std::size_t k = 0; k < n_; ++k) s += P_[i * n_ + k] * observation_[k * n_ + j];
        PC_[i * n_ + j] = s;
      }
    for (std::size_t i = 0; i < n_; ++i) out[i] = Ef_[i];
    for (std::size_t i = 0, u = n_; i < n_; ++i)
      for (std::size_t j = i; j < n_; ++j, ++u) {
        double correction = 0.0;
        for (std::size_t k = 0; k < n_; ++k) correction += PC_[i * n_ + k] * P_[k * n_ + j];
        out[u] = cross_[i * n_ + j] + cross_[j * n_ + i] + gg_[i * n_ + j] - correction;
      }
  }

 private:
  static std::vector<GiNaC::ex> flatten_diffusion(const pfgen::Model& model) {
    if (!model.diffusion.g) throw std::runtime_error("the quadrature baseline needs the diffusion as g");
    std::vector<GiNaC::ex> entries;
    for (const auto& row : *model.diffusion.g) entries.insert(entries.end(), row.begin(), row.end());
    return entries;
  }

  // Solves R X = Y for symmetric positive definite R (p x p), Y p x c, by Cholesky.
  static std::vector<double> solve(std::vector<double> R, std::vector<double> Y, std::size_t p, std::size_t c) {
    for (std::size_t j = 0; j < p; ++j) {
      for (std::size_t k = 0; k < j; ++k) R[j * p + j] -= R[j * p + k] * R[j * p + k];
      R[j * p + j] = std::sqrt(R[j * p + j]);
      for (std::size_t i = j + 1; i < p; ++i) {
        for (std::size_t k = 0; k < j; ++k) R[i * p + j] -= R[i * p + k] * R[j * p + k];
        R[i * p + j] /= R[j * p + j];
      }
    }
    for (std::size_t col = 0; col < c; ++col) {
      for (std::size_t i = 0; i < p; ++i) {
        for (std::size_t k = 0; k < i; ++k) Y[i * c + col] -= R[i * p + k] * Y[k * c + col];
        Y[i * c + col] /= R[i * p + i];
      }
      for (std::size_t i = p; i-- > 0;) {
        for (std::size_t k = i + 1; k < p; ++k) Y[i * c + col] -= R[k * p + i] * Y[k * c + col];
        Y[i * c + col] /= R[i * p + i];
      }
    }
    return Y;
  }

  void cholesky() {
    for (std::size_t j = 0; j < n_; ++j) {
      double d = P_[j * n_ + j];
      for (std::size_t k = 0; k < j; ++k) d -= L_[j * n_ + k] * L_[j * n_ + k];
      L_[j * n_ + j] = std::sqrt(d);
      for (std::size_t i = j + 1; i < n_; ++i) {
        double s = P_[i * n_ + j];
        for (std::size_t k = 0; k < j; ++k) s -= L_[i * n_ + k] * L_[j * n_ + k];
        L_[i * n_ + j] = s / L_[j * n_ + j];
      }
    }
  }

  // dx = L z, x = m + dx.
  void point(const double* m, const double* z) {
    for (std::size_t i = 0; i < n_; ++i) {
      double s = 0.0;
      for (std::size_t k = 0; k <= i; ++k) s += L_[i * n_ + k] * z[k];
      dx_[i] = s;
      x_[i] = m[i] + s;
    }
  }

  std::size_t n_;
  PolynomialFunction typed_f_, typed_g_;
  bool typed_ = false;
  PolynomialSet drift_;
  PolynomialSet diffusion_;
  std::size_t q_;
  std::size_t k_f_, k_g_;
  TensorGrid grid_f_, grid_g_;
  std::vector<double> observation_;
  std::vector<double> monomials_, P_, L_, dx_, x_, f_, g_, Ef_, cross_, gg_, PC_;
};

// ---------------------------------------------------------------------------
// Test states: m uniform in [-1, 1]^n, P = M M^T / n + 0.2 I with M uniform in [-1, 1].
std::vector<std::vector<double>> random_states(std::size_t n, std::size_t count) {
  std::mt19937 rng(static_cast<unsigned>(4242 + n));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::vector<double>> states;
  for (std::size_t s = 0; s < count; ++s) {
    std::vector<double> state;
    for (std::size_t i = 0; i < n; ++i) state.push_back(u(rng));
    std::vector<double> M(n * n);
    for (double& v : M) v = u(rng);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) {
        double v = i == j ? 0.2 : 0.0;
        for (std::size_t k = 0; k < n; ++k) v += M[i * n + k] * M[j * n + k] / static_cast<double>(n);
        state.push_back(v);
      }
    states.push_back(state);
  }
  return states;
}

double max_relative_difference(const std::vector<double>& reference, const std::vector<double>& value) {
  double scale = 0.0, difference = 0.0;
  for (std::size_t k = 0; k < reference.size(); ++k) {
    scale = std::max(scale, std::abs(reference[k]));
    difference = std::max(difference, std::abs(reference[k] - value[k]));
  }
  return scale > 0.0 ? difference / scale : difference;
}

// A timing loop over all states: loop(rounds) calls `call` rounds x states
// times and returns the seconds taken. Type-erased once per loop, not per call.
template <class Call>
std::function<double(std::size_t)> timing_loop(Call call, const std::vector<std::vector<double>>& states,
                                               std::size_t out_size) {
  return [call, &states, out_size](std::size_t rounds) {
    std::vector<double> out(out_size);
    auto start = Clock::now();
    for (std::size_t r = 0; r < rounds; ++r)
      for (const auto& state : states) {
        call(state.data(), out.data());
        clobber_memory();
      }
    double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    volatile double sink = out[0];
    (void)sink;
    return seconds;
  };
}

// Rounds for one repetition to last at least min_seconds (the short runs also warm the caches).
std::size_t calibrate(const std::function<double(std::size_t)>& loop, double min_seconds) {
  std::size_t rounds = 1;
  for (double t = loop(rounds); t < min_seconds / 10; t = loop(rounds)) rounds *= 4;
  double per_round = loop(rounds) / static_cast<double>(rounds);
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(min_seconds / per_round)));
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t k = values.size() / 2;
  return values.size() % 2 ? values[k] : (values[k - 1] + values[k]) / 2;
}

std::string compact(double ns) {
  char buffer[32];
  if (ns < 100) std::snprintf(buffer, sizeof buffer, "%.1f", ns);
  else std::snprintf(buffer, sizeof buffer, "%.0f", ns);
  return buffer;
}

}  // namespace
}  // namespace pfgen_bench

int main(int argc, char** argv) {
  using namespace pfgen_bench;
  int repeats = 7;
  double min_seconds = 0.1;
  std::size_t state_count = 64;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--repeats")) repeats = std::max(1, std::atoi(argv[k + 1]));
    else if (!std::strcmp(argv[k], "--min-time-ms")) min_seconds = std::max(1.0, std::atof(argv[k + 1])) / 1000.0;
    else if (!std::strcmp(argv[k], "--states")) state_count = std::max(1, std::atoi(argv[k + 1]));
    else {
      std::fprintf(stderr, "usage: bench_codegen [--repeats 7] [--min-time-ms 100] [--states 64]\n");
      return 2;
    }
  }

  struct Row {
    std::string label;
    std::size_t n, ops_naive, ops_cse, points;
    double ns_cse, ns_no_cse, ns_quadrature, difference;
    std::string layout;          // the quadrature's fastest evaluation of f and g
    double ns_by_layout[3];      // rows, columns, typed
    double no_cse_ratio, quadrature_ratio;
  };
  const char* layout_names[3] = {"rows", "columns", "typed"};
  std::vector<Row> rows;
  std::printf("%-16s %2s %9s %8s %9s %9s %10s %10s %9s %9s %7s %-7s %9s\n", "case", "n", "ops_naive", "ops_cse",
              "cse/naive", "ns_gen", "ns_no_cse", "ns_quad", "nocse/gen", "quad/gen", "GH_pts", "GH_eval",
              "max_rel_d");
  for (const BenchCase& c : bench_cases()) {
    pfgen::Model model = pfgen::load_model_file(c.model_path);
    GaussHermiteFilter quadrature(model, c.typed_f, c.typed_g);
    const std::size_t n = c.cse.n, size = c.cse.state_size;
    if (model.n() != n || c.no_cse.state_size != size) {
      std::fprintf(stderr, "%s: generated code and model disagree on the dimension\n", c.label.c_str());
      return 1;
    }
    auto states = random_states(n, state_count);

    // The three must compute the same thing before their times mean anything.
    double difference = 0.0;
    for (const auto& state : states) {
      std::vector<double> generated(size), no_cse(size), numeric(size);
      c.cse.derivatives(state.data(), generated.data());
      c.no_cse.derivatives(state.data(), no_cse.data());
      difference = std::max(difference, max_relative_difference(generated, no_cse));
      for (Layout layout : {Layout::Rows, Layout::Columns, Layout::Typed}) {
        quadrature.use(layout);
        quadrature.derivatives(state.data(), numeric.data());
        difference = std::max(difference, max_relative_difference(generated, numeric));
      }
    }
    if (!(difference <= 1e-9)) {
      std::fprintf(stderr, "%s: results disagree (max relative difference %.3g > 1e-9)\n", c.label.c_str(),
                   difference);
      return 1;
    }

    Row row{c.label, n, c.ops_naive, c.ops_cse, quadrature.points(), 0, 0, 0, difference, "", {0, 0, 0}, 0, 0};
    // Five methods, timed in interleaved repetitions so that a disturbance of the
    // machine hits all of them alike: generated, no CSE, quadrature x 3 evaluations.
    std::vector<std::function<double(std::size_t)>> loops{timing_loop(c.cse.derivatives, states, size),
                                                          timing_loop(c.no_cse.derivatives, states, size)};
    std::vector<GaussHermiteFilter> quadratures(3, quadrature);  // one per evaluation of f and g
    for (Layout layout : {Layout::Rows, Layout::Columns, Layout::Typed}) {
      GaussHermiteFilter& q = quadratures[static_cast<int>(layout)];
      q.use(layout);
      loops.push_back(timing_loop([&q](const double* s, double* o) { q.derivatives(s, o); }, states, size));
    }
    std::vector<std::size_t> rounds;
    for (const auto& loop : loops) rounds.push_back(calibrate(loop, min_seconds));
    std::vector<std::vector<double>> ns(loops.size());
    for (int r = 0; r < repeats; ++r)
      for (std::size_t k = 0; k < loops.size(); ++k)
        ns[k].push_back(loops[k](rounds[k]) * 1e9 / static_cast<double>(rounds[k] * states.size()));
    row.ns_cse = median(ns[0]);
    row.ns_no_cse = median(ns[1]);
    std::size_t best = 2;  // the quadrature's fastest evaluation of f and g counts
    for (std::size_t k = 2; k < loops.size(); ++k) {
      row.ns_by_layout[k - 2] = median(ns[k]);
      if (median(ns[k]) < median(ns[best])) best = k;
    }
    row.ns_quadrature = median(ns[best]);
    row.layout = layout_names[best - 2];
    // Ratios: medians of the per-repetition ratios.
    std::vector<double> no_cse_ratio, quadrature_ratio;
    for (int r = 0; r < repeats; ++r) {
      no_cse_ratio.push_back(ns[1][r] / ns[0][r]);
      quadrature_ratio.push_back(ns[best][r] / ns[0][r]);
    }
    row.no_cse_ratio = median(no_cse_ratio);
    row.quadrature_ratio = median(quadrature_ratio);
    std::printf("%-16s %2zu %9zu %8zu %8.1f%% %9s %10s %10s %8.2fx %8.1fx %7zu %-7s %9.1e\n", row.label.c_str(), n,
                row.ops_naive, row.ops_cse, 100.0 * row.ops_cse / row.ops_naive, compact(row.ns_cse).c_str(),
                compact(row.ns_no_cse).c_str(), compact(row.ns_quadrature).c_str(), row.no_cse_ratio,
                row.quadrature_ratio, row.points, row.layout.c_str(), row.difference);
    std::fflush(stdout);
    rows.push_back(row);
  }

  std::printf("\nquadrature ns per call by evaluation of f and g (rows: generic sparse polynomials; columns: generic\n"
              "dense coefficient matrix; typed: the model's f and g as plain C++ functions):\n");
  std::printf("%-16s %10s %10s %10s\n", "case", "rows", "columns", "typed");
  for (const Row& r : rows)
    std::printf("%-16s %10s %10s %10s\n", r.label.c_str(), compact(r.ns_by_layout[0]).c_str(),
                compact(r.ns_by_layout[1]).c_str(), compact(r.ns_by_layout[2]).c_str());

  // Targets of issue 4, item 10.
  bool cse_met = true, speed_met = false;
  std::string cse_figures, speed_figure = "n/a";
  for (const Row& r : rows) {
    if (r.label.rfind("dense", 0) == 0) {
      double ratio = static_cast<double>(r.ops_cse) / static_cast<double>(r.ops_naive);
      cse_met = cse_met && ratio <= 0.60;
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "%s%.1f%% at n = %zu", cse_figures.empty() ? "" : ", ", 100 * ratio, r.n);
      cse_figures += buffer;
    }
    if (r.label == "dense cubic n=4") {
      speed_met = r.quadrature_ratio >= 20.0;
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.1fx", r.quadrature_ratio);
      speed_figure = buffer;
    }
  }
  std::printf("\ntarget: CSE ops <= 60%% of naive on the dense cases: %s (%s)\n", cse_met ? "met" : "NOT met",
              cse_figures.c_str());
  std::printf("target: generated >= 20x faster than quadrature at dense cubic n = 4: %s (%s)\n",
              speed_met ? "met" : "NOT met", speed_figure.c_str());
  return 0;
}
