#include "pfgen/observations/sampled/joseph_update.hpp"

#include <utility>

#include "pfgen/codegen/filter_file.hpp"

namespace pfgen::codegen {
namespace {

using ir::Expr;
using ir::Type;

Expr index(const char* name) { return ir::name(name); }

// array[row * columns + column]: an entry of a row-major matrix.
Expr at(const std::string& array, const char* row, const Expr& columns, const char* column) {
  return ir::element(array, ir::add(ir::mul(index(row), columns), index(column)));
}

// for index in [begin, end): body.
ir::Statement over(const char* name, Expr begin, const Expr& end, ir::Block body) {
  return ir::loop(name, Type::Size, std::move(begin), end, std::move(body));
}

// name(t, state, params, out): a function of the filter state writing the local array `out`.
ir::Statement call(const std::string& function, const std::string& out) {
  return state_function_call(function, ir::name("t"), ir::name("state"), out);
}

}  // namespace

ir::Block mean_and_gain_complement_statements() {
  const Expr n = ir::dimension("n"), p = ir::dimension("p");
  const Expr zero = ir::whole_scalar(0), one = ir::whole_scalar(1);
  const Expr i = index("i"), j = index("j");
  ir::Block out;
  // m += K (y - h).
  out.push_back(over(
      "i", ir::integer(0), n,
      {over("r", ir::integer(0), p,
            {ir::accumulate(ir::element("state", i),
                            ir::mul(at("K", "i", p, "r"),
                                    ir::grouped(ir::sub(ir::element("y", index("r")), ir::element("h", index("r"))))))})}));
  out.push_back(ir::comment("A = Id - K C"));
  out.push_back(over(
      "i", ir::integer(0), n,
      {over("j", ir::integer(0), n,
            {ir::declare_variable("sum", Type::Scalar, ir::select(ir::equal(i, j), one, zero)),
             over("r", ir::integer(0), p, {ir::decrease(ir::name("sum"), ir::mul(at("K", "i", p, "r"), at("C", "r", n, "j")))}),
             ir::assign(at("A", "i", n, "j"), ir::name("sum"))})}));
  return out;
}

JosephUpdate joseph_update_statements() {
  const Expr n = ir::dimension("n"), p = ir::dimension("p");
  const Expr zero = ir::whole_scalar(0), one = ir::whole_scalar(1);
  // p (p + 1) / 2: the packed upper triangle of a p x p matrix (S, R).
  const Expr triangle = ir::div(ir::mul(p, ir::grouped(ir::add(p, ir::integer(1)))), ir::integer(2));
  JosephUpdate u;
  u.arrays = {ir::local_arrays({"u"}, Type::Scalar, ir::add(ir::mul(n, p), triangle)),
              ir::local_arrays({"CR"}, Type::Scalar, ir::add(ir::mul(p, n), triangle)),
              ir::local_arrays({"K"}, Type::Scalar, ir::mul(n, p)),
              ir::local_arrays({"h"}, Type::Scalar, p)};
  u.matrices = {ir::local_arrays({"P", "A", "AP"}, Type::Scalar, ir::mul(n, n))};
  u.views = {ir::local_view("C", "CR", ir::integer(0), ir::mul(p, n)), ir::packed_local_view("R", "CR", ir::mul(p, n), p)};
  u.counter = {ir::declare_variable("k", Type::Size, n)};
  u.solve = {call("innovation_terms", "u"),
             ir::conditional(ir::logical_not(ir::internal_call("solve_gain", {ir::local_array("u", false),
                                                                          ir::array_from("u", ir::mul(n, p), false),
                                                                          ir::local_array("K", true)})),
                             {ir::return_value(ir::boolean(false))}),
             call("observation_matrices", "CR"),
             call("predicted_observation", "h")};
  const Expr i = index("i"), j = index("j");
  // P (n x n) from its packed upper triangle, the state after m.
  u.update.push_back(over("i", ir::integer(0), n,
                          {over("j", i, n,
                                {ir::assign_symmetric(at("P", "i", n, "j"), at("P", "j", n, "i"),
                                                      ir::element("state", ir::post_increment("k")))})}));
  for (ir::Statement& s : mean_and_gain_complement_statements()) u.update.push_back(std::move(s));
  // AP = A P.
  u.update.push_back(over(
      "i", ir::integer(0), n,
      {over("j", ir::integer(0), n,
            {ir::declare_variable("sum", Type::Scalar, zero),
             over("l", ir::integer(0), n, {ir::accumulate(ir::name("sum"), ir::mul(at("A", "i", n, "l"), at("P", "l", n, "j")))}),
             ir::assign(at("AP", "i", n, "j"), ir::name("sum"))})}));
  // P = AP A^T + K R K^T, its upper triangle back into the state.
  u.update.push_back(ir::assign(ir::name("k"), n));
  const Expr r_ab = ir::packed_entry("R", index("a"), index("b"));
  u.update.push_back(over(
      "i", ir::integer(0), n,
      {over("j", i, n,
            {ir::declare_variable("sum", Type::Scalar, zero),
             over("l", ir::integer(0), n, {ir::accumulate(ir::name("sum"), ir::mul(at("AP", "i", n, "l"), at("A", "j", n, "l")))}),
             over("a", ir::integer(0), p,
                  {ir::laid_out(over("b", ir::integer(0), p,
                                     {ir::accumulate(ir::name("sum"), ir::mul(ir::mul(at("K", "i", p, "a"), r_ab),
                                                                              at("K", "j", p, "b")))}),
                                ir::Layout::Fit)}),
             ir::assign(ir::element("state", ir::post_increment("k")), ir::name("sum"))})}));
  u.update.push_back(ir::return_value(ir::boolean(true)));
  return u;
}

}  // namespace pfgen::codegen
