// The filter parts the sampled and delayed modules build as statements (sampled_predict.hpp) as each backend's emitter writes them: the same nodes give C++'s, C's and
// Rust's text, and the local-array nodes (ir::local_arrays, ir::local_array) are spelled as each
// language declares and passes an array.
#include <catch2/catch.hpp>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

TEST_CASE("local arrays: declared together and passed whole, as each language does", "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Double);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Float, "tmp", "Params");
  const ir::Block block = {
      ir::local_arrays({"a", "b"}, ir::Type::Scalar, ir::sub(ir::name("N"), ir::name("M"))),
      ir::call_statement("f", {ir::local_array("a", false), ir::local_array("b", true)}),
  };
  CHECK(cpp.block(block) == "  std::array<Scalar, N - M> a{}, b{};\n  f(a.data(), b.data());\n");
  CHECK(c.block(block) == "  float a[N - M], b[N - M];\n  f(a, b);\n");
  CHECK(rust.block(block, "    ") ==
        "    let mut a: [Scalar; N - M] = [0.0; N - M];\n    let mut b: [Scalar; N - M] = [0.0; N - M];\n    f(&a, &mut b);\n");
}

TEST_CASE("sampled predict: Heun's and cd-euler's sub-step as statements for every language", "[unit][codegen]") {
  const CEmitter c(ScalarMode::Double, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Double, "tmp", "Params");
  CHECK(c.block(predict_statements(false)) ==
        "  double first[ns_m_f_state_size], predicted[ns_m_f_state_size], second[ns_m_f_state_size];\n"
        "  ns_m_f_derivatives(t, state, params, first);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) predicted[i] = state[i] + first[i] * dt;\n"
        "  ns_m_f_derivatives(t + dt, predicted, params, second);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) state[i] += (first[i] + second[i]) * dt / 2.0;\n");
  CHECK(c.block(predict_statements(true)) ==
        "  double rates[ns_m_f_state_size];\n"
        "  double square[ns_m_f_state_size - ns_m_f_n];\n"
        "  ns_m_f_derivatives(t, state, params, rates);\n"
        "  ns_m_f_euler_square(t, state, params, square);\n"
        "  for (size_t i = 0; i < ns_m_f_state_size; ++i) state[i] += rates[i] * dt;\n"
        "  for (size_t i = ns_m_f_n; i < ns_m_f_state_size; ++i) state[i] += square[i - ns_m_f_n] * dt * dt;\n");
  CHECK(rust_indent(rust.block(predict_statements(true))) ==
        "    let mut rates: [Scalar; STATE_SIZE] = [0.0; STATE_SIZE];\n"
        "    let mut square: [Scalar; STATE_SIZE - STATES] = [0.0; STATE_SIZE - STATES];\n"
        "    derivatives(t, state, params, &mut rates);\n"
        "    euler_square(t, state, params, &mut square);\n"
        "    for i in 0..STATE_SIZE {\n"
        "        state[i] += rates[i] * dt;\n"
        "    }\n"
        "    for i in STATES..STATE_SIZE {\n"
        "        state[i] += square[i - STATES] * dt * dt;\n"
        "    }\n");
}
