#include "pfgen/observations/sampled/sampled_moment_update.hpp"

#include <algorithm>
#include <map>

#include "pfgen/codegen/filter_file.hpp"

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

// The state variable that holds the moment with these indices (in any order): P's entry at order 2.
std::uint32_t moment_variable(const FilterVariables& vars, std::vector<std::size_t> t) {
  std::sort(t.begin(), t.end());
  return t.size() == 2 ? vars.P(t[0], t[1]) : vars.higher_moment(t);
}

// The six ways to take one pair of four indices for U and the other for Q, and the three pairings for Q Q.
constexpr std::size_t kSplits[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {2, 3, 0, 1}, {1, 3, 0, 2}, {1, 2, 0, 3}};
constexpr std::size_t kPairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};

}  // namespace

MomentsAfterUpdate updated_moments(const FilterVariables& vars, const NumericMatrix& A, const JointMoment& z,
                                   const NumericMatrix& Q) {
  const std::size_t n = vars.n(), N = A.front().size();
  MomentsAfterUpdate out;
  out.higher.resize(vars.higher_moments().size());
  NumericMatrix U;  // A Z2 A^T
  for (std::size_t order = 2; order <= vars.order(); ++order) {
    // The full tensor of z's moments, then A on the first index (which moves last), `order` times: the first index
    // runs over N entries, the contracted ones over n.
    std::vector<GiNaC::numeric> tensor;
    for (const auto& t : tuples(N, order)) {
      std::vector<std::size_t> sorted = t;
      std::sort(sorted.begin(), sorted.end());
      tensor.push_back(z(sorted));
    }
    for (std::size_t turn = 0; turn < order; ++turn) {
      const std::size_t rest = tensor.size() / N;
      std::vector<GiNaC::numeric> contracted(rest * n);
      for (std::size_t r = 0; r < rest; ++r)
        for (std::size_t i = 0; i < n; ++i) {
          GiNaC::numeric sum = 0;
          for (std::size_t a = 0; a < N; ++a) sum += A[i][a] * tensor[a * rest + r];
          contracted[r * n + i] = sum;
        }
      tensor.swap(contracted);
    }
    if (order == 2) {
      U.assign(n, std::vector<GiNaC::numeric>(n));
      out.P.assign(n, std::vector<GiNaC::numeric>(n));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
          U[i][j] = tensor[i * n + j];
          out.P[i][j] = U[i][j] + Q[i][j];
        }
      continue;
    }
    for (std::size_t q = 0; q < vars.higher_moments().size(); ++q) {
      const std::vector<std::size_t>& t = vars.higher_moments()[q];
      if (t.size() != order) continue;
      GiNaC::numeric value = tensor[flat(t, n)];
      if (order == 4) {
        for (const auto& s : kSplits) value += U[t[s[0]]][t[s[1]]] * Q[t[s[2]]][t[s[3]]];
        for (const auto& s : kPairings) value += Q[t[s[0]]][t[s[1]]] * Q[t[s[2]]][t[s[3]]];
      }
      out.higher[q] = value;
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

// tensor <- `A`'s contraction with tensor's first index, which moves last: contracted(r, i) = sum_a A_ia tensor(a, r)
// for r over `rest` entries and a over A's `columns` (A n x columns, row-major); then tensor = contracted (rest n
// entries).
void contract(ir::Block& out, const std::string& A, const ir::Expr& columns, std::size_t rest, std::size_t n) {
  const ir::Expr N = ir::dimension("n"), zero = ir::whole_scalar(0);
  out.push_back(over(
      "r", ir::integer(rest),
      {over("i", N,
            {ir::declare_variable("sum", ir::Type::Scalar, zero),
             over("a", columns,
                  {ir::accumulate(ir::name("sum"),
                                  ir::mul(at(A, "i", columns, "a"),
                                          ir::element("tensor", ir::add(ir::mul(ir::name("a"), ir::integer(rest)),
                                                                        ir::name("r")))))}),
             ir::assign(at("contracted", "r", N, "i"), ir::name("sum"))})}));
  out.push_back(over("e", ir::integer(rest * n),
                     {ir::assign(ir::element("tensor", ir::name("e")), ir::element("contracted", ir::name("e")))}));
}

// noise = K R K^T (n x n), and with `apat` also apat = AP A^T.
ir::Statement noise_statement(bool apat) {
  const ir::Expr N = ir::dimension("n"), p = ir::dimension("p"), zero = ir::whole_scalar(0);
  const ir::Expr r_ab = ir::packed_entry("R", ir::name("a"), ir::name("b"));
  ir::Block body = {ir::declare_variable("sum", ir::Type::Scalar, zero)};
  if (apat) {
    body.push_back(over("l", N, {ir::accumulate(ir::name("sum"), ir::mul(at("AP", "i", N, "l"), at("A", "j", N, "l")))}));
    body.push_back(ir::assign(at("apat", "i", N, "j"), ir::name("sum")));
    body.push_back(ir::assign(ir::name("sum"), zero));
  }
  body.push_back(over("a", p,
                      {ir::laid_out(over("b", p,
                                         {ir::accumulate(ir::name("sum"), ir::mul(ir::mul(at("K", "i", p, "a"), r_ab),
                                                                                  at("K", "j", p, "b")))}),
                                    ir::Layout::Fit)}));
  body.push_back(ir::assign(at("noise", "i", N, "j"), ir::name("sum")));
  return over("i", N, {over("j", N, std::move(body))});
}

// The order-4 moment with indices t: the contracted tensor's entry and the noise's terms (U in apat).
ir::Expr fourth_moment(const std::vector<std::size_t>& t, std::size_t n) {
  std::vector<ir::Expr> terms = {ir::element("tensor", flat(t, n))};
  for (const auto& s : kSplits)
    terms.push_back(ir::mul(entry("apat", t[s[0]], t[s[1]], n), entry("noise", t[s[2]], t[s[3]], n)));
  for (const auto& s : kPairings)
    terms.push_back(ir::mul(entry("noise", t[s[0]], t[s[1]], n), entry("noise", t[s[2]], t[s[3]], n)));
  return ir::sum(std::move(terms));
}

}  // namespace

ir::Block moment_update_statements(const FilterVariables& vars) {
  if (vars.higher_moments().empty()) return {};
  const std::size_t n = vars.n();
  const ir::Expr N = ir::dimension("n");
  ir::Block out;
  out.push_back(ir::comment("The higher central moments of the updated law: A on each index, and at order 4 the "
                            "noise's terms (docs/theory.md)"));
  out.push_back(ir::local_arrays({"tensor", "contracted"}, ir::Type::Scalar, ir::integer(power(n, vars.order()))));
  if (vars.order() >= 4) {
    out.push_back(ir::local_arrays({"apat", "noise"}, ir::Type::Scalar, ir::mul(N, N)));
    out.push_back(noise_statement(true));
  }
  for (std::size_t order = 3; order <= vars.order(); ++order) {
    for (const auto& t : tuples(n, order))
      out.push_back(ir::assign(ir::element("tensor", flat(t, n)), ir::element("state", moment_variable(vars, t))));
    for (std::size_t turn = 0; turn < order; ++turn) contract(out, "A", N, power(n, order - 1), n);
    for (const auto& t : vars.higher_moments())
      if (t.size() == order)
        out.push_back(ir::assign(ir::element("state", vars.higher_moment(t)),
                                 order == 4 ? fourth_moment(t, n) : ir::element("tensor", flat(t, n))));
  }
  return out;
}

JosephUpdate joint_moment_update_statements(const FilterVariables& vars, std::size_t r,
                                            const std::vector<std::vector<std::size_t>>& joint) {
  const std::size_t n = vars.n(), columns = n + r, order = vars.order();
  const ir::Expr N = ir::dimension("n"), p = ir::dimension("p"), width = ir::integer(columns);
  std::map<std::vector<std::size_t>, std::size_t> joint_entry;
  for (std::size_t q = 0; q < joint.size(); ++q) joint_entry.emplace(joint[q], q);
  JosephUpdate u = joseph_update_statements();
  u.arrays.push_back(ir::local_arrays({"z"}, ir::Type::Scalar, ir::integer(joint.size())));
  u.matrices = {ir::local_arrays({"A", "noise"}, ir::Type::Scalar, ir::mul(N, N)),
                ir::local_arrays({"Abar"}, ir::Type::Scalar, ir::mul(N, width)),
                ir::local_arrays({"tensor", "contracted"}, ir::Type::Scalar, ir::integer(power(columns, order)))};
  if (order >= 4) u.matrices.push_back(ir::local_arrays({"apat"}, ir::Type::Scalar, ir::mul(N, N)));
  u.counter.clear();
  // Before m moves: z's moments are the prior's.
  u.solve.push_back(state_function_call("joint_moments", ir::name("t"), ir::name("state"), "z"));
  ir::Block& out = u.update;
  out = mean_and_gain_complement_statements();
  out.push_back(ir::comment("Abar = [A, -K]: x+ - m+ = Abar z - K v (docs/theory.md)"));
  out.push_back(over("i", N,
                     {over("j", N, {ir::assign(at("Abar", "i", width, "j"), at("A", "i", N, "j"))}),
                      over("r", p, {ir::assign(ir::element("Abar", ir::add(ir::add(ir::mul(ir::name("i"), width), N),
                                                                           ir::name("r"))),
                                               ir::neg(at("K", "i", p, "r")))})}));
  out.push_back(noise_statement(false));
  out.push_back(ir::comment("P and the higher central moments: Abar on each index of z's moments, and the noise's "
                            "terms"));
  for (std::size_t k = 2; k <= order; ++k) {
    for (const auto& t : tuples(columns, k)) {
      std::vector<std::size_t> sorted = t;
      std::sort(sorted.begin(), sorted.end());
      out.push_back(ir::assign(ir::element("tensor", flat(t, columns)),
                               sorted.back() < n ? ir::element("state", moment_variable(vars, sorted))
                                                 : ir::element("z", joint_entry.at(sorted))));
    }
    for (std::size_t turn = 0; turn < k; ++turn) contract(out, "Abar", width, power(columns, k - 1 - turn) * power(n, turn), n);
    if (k == 2) {
      if (order >= 4)
        out.push_back(over("e", ir::mul(N, N), {ir::assign(ir::element("apat", ir::name("e")),
                                                           ir::element("tensor", ir::name("e")))}));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i; j < n; ++j)
          out.push_back(ir::assign(ir::element("state", vars.P(i, j)),
                                   ir::add(entry("tensor", i, j, n), entry("noise", i, j, n))));
      continue;
    }
    for (const auto& t : vars.higher_moments())
      if (t.size() == k)
        out.push_back(ir::assign(ir::element("state", vars.higher_moment(t)),
                                 k == 4 ? fourth_moment(t, n) : ir::element("tensor", flat(t, n))));
  }
  out.push_back(ir::return_value(ir::boolean(true)));
  return u;
}

}  // namespace pfgen::codegen
