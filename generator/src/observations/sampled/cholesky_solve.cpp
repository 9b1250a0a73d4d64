#include "pfgen/observations/sampled/cholesky_solve.hpp"

#include <string>
#include <vector>

namespace pfgen::codegen {
namespace {

// What the solve reads besides PCt, S and K: the file's sizes and the scalar 0.
struct CholeskyNames {
  ir::Expr n, p, zero;
};

ir::Expr L(std::size_t a, std::size_t b) { return ir::name("L" + std::to_string(a) + "_" + std::to_string(b)); }

std::size_t packed(std::size_t a, std::size_t b, std::size_t r) {
  return a * r - a * (a + 1) / 2 + b;  // a <= b
}

// first - terms[0] - terms[1] - ..., left to right.
ir::Expr minus(ir::Expr first, std::vector<ir::Expr> terms) {
  for (ir::Expr& term : terms) first = ir::sub(std::move(first), std::move(term));
  return first;
}

}  // namespace

ir::Block cholesky_gain_statements(std::size_t r) {
  const CholeskyNames names{ir::dimension("n"), ir::dimension("p"), ir::whole_scalar(0)};
  using ir::Type;
  ir::Block body;
  // S = L L^T, column by column: L_jj = sqrt(S_jj - sum_k L_jk^2), L_ij = (S_ji - sum_k L_ik L_jk) / L_jj.
  for (std::size_t j = 0; j < r; ++j) {
    std::vector<ir::Expr> squares;
    for (std::size_t k = 0; k < j; ++k) squares.push_back(ir::mul(L(j, k), L(j, k)));
    const std::string d = "d" + std::to_string(j);
    body.push_back(ir::declare(d, Type::Scalar, minus(ir::element("S", packed(j, j, r)), std::move(squares))));
    body.push_back(ir::conditional(ir::logical_not(ir::grouped(ir::greater(ir::name(d), names.zero))),
                                   {ir::return_value(ir::boolean(false))}));
    body.push_back(ir::declare(L(j, j).name, Type::Scalar, ir::call(Function::Sqrt, {ir::name(d)})));
    for (std::size_t i = j + 1; i < r; ++i) {
      std::vector<ir::Expr> products;
      for (std::size_t k = 0; k < j; ++k) products.push_back(ir::mul(L(i, k), L(j, k)));
      body.push_back(ir::declare(
          L(i, j).name, Type::Scalar,
          ir::div(ir::grouped(minus(ir::element("S", packed(j, i, r)), std::move(products))), L(j, j))));
    }
  }
  // Each row k of K solves S k = b (b the row of PCt): L z = b, then L^T k = z.
  const ir::Expr i = ir::name("i");
  ir::Block row = {ir::view("b", "PCt", ir::mul(i, names.p), names.p, false),
                   ir::view("k", "K", ir::mul(i, names.p), names.p, true)};
  for (std::size_t a = 0; a < r; ++a) {
    std::vector<ir::Expr> known;
    for (std::size_t c = 0; c < a; ++c) known.push_back(ir::mul(L(a, c), ir::name("z" + std::to_string(c))));
    row.push_back(ir::declare("z" + std::to_string(a), Type::Scalar,
                              ir::div(ir::grouped(minus(ir::element("b", a), std::move(known))), L(a, a))));
  }
  for (std::size_t a = r; a-- > 0;) {
    std::vector<ir::Expr> known;
    for (std::size_t c = a + 1; c < r; ++c) known.push_back(ir::mul(L(c, a), ir::element("k", c)));
    row.push_back(ir::assign(ir::element("k", a),
                             ir::div(ir::grouped(minus(ir::name("z" + std::to_string(a)), std::move(known))), L(a, a))));
  }
  body.push_back(ir::loop("i", Type::Size, ir::integer(0), names.n, std::move(row)));
  body.push_back(ir::return_value(ir::boolean(true)));
  return body;
}

}  // namespace pfgen::codegen
