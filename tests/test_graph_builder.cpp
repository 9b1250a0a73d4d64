// GraphBuilder (codegen/graph_builder.hpp): polynomials over the filter variables, with
// coefficients in parameters and time, become ExpressionGraph nodes. Inputs are named as printed
// and read from their argument; integer powers are products by repeated squaring; monomials
// share their common prefix; coefficients with functions of time become calls. The round trip
// reads a graph back into a polynomial (with a conversion of this file's own, independent of the
// builder) and finds the polynomial it was built from, on seeded random polynomials.
#include <catch2/catch.hpp>

#include <functional>
#include <map>
#include <random>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/codegen/moment_form.hpp"
#include "pfgen/derivation/gaussian_expectation.hpp"
#include "pfgen/kinds/model_functions.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

namespace {

const Model& model() {
  static const Model m = load_model_text(R"model(name: unit
states: [x1, x2]
parameters: {a: 0.5, b: 2}
drift: ["-a*x1 + b*sin(t)", "-x2"]
diffusion: [["1", "0"], ["0", "1"]]
observation: {A: [["1", "0"]], B: [["1"]]}
)model",
                                         "unit.yaml");
  return m;
}

GiNaC::ex parameter(const std::string& name) {
  for (const auto& p : model().parameters)
    if (p.name == name) return p.symbol;
  throw std::logic_error("no parameter " + name);
}

Polynomial var(std::uint32_t v, std::uint32_t exponent = 1) {
  Polynomial p;
  p.add_term(Monomial::variable(v, exponent), 1);
  return p;
}

// Graph -> polynomial, node by node: inputs by name (filter variables, parameters, time),
// constants, arithmetic on polynomials, and calls of <cmath> functions on constants.
Polynomial to_polynomial(const ExpressionGraph& graph, std::size_t root, const FilterVariables& vars) {
  std::map<std::string, GiNaC::ex> symbols = {{model().time.get_name(), model().time}};
  for (const auto& p : model().parameters) symbols[p.name] = p.symbol;
  std::map<std::string, std::uint32_t> variables;
  for (std::uint32_t v = 0; v < vars.count(); ++v) variables[vars.text_name(v)] = v;
  const std::map<std::string, std::function<GiNaC::ex(const GiNaC::ex&)>> functions = {
      {"sin", [](const GiNaC::ex& e) { return GiNaC::sin(e); }},
      {"cos", [](const GiNaC::ex& e) { return GiNaC::cos(e); }},
      {"exp", [](const GiNaC::ex& e) { return GiNaC::exp(e); }},
      {"sqrt", [](const GiNaC::ex& e) { return GiNaC::sqrt(e); }}};

  std::vector<Polynomial> value(graph.size());
  auto constant_of = [&](std::size_t id) {
    const Polynomial& p = value[id];
    REQUIRE(p.terms().size() <= 1);
    if (p.is_zero()) return GiNaC::ex(0);
    REQUIRE(p.terms().begin()->first.is_one());
    return p.terms().begin()->second;
  };
  for (std::size_t id = 0; id <= root; ++id) {
    const Node& node = graph.node(id);
    const auto& a = node.args;
    switch (node.kind) {
      case OpKind::Input:
        value[id] = variables.count(node.name()) ? var(variables.at(node.name()))
                                               : Polynomial::constant(symbols.at(node.name()));
        break;
      case OpKind::Constant: value[id] = Polynomial::constant(node.value()); break;
      case OpKind::Add: value[id] = value[a[0]] + value[a[1]]; break;
      case OpKind::Sub: value[id] = value[a[0]] - value[a[1]]; break;
      case OpKind::Mul: value[id] = value[a[0]] * value[a[1]]; break;
      case OpKind::Neg: value[id] = value[a[0]].scaled(-1); break;
      case OpKind::Div: value[id] = value[a[0]].scaled(1 / constant_of(a[1])); break;
      case OpKind::Call:
        if (node.function == pfgen::codegen::Function::Pow) {
          value[id] = Polynomial::constant(GiNaC::pow(constant_of(a[0]), constant_of(a[1])));
        } else {
          REQUIRE(functions.count(function_name(node.function)) == 1);
          value[id] = Polynomial::constant(functions.at(function_name(node.function))(constant_of(a[0])));
        }
        break;
      case OpKind::ZeroWhereZero:
        value[id] = constant_of(a[0]).is_zero() ? Polynomial() : value[a[1]];
        break;
    }
  }
  return value[root];
}

// A random polynomial in the 5 variables of n = 2: up to 6 terms of degree up to 6, with rational
// coefficients, some times parameters, powers of them (1/a too), sums, or functions of time.
Polynomial random_polynomial(std::mt19937& rng) {
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const GiNaC::ex a = parameter("a"), b = parameter("b"), t = model().time;
  Polynomial p;
  const int terms = pick(1, 6);
  for (int k = 0; k < terms; ++k) {
    Monomial m;
    for (std::uint32_t v = 0; v < 5; ++v)
      if (pick(0, 2) == 0) m = m * Monomial::variable(v, static_cast<std::uint32_t>(pick(1, 4)));
    GiNaC::ex c = GiNaC::numeric(pick(1, 19) * (pick(0, 1) ? 1 : -1), pick(1, 7));
    switch (pick(0, 7)) {
      case 0: c *= a; break;
      case 1: c *= GiNaC::sin(t); break;
      case 2: c *= GiNaC::pow(a, 2) * b; break;
      case 3: c += a * GiNaC::numeric(pick(1, 5), 3); break;
      case 4: c /= a; break;
      case 5: c *= GiNaC::exp(-t) + GiNaC::sqrt(t); break;
      default: break;  // a plain rational, the common case
    }
    p.add_term(m, c);
  }
  return p;
}

}  // namespace

TEST_CASE("graph builder: inputs are named as printed and read from their argument", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(2);
  GraphBuilder builder(graph, model(), vars, "s", "q");
  const std::vector<std::size_t> order = builder.declaration_order();
  // Each input's source, as the C++ emitter spells it (the graph holds it unspelled).
  const pfgen::codegen::CppEmitter cpp(pfgen::codegen::ScalarMode::Double);
  std::vector<std::pair<std::string, std::string>> declared;
  for (std::size_t id : order) declared.emplace_back(graph.node(id).name(), cpp.input_source(graph.node(id)));
  CHECK(declared == std::vector<std::pair<std::string, std::string>>{
                        {"m1", "s[0]"}, {"m2", "s[1]"}, {"P11", "s[2]"}, {"P12", "s[3]"}, {"P22", "s[4]"},
                        {"a", "q.a"}, {"b", "q.b"}});
  CHECK(graph.node(order[3]).source().kind == pfgen::codegen::InputSource::Kind::Element);
  CHECK(graph.node(order[3]).source().container == "s");
  CHECK(graph.node(order[3]).source().index == 3);
  CHECK(graph.node(order[5]).source().kind == pfgen::codegen::InputSource::Kind::Field);
  CHECK(graph.node(order[5]).source().container == "q");
  // The time is the function's argument itself.
  const std::size_t t = builder.expression(model().time);
  CHECK(graph.node(t).kind == OpKind::Input);
  CHECK(graph.node(t).name() == "t");
  CHECK(graph.node(t).source().kind == pfgen::codegen::InputSource::Kind::Argument);
  CHECK(builder.variable(vars.P(1, 0)) == order[3]);

  // From n = 10 on the indices are separated, as pfgen prints them.
  ExpressionGraph big;
  GraphBuilder ten(big, model(), FilterVariables(10), "state", "params");
  CHECK(big.node(ten.variable(FilterVariables(10).P(0, 9))).name() == "P1_10");
  CHECK(big.node(ten.variable(FilterVariables(10).P(0, 9))).source().index == 19);
}

TEST_CASE("graph builder: which arguments the outputs read", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(2);
  GraphBuilder builder(graph, model(), vars);
  auto uses = [&](const Polynomial& p) { return builder.uses({builder.polynomial(p)}); };
  const InputUse none = uses(Polynomial::constant(3));
  CHECK_FALSE(none.variables);
  CHECK_FALSE(none.parameters);
  CHECK_FALSE(none.time);
  const InputUse m = uses(var(vars.m(0)));
  CHECK(m.variables);
  CHECK_FALSE(m.parameters);
  const InputUse a_sin_t = uses(Polynomial::constant(parameter("a") * GiNaC::sin(model().time)));
  CHECK_FALSE(a_sin_t.variables);
  CHECK(a_sin_t.parameters);
  CHECK(a_sin_t.time);
}

TEST_CASE("graph builder: integer powers are products by repeated squaring, never pow()", "[unit][codegen]") {
  const FilterVariables vars(2);
  // exponent -> multiplications: x^2 = x*x, x^4 = (x^2)^2, x^5 = x^4*x, x^7 = (x^3)^2*x, x^8 = ((x^2)^2)^2
  for (const auto& [exponent, muls] : std::vector<std::pair<std::uint32_t, std::size_t>>{
           {1, 0}, {2, 1}, {3, 2}, {4, 2}, {5, 3}, {7, 4}, {8, 3}}) {
    ExpressionGraph graph;
    GraphBuilder builder(graph, model(), vars);
    const std::size_t root = builder.polynomial(var(vars.m(0), exponent));
    const OpCounts counts = graph.shared_counts({root});
    INFO("m1^" << exponent);
    CHECK(counts.muls == muls);
    CHECK(counts.total() == muls);
  }
  // A negative integer power of a parameter is 1 / (product).
  ExpressionGraph graph;
  GraphBuilder builder(graph, model(), vars);
  const std::size_t inverse = builder.expression(GiNaC::pow(parameter("a"), -3));
  CHECK(graph.node(inverse).kind == OpKind::Div);
  CHECK(graph.shared_counts({inverse}).muls == 2);
  CHECK(graph.shared_counts({inverse}).calls == 0);
}

TEST_CASE("graph builder: monomials share their common prefix; sums keep the canonical term order",
          "[unit][codegen]") {
  const FilterVariables vars(2);
  ExpressionGraph graph;
  GraphBuilder builder(graph, model(), vars);
  // m1^2 m2 and m1^2 P11: m1*m1 once, then one product each.
  const std::size_t first = builder.polynomial(var(vars.m(0), 2) * var(vars.m(1)));
  const std::size_t second = builder.polynomial(var(vars.m(0), 2) * var(vars.P(0, 0)));
  CHECK(graph.shared_counts({first, second}).muls == 3);
  CHECK(graph.tree_counts({first, second}).muls == 4);

  // 3 m1^2 - m2: the higher degree first; a negative coefficient is a subtraction.
  const std::size_t p = builder.polynomial(var(vars.m(1)).scaled(-1) + var(vars.m(0), 2).scaled(3));
  const Node& root = graph.node(p);
  REQUIRE(root.kind == OpKind::Sub);
  CHECK(graph.node(root.args[1]).name() == "m2");
  CHECK(graph.node(root.args[0]).kind == OpKind::Mul);
  // A leading negative term is a negation; the zero polynomial a constant 0.
  CHECK(graph.node(builder.polynomial(var(vars.m(0)).scaled(-1))).kind == OpKind::Neg);
  const Node& zero = graph.node(builder.polynomial(Polynomial()));
  CHECK(zero.kind == OpKind::Constant);
  CHECK(zero.value().is_zero());
}

TEST_CASE("graph builder: coefficients with functions of time become calls of <cmath>", "[unit][codegen]") {
  const FilterVariables vars(2);
  ExpressionGraph graph;
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex t = model().time;
  auto call_name = [&](const GiNaC::ex& e) {
    const Node& node = graph.node(builder.expression(e));
    return node.kind == OpKind::Call ? std::string(function_name(node.function)) : std::string("(not a call)");
  };
  CHECK(call_name(GiNaC::sin(t)) == "sin");
  CHECK(call_name(GiNaC::exp(t)) == "exp");
  CHECK(call_name(GiNaC::sqrt(t)) == "sqrt");
  CHECK(call_name(GiNaC::pow(t, GiNaC::numeric(1, 3))) == "pow");
  // Every function a model may call is a call of its own, in both backends' table.
  for (const pfgen::ModelFunction& f : pfgen::model_functions()) {
    INFO(f.name);
    GiNaC::exvector args(f.arity, t);
    CHECK(call_name(GiNaC::function(GiNaC::function::find_function(f.name, static_cast<unsigned>(f.arity)), args)) ==
          f.name);
  }
  CHECK_THROWS_AS(builder.expression(GiNaC::zeta(t)), CodegenError);
  CHECK_THROWS_AS(builder.expression(GiNaC::I * t), CodegenError);
  CHECK_THROWS_AS(builder.expression(GiNaC::symbol("stranger")), CodegenError);
}

TEST_CASE("graph builder: reading the graph back gives the polynomial it was built from", "[unit][codegen]") {
  std::mt19937 rng(20240611);
  const FilterVariables vars(2);
  for (int run = 0; run < 200; ++run) {
    const Polynomial p = random_polynomial(rng);
    ExpressionGraph graph;
    GraphBuilder builder(graph, model(), vars);
    const std::size_t root = builder.polynomial(p);
    const Polynomial back = to_polynomial(graph, root, vars);
    INFO("run " << run << ": " << p.to_ex(vars.symbols()) << " came back as " << back.to_ex(vars.symbols()));
    CHECK(back == p);
  }
}

// The moment form (codegen/moment_form) writes E[q] as sum_a c_a E[x^a] over moments built once:
// read back, each expectation is the polynomial GaussianExpectation derives, with several
// expectations sharing one graph (and its moments) as derivatives() shares them.
TEST_CASE("moment form: expectations over shared moments read back as the derived expectations", "[unit][codegen]") {
  std::mt19937 rng(20261127);
  auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const FilterVariables vars(2);
  const GiNaC::ex a = parameter("a"), t = model().time;
  for (int run = 0; run < 50; ++run) {
    ExpressionGraph graph;
    GraphBuilder builder(graph, model(), vars);
    MomentForm form(builder, vars);
    GaussianExpectation expectation(vars);
    for (int k = 0; k < 4; ++k) {
      Polynomial q;  // over the states x1, x2 (variables 0 and 1)
      for (int term = pick(1, 6); term > 0; --term) {
        Monomial m;
        for (std::uint32_t v = 0; v < 2; ++v)
          if (pick(0, 2) > 0) m = m * Monomial::variable(v, static_cast<std::uint32_t>(pick(1, 3)));
        GiNaC::ex c = GiNaC::numeric(pick(1, 9) * (pick(0, 1) ? 1 : -1), pick(1, 4));
        if (pick(0, 3) == 0) c *= a;
        if (pick(0, 5) == 0) c *= GiNaC::sin(t);
        q.add_term(m, c);
      }
      const std::size_t root = form.expectation(q);
      const Polynomial back = to_polynomial(graph, root, vars), derived = expectation.of(q);
      INFO("run " << run << ": E[" << q.to_ex(vars.symbols()) << "] came back as " << back.to_ex(vars.symbols()));
      CHECK(back == derived);
    }
  }
}
