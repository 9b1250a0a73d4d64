// The statement IR (codegen/ir/statements.hpp) as the C-family emitters print it: each node by its
// own method, a loop's or a conditional's single statement on its header's line, a nested loop on
// the next line, several statements in braces, parentheses only where the builder grouped.
#include <catch2/catch.hpp>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/codegen/ir/statements.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

TEST_CASE("statement IR: every node as C++ and C print it", "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Template);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const ir::Expr i = ir::name("i"), n = ir::name("n");
  const ir::Block block = {
      ir::comment("a comment"),
      ir::unused("t"),
      ir::declare("d", ir::Type::Scalar, ir::sub(ir::element("S", 0), ir::mul(ir::name("a"), ir::number(2)))),
      ir::declare_array("w", ir::Type::Scalar, 4),
      ir::conditional(ir::logical_not(ir::grouped(ir::greater(ir::name("d"), ir::number(0)))),
                      {ir::return_value(ir::boolean(false))}),
      ir::loop("i", ir::Type::Size, ir::integer(0), n, {ir::accumulate(ir::element("x", i), ir::field("params", "a"))}),
      ir::loop("i", ir::Type::Int, ir::integer(0), ir::integer(3),
               {ir::loop("j", ir::Type::Int, i, ir::integer(3),
                         {ir::assign_all({ir::element("P", ir::add(ir::mul(i, ir::integer(3)), ir::name("j"))),
                                          ir::element("P", ir::add(ir::mul(ir::name("j"), ir::integer(3)), i))},
                                         ir::element("s", ir::add(ir::integer(3), ir::name("u"))))},
                         std::nullopt, "u")},
               ir::Loop::Follower{"u", ir::integer(0)}),
      ir::loop("i", ir::Type::Size, ir::integer(0), n,
               {ir::view("b", "B", ir::mul(i, n), n, false), ir::view("k", "K", ir::mul(i, n), n, true),
                ir::assign(ir::element("k", 0), ir::div(ir::grouped(ir::neg(ir::element("b", 0))), ir::name("d")))}),
      ir::call_statement("step", {ir::name("t"), ir::name("state")}),
      ir::return_value(ir::call(Function::Sqrt, {ir::name("d")})),
  };
  CHECK(cpp.block(block) ==
        "  // a comment\n"
        "  (void)t;\n"
        "  const Scalar d = S[0] - a * Scalar(2);\n"
        "  Scalar w[4];\n"
        "  if (!(d > Scalar(0))) return false;\n"
        "  for (std::size_t i = 0; i < n; ++i) x[i] += params.a;\n"
        "  for (int i = 0, u = 0; i < 3; ++i)\n"
        "    for (int j = i; j < 3; ++j, ++u) P[i * 3 + j] = P[j * 3 + i] = s[3 + u];\n"
        "  for (std::size_t i = 0; i < n; ++i) {\n"
        "    const Scalar* b = B + i * n;\n"
        "    Scalar* k = K + i * n;\n"
        "    k[0] = (-b[0]) / d;\n"
        "  }\n"
        "  step(t, state);\n"
        "  return std::sqrt(d);\n");
  CHECK(c.block(block) ==
        "  // a comment\n"
        "  (void)t;\n"
        "  const float d = S[0] - a * 2.0f;\n"
        "  float w[4];\n"
        "  if (!(d > 0.0f)) return 0;\n"
        "  for (size_t i = 0; i < n; ++i) x[i] += params->a;\n"
        "  for (int i = 0, u = 0; i < 3; ++i)\n"
        "    for (int j = i; j < 3; ++j, ++u) P[i * 3 + j] = P[j * 3 + i] = s[3 + u];\n"
        "  for (size_t i = 0; i < n; ++i) {\n"
        "    const float* b = B + i * n;\n"
        "    float* k = K + i * n;\n"
        "    k[0] = (-b[0]) / d;\n"
        "  }\n"
        "  step(t, state);\n"
        "  return sqrtf(d);\n");
}

TEST_CASE("statement IR: the file's sizes and whole numbers of the scalar as each language spells them",
          "[unit][codegen]") {
  // What a module writes once (codegen/heun_step.cpp) and every backend spells:
  // the sizes its file declares and a whole number in the scalar type.
  const ir::Expr i = ir::name("i");
  const ir::Block block = {ir::loop(
      "i", ir::Type::Size, ir::integer(0), ir::dimension("state_size"),
      {ir::accumulate(ir::element("x", i), ir::div(ir::element("y", ir::mul(i, ir::dimension("p"))), ir::whole_scalar(2)))})};
  CHECK(CppEmitter(ScalarMode::Float).block(block) ==
        "  for (std::size_t i = 0; i < state_size; ++i) x[i] += y[i * p] / Scalar(2);\n");
  CHECK(CEmitter(ScalarMode::Double, "tmp", "ns_m_f", "ns_m_f_params").block(block) ==
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) x[i] += y[i * ns_m_f_p] / 2.0;\n");
  CHECK(RustEmitter(ScalarMode::Float, "tmp", "Params").block(ir::Block{ir::assign(
            ir::element("x", ir::dimension("n")), ir::mul(ir::whole_scalar(2), ir::element("y", ir::dimension("p"))))}) ==
        "  x[STATES] = 2.0 * y[OBSERVATIONS];\n");
  CHECK(RustEmitter(ScalarMode::Double, "tmp", "Params").expression(ir::dimension("delay_steps")) == "DELAY_STEPS");
}
