// The sampled update (joseph_update.hpp) as statements: the nodes it adds to the IR (a variable,
// `-=`, ==, a selection, a file's function as a value, an array from an offset, a post-increment,
// a loop's one statement below its header) as each backend's emitter writes them, and the update
// as C writes it (byte for byte the text C's filters have always had) and Rust (which borrows
// CR's parts only after observation_matrices() has written it: its template places the views last).
#include <catch2/catch.hpp>

#include <string>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/backends/cpp/cpp_emitter.hpp"
#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/sampled/joseph_update.hpp"

using namespace pfgen;
using namespace pfgen::codegen;

TEST_CASE("joseph update's nodes: each language's spelling", "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Double);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Float, "tmp", "Params");
  const ir::Block block = {
      ir::declare_variable("s", ir::Type::Scalar,
                           ir::select(ir::equal(ir::name("i"), ir::name("j")), ir::whole_scalar(1), ir::whole_scalar(0))),
      ir::decrease(ir::name("s"), ir::file_call("g", {ir::array_from("u", ir::name("N"), false), ir::name("i")})),
      ir::assign(ir::element("x", ir::post_increment("k")), ir::name("s")),
      ir::laid_out(ir::loop("a", ir::Type::Size, ir::integer(0), ir::name("N"), {ir::accumulate(ir::name("s"), ir::name("a"))}),
                   ir::Layout::NextLine),
  };
  CHECK(c.block(block) ==
        "  float s = i == j ? 1.0f : 0.0f;\n"
        "  s -= ns_m_f_g(u + N, i);\n"
        "  x[k++] = s;\n"
        "  for (size_t a = 0; a < N; ++a)\n"
        "    s += a;\n");
  CHECK(cpp.block(block) ==
        "  Scalar s = i == j ? Scalar(1) : Scalar(0);\n"
        "  s -= g(u.data() + N, i);\n"
        "  x[k++] = s;\n"
        "  for (std::size_t a = 0; a < N; ++a)\n"
        "    s += a;\n");
  CHECK(rust_indent(rust.block(block)) ==
        "    let mut s: Scalar = if i == j { 1.0 } else { 0.0 };\n"
        "    s -= g(&u[N..], i);\n"
        "    x[{ k += 1; k - 1 }] = s;\n"
        "    for a in 0..N {\n"
        "        s += a;\n"
        "    }\n");
  // A view from an array's start is the array (C), its first entries (Rust).
  const ir::Block view = {ir::view("C", "CR", ir::integer(0), ir::name("M"), false)};
  CHECK(c.block(view) == "  const float* C = CR;\n");
  CHECK(rust.block(view) == "  let C = &CR[..M];\n");
}

TEST_CASE("joseph update: C's text from the statements, Rust's views after the calls", "[unit][codegen]") {
  const CEmitter c(ScalarMode::Double, "tmp", "f", "f_params");
  const JosephUpdate u = joseph_update_statements();
  const std::string text = c.block(u.arrays) + c.block(u.views) + c.block(u.solve) + c.block(u.update);
  CHECK(text ==
        "  double u[f_n * f_p + f_p * (f_p + 1) / 2];\n"
        "  double CR[f_p * f_n + f_p * (f_p + 1) / 2];\n"
        "  double K[f_n * f_p];\n"
        "  double h[f_p];\n"
        "  double P[f_n * f_n], A[f_n * f_n], AP[f_n * f_n];\n"
        "  const double* C = CR;\n"
        "  const double* R = CR + f_p * f_n;\n"
        "  size_t k = f_n;\n"
        "  f_innovation_terms(t, state, params, u);\n"
        "  if (!f_solve_gain(u, u + f_n * f_p, K)) return 0;\n"
        "  f_observation_matrices(t, state, params, CR);\n"
        "  f_predicted_observation(t, state, params, h);\n"
        "  for (size_t i = 0; i < f_n; ++i)\n"
        "    for (size_t j = i; j < f_n; ++j) {\n"
        "      P[i * f_n + j] = state[k++];\n"
        "      P[j * f_n + i] = P[i * f_n + j];\n"
        "    }\n"
        "  for (size_t i = 0; i < f_n; ++i)\n"
        "    for (size_t r = 0; r < f_p; ++r) state[i] += K[i * f_p + r] * (y[r] - h[r]);\n"
        "  // A = Id - K C\n"
        "  for (size_t i = 0; i < f_n; ++i)\n"
        "    for (size_t j = 0; j < f_n; ++j) {\n"
        "      double sum = i == j ? 1.0 : 0.0;\n"
        "      for (size_t r = 0; r < f_p; ++r) sum -= K[i * f_p + r] * C[r * f_n + j];\n"
        "      A[i * f_n + j] = sum;\n"
        "    }\n"
        "  for (size_t i = 0; i < f_n; ++i)\n"
        "    for (size_t j = 0; j < f_n; ++j) {\n"
        "      double sum = 0.0;\n"
        "      for (size_t l = 0; l < f_n; ++l) sum += A[i * f_n + l] * P[l * f_n + j];\n"
        "      AP[i * f_n + j] = sum;\n"
        "    }\n"
        "  k = f_n;\n"
        "  for (size_t i = 0; i < f_n; ++i)\n"
        "    for (size_t j = i; j < f_n; ++j) {\n"
        "      double sum = 0.0;\n"
        "      for (size_t l = 0; l < f_n; ++l) sum += AP[i * f_n + l] * A[j * f_n + l];\n"
        "      for (size_t a = 0; a < f_p; ++a)\n"
        "        for (size_t b = 0; b < f_p; ++b)\n"
        "          sum += K[i * f_p + a] * f_packed_at(R, a, b) * K[j * f_p + b];\n"
        "      state[k++] = sum;\n"
        "    }\n"
        "  return 1;\n");
  // No backend's template writes the update itself any more: C and Rust place the four parts
  // (Rust's views after the calls that fill CR), C++'s keeps its own form.
  for (const char* name : {"c/sampled_filter.c.tmpl", "rust/sampled_filter.rs.tmpl"}) {
    INFO(name);
    const std::string tmpl = embedded_template(name);
    CHECK(tmpl.find("// A = Id - K C") == std::string::npos);
    CHECK(tmpl.find("packed_at(R, a, b)") == std::string::npos);
  }
  const std::string rust = embedded_template("rust/sampled_filter.rs.tmpl");
  CHECK(rust.find("{{update_solve}}{{update_views}}") != std::string::npos);
}
