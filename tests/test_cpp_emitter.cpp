// CppEmitter (codegen/cpp_emitter.hpp): literals in each scalar mode (float code stays float:
// every literal carries `f`), the inputs declared once at the top, temporaries for each needed
// operation in topological order, the tree form without temporaries, and integer powers written
// as products.
#include <catch2/catch.hpp>

#include <regex>

#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

namespace {

const Model& model() {
  static const Model m = load_model_text(R"model(name: unit
states: [x1]
parameters: {a: 0.5}
drift: ["-a*x1"]
diffusion: [["1"]]
observation: {A: [["1"]], B: [["1"]]}
)model",
                                         "unit.yaml");
  return m;
}

Polynomial var(std::uint32_t v, std::uint32_t exponent = 1) {
  Polynomial p;
  p.add_term(Monomial::variable(v, exponent), 1);
  return p;
}

// Number literals in C++ text that are not float literals (no `f` suffix), outside of names
// (m1, P11, tmp3, state[0] are no literals) and array indices.
std::vector<std::string> non_float_literals(const std::string& code) {
  std::vector<std::string> found;
  const std::regex number(R"((^|[^A-Za-z0-9_.\[])([0-9]+\.?[0-9]*(e[-+]?[0-9]+)?)(f?))");
  for (auto it = std::sregex_iterator(code.begin(), code.end(), number); it != std::sregex_iterator(); ++it)
    if ((*it)[4].str().empty()) found.push_back((*it)[2].str());
  return found;
}

}  // namespace

TEST_CASE("emitter: literals follow the scalar mode", "[unit][codegen]") {
  const CppEmitter f(ScalarMode::Float), d(ScalarMode::Double), t(ScalarMode::Template);
  const GiNaC::numeric tenth(1, 10), third(1, 3), two(2), minus_half(-1, 2);
  CHECK(f.literal(tenth) == "0.1f");
  CHECK(f.literal(third) == "0.33333334f");  // the shortest text that reads back as float(1/3)
  CHECK(f.literal(two) == "2.0f");
  CHECK(f.literal(minus_half) == "(-0.5f)");
  CHECK(f.literal(GiNaC::numeric(1, 1000000000)) == "1e-09f");
  CHECK(d.literal(tenth) == "0.1");
  CHECK(d.literal(third) == "0.3333333333333333");
  CHECK(d.literal(two) == "2.0");
  CHECK(d.literal(minus_half) == "(-0.5)");
  CHECK(t.literal(tenth) == "Scalar(0.1)");
  CHECK(t.literal(two) == "Scalar(2)");
  CHECK(t.literal(minus_half) == "(Scalar(-0.5))");
  CHECK(t.literal(GiNaC::numeric(10000000)) == "Scalar(1e+07)");  // large integers as floating literals
  CHECK(scalar_mode_name(ScalarMode::Float) == "float");
  CHECK(scalar_mode_name(ScalarMode::Double) == "double");
  CHECK(scalar_mode_name(ScalarMode::Template) == "template");

  // Beyond the scalar's range a literal would print as inf: refused.
  const GiNaC::numeric huge = GiNaC::numeric(10).power(39);
  CHECK_THROWS_AS(f.literal(huge), CodegenError);
  CHECK(d.literal(huge) == "1e+39");
  CHECK_THROWS_AS(d.literal(GiNaC::numeric(10).power(309)), CodegenError);
}

TEST_CASE("emitter: inputs once at the top, then each needed operation once, in order", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex a = model().parameters.at(0).symbol;
  // out[0] = m1^2 P11 + a m1^2 (m1^2 shared), out[1] = P11; m1, P11 and a read, t not.
  const Polynomial square = var(vars.m(0), 2);
  const std::vector<std::size_t> roots = {builder.polynomial(square * var(vars.P(0, 0)) + square.scaled(a)),
                                          builder.polynomial(var(vars.P(0, 0)))};
  const CppEmitter emitter(ScalarMode::Double);
  CHECK(emitter.input_declarations(graph, roots, builder.declaration_order()) ==
        "  const Scalar m1 = state[0];\n"
        "  const Scalar P11 = state[1];\n"
        "  const Scalar a = params.a;\n");
  CHECK(emitter.input_declarations(graph, {roots[1]}, builder.declaration_order()) ==
        "  const Scalar P11 = state[1];\n");
  // The time has no declaration: it is the function's argument.
  const std::size_t time = builder.expression(model().time);
  CHECK(emitter.input_declarations(graph, {time}, {time}).empty());

  const std::string body = emitter.shared_body(graph, roots, "out");
  CHECK(body ==
        "  const Scalar tmp0 = m1 * m1;\n"
        "  const Scalar tmp1 = P11 * tmp0;\n"
        "  const Scalar tmp2 = a * tmp0;\n"
        "  const Scalar tmp3 = tmp1 + tmp2;\n"
        "  out[0] = tmp3;\n"
        "  out[1] = P11;\n");
  CHECK(CppEmitter(ScalarMode::Double, "tmp_").shared_body(graph, roots, std::vector<std::string>{"x", "y[3]"}) ==
        "  const Scalar tmp_0 = m1 * m1;\n"
        "  const Scalar tmp_1 = P11 * tmp_0;\n"
        "  const Scalar tmp_2 = a * tmp_0;\n"
        "  const Scalar tmp_3 = tmp_1 + tmp_2;\n"
        "  x = tmp_3;\n"
        "  y[3] = P11;\n");
  // Without sharing: every output one nested expression, no temporaries.
  CHECK(emitter.tree_body(graph, roots, "out") ==
        "  out[0] = ((P11 * (m1 * m1)) + (a * (m1 * m1)));\n"
        "  out[1] = P11;\n");
}

TEST_CASE("emitter: integer powers are written as products, calls by their <cmath> names", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const std::vector<std::size_t> roots = {builder.polynomial(var(vars.m(0), 5)),
                                          builder.expression(GiNaC::sin(model().time))};
  const std::string body = CppEmitter(ScalarMode::Double).shared_body(graph, roots, "h");
  CHECK(body ==
        "  const Scalar tmp0 = m1 * m1;\n"
        "  const Scalar tmp1 = tmp0 * tmp0;\n"
        "  const Scalar tmp2 = m1 * tmp1;\n"  // operands of * and + in node order
        "  const Scalar tmp3 = std::sin(t);\n"
        "  h[0] = tmp2;\n"
        "  h[1] = tmp3;\n");
  CHECK(body.find("pow") == std::string::npos);
}

TEST_CASE("emitter: float code holds float literals only", "[unit][codegen]") {
  // The scan itself finds a double literal, and passes names and indices.
  CHECK(non_float_literals("x = 0.5 * tmp1 + state[2];") == std::vector<std::string>{"0.5"});
  CHECK(non_float_literals("x = 0.5f * m1 + 2.0f + P11 + 1e-09f;").empty());

  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex a = model().parameters.at(0).symbol;
  Polynomial p = var(vars.m(0), 3).scaled(GiNaC::numeric(1, 3));
  p += var(vars.P(0, 0)).scaled(-2 * a + GiNaC::numeric(7, 10));
  p += Polynomial::constant(GiNaC::numeric(-5) + GiNaC::pow(a, -2));
  const std::vector<std::size_t> roots = {builder.polynomial(p)};
  const std::string shared = CppEmitter(ScalarMode::Float).shared_body(graph, roots, "out");
  const std::string tree = CppEmitter(ScalarMode::Float).tree_body(graph, roots, "out");
  INFO(shared << tree);
  CHECK(non_float_literals(shared).empty());
  CHECK(non_float_literals(tree).empty());
  CHECK(shared.find("0.33333334f") != std::string::npos);
  CHECK(shared.find("double") == std::string::npos);
  // The same graph in double mode does hold double literals: the scan is not vacuous.
  CHECK_FALSE(non_float_literals(CppEmitter(ScalarMode::Double).shared_body(graph, roots, "out")).empty());
}
