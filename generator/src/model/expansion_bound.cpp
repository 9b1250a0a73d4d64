#include "pfgen/model/expansion_bound.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace pfgen {
namespace {

// log C(a + b, b), for non-negative a, b in double.
double log_binomial(double a, double b) { return std::lgamma(a + b + 1) - std::lgamma(a + 1) - std::lgamma(b + 1); }

// exp of a log count: the counts are whole numbers, and lgamma's last bits must not put a bound
// one below the count it bounds.
double from_log(double log_count) { return log_count < 36 ? std::round(std::exp(log_count)) : std::exp(log_count); }

// What the bound knows of a subexpression: its term count and its degree in each variable.
struct Shape {
  double terms = 1;
  std::map<unsigned, double> degree;  // variable index -> degree (absent: 0)
  double total_degree = 0;
};

class Bounder {
 public:
  double run(const GiNaC::ex& e) { return shape(e).terms; }

 private:
  std::map<GiNaC::ex, unsigned, GiNaC::ex_is_less> variables_;

  // No expansion has more terms than there are monomials of its degrees.
  static void cap(Shape& s) {
    double box = 0;  // log of prod (d_k + 1)
    for (const auto& [k, d] : s.degree) box += std::log1p(d);
    const double simplex = log_binomial(static_cast<double>(s.degree.size()), s.total_degree);
    const double limit = std::min(box, simplex);
    if (std::isnan(s.terms) || s.terms > from_log(limit)) s.terms = from_log(limit);
  }

  Shape variable(const GiNaC::ex& e) {
    const unsigned index = variables_.emplace(e, static_cast<unsigned>(variables_.size())).first->second;
    Shape s;
    s.degree[index] = 1;
    s.total_degree = 1;
    return s;
  }

  Shape shape(const GiNaC::ex& e) {
    if (GiNaC::is_a<GiNaC::numeric>(e)) return Shape{};
    if (GiNaC::is_a<GiNaC::add>(e)) {
      Shape sum;
      sum.terms = 0;
      for (std::size_t i = 0; i < e.nops(); ++i) {
        const Shape term = shape(e.op(i));
        sum.terms += term.terms;
        for (const auto& [k, d] : term.degree) sum.degree[k] = std::max(sum.degree[k], d);
        sum.total_degree = std::max(sum.total_degree, term.total_degree);
      }
      cap(sum);
      return sum;
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) {
      Shape product;
      for (std::size_t i = 0; i < e.nops(); ++i) {
        const Shape factor = shape(e.op(i));
        product.terms *= factor.terms;
        for (const auto& [k, d] : factor.degree) product.degree[k] += d;
        product.total_degree += factor.total_degree;
      }
      cap(product);
      return product;
    }
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1))) {
      const GiNaC::numeric& exponent = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
      // expand() multiplies out only non-negative integer powers; others stay one factor.
      if (!exponent.is_nonneg_integer()) return variable(e);
      const double k = exponent.to_double();
      Shape power = shape(e.op(0));
      // Multisets of k terms out of T: C(T + k - 1, k).
      if (power.terms > 1) power.terms = from_log(log_binomial(power.terms - 1, k));
      for (auto& [index, d] : power.degree) d *= k;
      power.total_degree *= k;
      cap(power);
      return power;
    }
    // A symbol, a constant such as Pi, a function call or a symbolic power: one factor.
    return variable(e);
  }
};

}  // namespace

double expanded_terms_bound(const GiNaC::ex& e) { return Bounder().run(e); }

}  // namespace pfgen
