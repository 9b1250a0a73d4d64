// ExpressionGraph (codegen/expression_graph.hpp): hash-consing (the same operation on the same
// operands is one node, commutative operations in either order too), node numbers in creation
// order with operands before their users, which nodes outputs need, and operation counts with
// and without sharing.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"

using namespace pfgen::codegen;

TEST_CASE("expression graph: the same operation on the same operands is one node", "[unit][codegen]") {
  ExpressionGraph g;
  const std::size_t x = g.input("x", InputSource::element("state", 0));
  const std::size_t y = g.input("y", InputSource::element("state", 1));
  CHECK(g.input("x", InputSource::element("state", 0)) == x);
  CHECK(g.input("x") == x);  // a name is one input, whatever the source given later
  CHECK(g.node(x).source().container == "state");
  CHECK(g.node(x).source().index == 0);
  CHECK(x != y);

  const std::size_t third = g.constant(GiNaC::numeric(1, 3));
  CHECK(g.constant(GiNaC::numeric(1, 3)) == third);
  CHECK(g.constant(GiNaC::numeric(2, 3)) != third);

  // Commutative operations share a node whatever the operand order; the others do not.
  CHECK(g.mul(x, y) == g.mul(y, x));
  CHECK(g.add(x, y) == g.add(y, x));
  CHECK(g.sub(x, y) != g.sub(y, x));
  CHECK(g.div(x, y) != g.div(y, x));
  CHECK(g.sub(x, y) == g.sub(x, y));
  CHECK(g.neg(x) == g.neg(x));
  CHECK(g.neg(x) != g.neg(y));
  CHECK(g.mul(x, y) != g.add(x, y));
  CHECK(g.call(Function::Sin, {x}) == g.call(Function::Sin, {x}));
  CHECK(g.call(Function::Sin, {x}) != g.call(Function::Cos, {x}));
  CHECK(g.call(Function::Pow, {x, y}) != g.call(Function::Pow, {y, x}));

  const std::size_t before = g.size();
  g.mul(g.add(y, x), g.mul(y, x));  // both operands exist: one new node only
  CHECK(g.size() == before + 1);
}

TEST_CASE("expression graph: nodes are numbered in creation order, operands first", "[unit][codegen]") {
  ExpressionGraph g;
  const std::size_t x = g.input("x", InputSource::element("state", 0));
  const std::size_t two = g.constant(2);
  const std::size_t square = g.mul(x, x);
  const std::size_t sum = g.add(g.mul(two, square), g.call(Function::Exp, {x}));
  CHECK(x == 0);
  CHECK(two == 1);
  CHECK(square == 2);
  CHECK(sum == g.size() - 1);
  for (std::size_t id = 0; id < g.size(); ++id)
    for (std::size_t arg : g.node(id).args) CHECK(arg < id);
  CHECK(g.is_leaf(x));
  CHECK(g.is_leaf(two));
  CHECK_FALSE(g.is_leaf(square));
}

// The rules the graph applies as it is built are exact in IEEE arithmetic (negation is exact and
// rounding symmetric about zero; x * 1 is x), so the generated code's values do not depend on them;
// each saves an operation or costs none.
TEST_CASE("expression graph: signs fold into sums and a product with exact 1 is its other factor", "[unit][codegen]") {
  ExpressionGraph g;
  const std::size_t a = g.input("a"), b = g.input("b");
  const std::size_t one = g.constant(GiNaC::numeric(1));
  CHECK(g.mul(a, one) == a);
  CHECK(g.mul(one, b) == b);
  CHECK(g.mul(a, g.constant(GiNaC::numeric(1.0))) != a);  // a float 1.0 is the model's number, kept as written
  CHECK(g.add(a, g.neg(b)) == g.sub(a, b));
  CHECK(g.add(g.neg(a), b) == g.sub(b, a));
  CHECK(g.sub(a, g.neg(b)) == g.add(a, b));
  CHECK(g.neg(g.neg(a)) == a);
  const std::size_t both = g.add(g.neg(a), g.neg(b));  // no cheaper form without a negation
  CHECK(g.node(both).kind == OpKind::Add);
  CHECK(g.shared_counts({g.add(a, g.neg(b))}).total() == 1);
}

TEST_CASE("expression graph: what outputs need, in topological order without leaves", "[unit][codegen]") {
  ExpressionGraph g;
  const std::size_t x = g.input("x", InputSource::element("state", 0));
  const std::size_t y = g.input("y", InputSource::element("state", 1));
  const std::size_t z = g.input("z", InputSource::element("state", 2));
  const std::size_t xy = g.mul(x, y);
  const std::size_t unused = g.mul(y, z);
  const std::size_t out = g.add(xy, g.mul(x, x));

  CHECK(g.needed_operations({out}) == std::vector<std::size_t>{xy, xy + 2, out});
  CHECK(g.needed_operations({xy}) == std::vector<std::size_t>{xy});
  CHECK(g.needed_operations({x}).empty());
  CHECK(g.needed_operations({}).empty());

  const std::vector<bool> needed = g.needed({out});
  CHECK(needed[x]);
  CHECK(needed[y]);
  CHECK_FALSE(needed[z]);
  CHECK_FALSE(needed[unused]);
  CHECK(needed[out]);
  CHECK(g.needed({z})[z]);  // an output needs itself
}

TEST_CASE("expression graph: operation counts with and without sharing", "[unit][codegen]") {
  ExpressionGraph g;
  const std::size_t x = g.input("x", InputSource::element("state", 0));
  const std::size_t y = g.input("y", InputSource::element("state", 1));
  const std::size_t xy = g.mul(x, y);                         // 1 mul
  const std::size_t a = g.add(xy, g.constant(1));             // 1 add
  const std::size_t b = g.sub(xy, g.div(x, y));               // 1 add (sub), 1 div
  const std::size_t c = g.neg(g.call(Function::Sin, {xy}));      // 1 add (neg), 1 call
  const std::vector<std::size_t> outputs = {a, b, c};

  const OpCounts shared = g.shared_counts(outputs);
  CHECK(shared.adds == 3);
  CHECK(shared.muls == 1);
  CHECK(shared.divs == 1);
  CHECK(shared.calls == 1);
  CHECK(shared.total() == 6);

  // As separate trees, x*y is computed once per output that reads it.
  const OpCounts tree = g.tree_counts(outputs);
  CHECK(tree.adds == 3);
  CHECK(tree.muls == 3);
  CHECK(tree.divs == 1);
  CHECK(tree.calls == 1);

  // Within one output too: (x*y) + (x*y) is one product shared, two as a tree.
  const std::size_t doubled = g.add(xy, xy);
  CHECK(g.shared_counts({doubled}).muls == 1);
  CHECK(g.tree_counts({doubled}).muls == 2);
  CHECK(g.shared_counts({x, g.constant(3)}).total() == 0);

  OpCounts sum = shared;
  sum += tree;
  CHECK(sum.adds == 6);
  CHECK(sum.muls == 4);
  CHECK(sum.divs == 2);
  CHECK(sum.calls == 2);
  CHECK(sum.total() == shared.total() + tree.total());
}

// The index is an open-addressing table that grows as nodes are added (expression_graph.cpp): every
// node must still be found after many growths, and equal constants stay one node only when they
// would be spelled alike (an exact 2 and a float 2.0 are two constants; a float prints with a point).
TEST_CASE("expression graph: a large graph finds every node again, and constants keep their exactness",
          "[unit][codegen]") {
  ExpressionGraph g;
  std::vector<std::size_t> inputs;
  for (int k = 0; k < 300; ++k) inputs.push_back(g.input("x" + std::to_string(k), InputSource::element("state", k)));
  std::vector<std::size_t> products, sums;
  for (std::size_t a = 0; a < inputs.size(); ++a)
    for (std::size_t b = a; b < inputs.size(); ++b) products.push_back(g.mul(inputs[a], inputs[b]));
  for (std::size_t k = 1; k < products.size(); ++k) sums.push_back(g.sub(products[k], products[k - 1]));
  const std::size_t size = g.size();
  CHECK(size == 300 + 45150 + 45149);
  std::size_t k = 0;
  for (std::size_t a = 0; a < inputs.size(); ++a)
    for (std::size_t b = a; b < inputs.size(); ++b) CHECK(g.mul(inputs[b], inputs[a]) == products[k++]);
  for (std::size_t j = 1; j < products.size(); ++j) CHECK(g.sub(products[j], products[j - 1]) == sums[j - 1]);
  CHECK(g.size() == size);
  for (int j = 0; j < 300; ++j) CHECK(g.node(inputs[j]).name() == "x" + std::to_string(j));

  const std::size_t exact_two = g.constant(GiNaC::numeric(2));
  const std::size_t float_two = g.constant(GiNaC::numeric(2.0));
  CHECK(exact_two != float_two);
  CHECK(g.constant(GiNaC::numeric(4, 2)) == exact_two);
  CHECK(g.constant(GiNaC::numeric(2.0)) == float_two);
  CHECK(g.node(exact_two).value().is_rational());
  CHECK_FALSE(g.node(float_two).value().is_rational());
  CHECK(g.is_leaf(float_two));
}
