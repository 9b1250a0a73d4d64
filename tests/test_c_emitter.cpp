// CEmitter (codegen/backends/c/c_emitter.hpp): the C99 spelling of the same graph the C++ backend
// writes: declarations of `double`/`float`, <math.h> names for the scalar type (sinf, fabs),
// parameters through a pointer (params->a); no templates; and a body too large for one function
// split into static functions that name only what they read and compute the same operations, with
// the same temporaries, as the unsplit body.
#include <catch2/catch.hpp>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
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

CEmitter c_emitter(ScalarMode mode) { return CEmitter(mode, "tmp", "ns_unit_optimal", "ns_unit_optimal_params"); }

}  // namespace

TEST_CASE("c emitter: C's declarations, <math.h> names per scalar, parameters through a pointer", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex a = model().parameters.at(0).symbol;
  const std::vector<std::size_t> roots = {builder.polynomial(var(vars.m(0), 2).scaled(a)),
                                          builder.expression(GiNaC::sin(model().time) + GiNaC::abs(model().time))};
  const FunctionSignature signature{"derivatives", "t", {"state"}, "params", "out"};
  const FunctionBody body =
      c_emitter(ScalarMode::Float).function_body(graph, roots, signature, builder.declaration_order(), true);
  CHECK(body.helpers.empty());
  CHECK(body.statements ==
        "  const float m1 = state[0];\n"
        "  const float a = params->a;\n"
        "  const float tmp0 = m1 * m1;\n"
        "  const float tmp1 = a * tmp0;\n"
        "  const float tmp2 = fabsf(t);\n"  // GiNaC's order of the sum's terms
        "  const float tmp3 = sinf(t);\n"
        "  const float tmp4 = tmp2 + tmp3;\n"
        "  out[0] = tmp1;\n"
        "  out[1] = tmp4;\n");
  CHECK(c_emitter(ScalarMode::Double).call(Function::Sqrt, {"d0"}) == "sqrt(d0)");
  CHECK(c_emitter(ScalarMode::Double).call(Function::Abs, {"x"}) == "fabs(x)");
  CHECK(c_emitter(ScalarMode::Float).literal(GiNaC::numeric(1, 10)) == "0.1f");
  CHECK(c_emitter(ScalarMode::Double).literal(GiNaC::numeric(-1, 2)) == "(-0.5)");
  // The same graph in C++: the same statements but for the spellings.
  const FunctionBody cpp = CppEmitter(ScalarMode::Float).function_body(graph, roots, signature,
                                                                       builder.declaration_order(), true);
  CHECK(cpp.statements.find("std::sin(t)") != std::string::npos);
  CHECK(cpp.statements.find("params.a") != std::string::npos);
  CHECK_THROWS_AS(c_emitter(ScalarMode::Template), CodegenError);
}

TEST_CASE("c emitter: a split body is static functions computing the unsplit body's operations", "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex a = model().parameters.at(0).symbol;
  const Polynomial square = var(vars.m(0), 2);
  // out[0] = m1^2 P11 + a m1^2, out[1] = P11 (t read by neither).
  const std::vector<std::size_t> roots = {builder.polynomial(square * var(vars.P(0, 0)) + square.scaled(a)),
                                          builder.polynomial(var(vars.P(0, 0)))};
  const FunctionSignature signature{"gain", "t", {"state"}, "params", "K"};
  CEmitter emitter = c_emitter(ScalarMode::Double);
  const FunctionBody whole = emitter.function_body(graph, roots, signature, builder.declaration_order(), true);
  emitter.split_above(2, "shared");
  const FunctionBody split = emitter.function_body(graph, roots, signature, builder.declaration_order(), true);
  INFO(split.helpers << split.statements);
  CHECK(split.statements ==
        "  // 4 operations in 2 parts of at most 2, each its own function: one function this large takes a "
        "compiler minutes.\n"
        "  double shared[2];\n"
        "  ns_unit_optimal_gain_part0(t, state, params, K, shared);\n"
        "  ns_unit_optimal_gain_part1(t, state, params, K, shared);\n");
  CHECK(split.helpers ==
        "static void ns_unit_optimal_gain_part0(double t, const double* state, const ns_unit_optimal_params* params, "
        "double* K, double* shared) {\n"
        "  (void)t;\n"
        "  (void)params;\n"
        "  (void)K;\n"
        "  const double m1 = state[0];\n"
        "  const double P11 = state[1];\n"
        "  const double tmp0 = m1 * m1;\n"
        "  const double tmp1 = P11 * tmp0;\n"
        "  shared[0] = tmp0;\n"
        "  shared[1] = tmp1;\n"
        "}\n\n"
        "static void ns_unit_optimal_gain_part1(double t, const double* state, const ns_unit_optimal_params* params, "
        "double* K, double* shared) {\n"
        "  (void)t;\n"
        "  const double P11 = state[1];\n"
        "  const double a = params->a;\n"
        "  const double tmp0 = shared[0];\n"
        "  const double tmp1 = shared[1];\n"
        "  const double tmp2 = a * tmp0;\n"
        "  const double tmp3 = tmp1 + tmp2;\n"
        "  K[0] = tmp3;\n"
        "  K[1] = P11;\n"
        "}\n\n");
  // Each operation of the unsplit body appears once among the parts, with its temporary's number.
  for (const char* line : {"const double tmp0 = m1 * m1;", "const double tmp1 = P11 * tmp0;",
                           "const double tmp2 = a * tmp0;", "const double tmp3 = tmp1 + tmp2;"}) {
    CHECK(whole.statements.find(line) != std::string::npos);
    CHECK(split.helpers.find(line) != std::string::npos);
  }
}
