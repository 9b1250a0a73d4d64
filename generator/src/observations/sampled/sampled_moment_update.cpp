#include "pfgen/observations/sampled/sampled_moment_update.hpp"

#include <algorithm>

namespace pfgen {
namespace {

std::size_t power(std::size_t n, std::size_t k) {
  std::size_t out = 1;
  for (std::size_t i = 0; i < k; ++i) out *= n;
  return out;
}

// Every index tuple of k states out of n, in the row-major order of the full tensor.
std::vector<std::vector<std::size_t>> tuples(std::size_t n, std::size_t k) {
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::size_t> t(k, 0);
  for (std::size_t e = 0; e < power(n, k); ++e) {
    std::size_t rest = e;
    for (std::size_t d = k; d-- > 0;) {
      t[d] = rest % n;
      rest /= n;
    }
    out.push_back(t);
  }
  return out;
}

std::size_t flat(const std::vector<std::size_t>& t, std::size_t n) {
  std::size_t e = 0;
  for (std::size_t i : t) e = e * n + i;
  return e;
}

// The state variable that holds the moment with these indices (in any order).
std::uint32_t moment_variable(const FilterVariables& vars, std::vector<std::size_t> t) {
  std::sort(t.begin(), t.end());
  return vars.higher_moment(t);
}

// The six ways to take one pair of four indices for U and the other for Q, and the three pairings for Q Q.
constexpr std::size_t kSplits[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {2, 3, 0, 1}, {1, 3, 0, 2}, {1, 2, 0, 3}};
constexpr std::size_t kPairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};

}  // namespace

std::vector<GiNaC::numeric> updated_higher_moments(const FilterVariables& vars, const NumericMatrix& A,
                                                   const NumericMatrix& P, const NumericMatrix& Q,
                                                   const std::vector<GiNaC::numeric>& moments) {
  const std::size_t n = vars.n();
  NumericMatrix U(n, std::vector<GiNaC::numeric>(n, 0));  // A P A^T
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = 0; b < n; ++b) U[i][j] += A[i][a] * P[a][b] * A[j][b];
  std::vector<GiNaC::numeric> out(moments.size());
  const std::uint32_t first = vars.first_higher_moment();
  for (std::size_t order = 3; order <= vars.order(); ++order) {
    const std::size_t size = power(n, order), rest = size / n;
    std::vector<GiNaC::numeric> tensor(size), contracted(size);
    for (const auto& t : tuples(n, order)) tensor[flat(t, n)] = moments.at(moment_variable(vars, t) - first);
    // contracted(r, i) = sum_a A_ia tensor(a, r): A on the first index, which moves last; `order` times.
    for (std::size_t turn = 0; turn < order; ++turn) {
      for (std::size_t r = 0; r < rest; ++r)
        for (std::size_t i = 0; i < n; ++i) {
          GiNaC::numeric sum = 0;
          for (std::size_t a = 0; a < n; ++a) sum += A[i][a] * tensor[a * rest + r];
          contracted[r * n + i] = sum;
        }
      tensor.swap(contracted);
    }
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
      const std::vector<std::size_t>& t = vars.higher_moments()[q];
      if (t.size() != order) continue;
      GiNaC::numeric value = tensor[flat(t, n)];
      if (order == 4) {
        for (const auto& s : kSplits) value += U[t[s[0]]][t[s[1]]] * Q[t[s[2]]][t[s[3]]];
        for (const auto& s : kPairings) value += Q[t[s[0]]][t[s[1]]] * Q[t[s[2]]][t[s[3]]];
      }
      out[q] = value;
    }
  }
  return out;
}

}  // namespace pfgen

namespace pfgen::codegen {
namespace {

ir::Expr entry(const char* array, std::size_t row, std::size_t column, std::size_t n) {
  return ir::element(array, row * n + column);
}

// array[row * columns + column], its indices loop variables.
ir::Expr at(const std::string& array, const char* row, const ir::Expr& columns, const char* column) {
  return ir::element(array, ir::add(ir::mul(ir::name(row), columns), ir::name(column)));
}

ir::Statement over(const char* index, ir::Expr end, ir::Block body) {
  return ir::loop(index, ir::Type::Size, ir::integer(0), std::move(end), std::move(body));
}

}  // namespace

ir::Block moment_update_statements(const FilterVariables& vars) {
  if (vars.higher_moments().empty()) return {};
  const std::size_t n = vars.n();
  const ir::Expr N = ir::dimension("n"), p = ir::dimension("p"), zero = ir::whole_scalar(0);
  ir::Block out;
  out.push_back(ir::comment("The higher central moments of the updated law: A on each index, and at order 4 the "
                            "noise's terms (docs/theory.md)"));
  out.push_back(ir::local_arrays({"tensor", "contracted"}, ir::Type::Scalar, ir::integer(power(n, vars.order()))));
  if (vars.order() >= 4) {
    out.push_back(ir::local_arrays({"apat", "noise"}, ir::Type::Scalar, ir::mul(N, N)));
    // apat = A P A^T = AP A^T, noise = K R K^T.
    const ir::Expr r_ab = ir::packed_entry("R", ir::name("a"), ir::name("b"));
    out.push_back(over(
        "i", N,
        {over("j", N,
              {ir::declare_variable("sum", ir::Type::Scalar, zero),
               over("l", N, {ir::accumulate(ir::name("sum"), ir::mul(at("AP", "i", N, "l"), at("A", "j", N, "l")))}),
               ir::assign(at("apat", "i", N, "j"), ir::name("sum")),
               ir::assign(ir::name("sum"), zero),
               over("a", p,
                    {ir::laid_out(over("b", p,
                                       {ir::accumulate(ir::name("sum"), ir::mul(ir::mul(at("K", "i", p, "a"), r_ab),
                                                                                at("K", "j", p, "b")))}),
                                  ir::Layout::Fit)}),
               ir::assign(at("noise", "i", N, "j"), ir::name("sum"))})}));
  }
  for (std::size_t order = 3; order <= vars.order(); ++order) {
    const std::size_t size = power(n, order), rest = size / n;
    for (const auto& t : tuples(n, order))
      out.push_back(ir::assign(ir::element("tensor", flat(t, n)), ir::element("state", moment_variable(vars, t))));
    auto contraction = [&] { return over(
        "r", ir::integer(rest),
        {over("i", N,
              {ir::declare_variable("sum", ir::Type::Scalar, zero),
               over("a", N,
                    {ir::accumulate(ir::name("sum"),
                                    ir::mul(at("A", "i", N, "a"),
                                            ir::element("tensor", ir::add(ir::mul(ir::name("a"), ir::integer(rest)),
                                                                          ir::name("r")))))}),
               ir::assign(at("contracted", "r", N, "i"), ir::name("sum"))})}); };
    auto copy_back = [&] {
      return over("e", ir::integer(size),
                  {ir::assign(ir::element("tensor", ir::name("e")), ir::element("contracted", ir::name("e")))});
    };
    for (std::size_t turn = 0; turn < order; ++turn) {
      out.push_back(contraction());
      out.push_back(copy_back());
    }
    for (const auto& t : vars.higher_moments()) {
      if (t.size() != order) continue;
      std::vector<ir::Expr> terms = {ir::element("tensor", flat(t, n))};
      if (order == 4) {
        for (const auto& s : kSplits)
          terms.push_back(ir::mul(entry("apat", t[s[0]], t[s[1]], n), entry("noise", t[s[2]], t[s[3]], n)));
        for (const auto& s : kPairings)
          terms.push_back(ir::mul(entry("noise", t[s[0]], t[s[1]], n), entry("noise", t[s[2]], t[s[3]], n)));
      }
      out.push_back(ir::assign(ir::element("state", vars.higher_moment(t)), ir::sum(std::move(terms))));
    }
  }
  return out;
}

}  // namespace pfgen::codegen
