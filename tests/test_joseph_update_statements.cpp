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
#include "pfgen/observations/sampled/sampled_predict.hpp"

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
  const std::string text = c.block(u.arrays) + c.block(u.matrices) + c.block(u.views) + c.block(u.counter) +
                           c.block(u.solve) + c.block(u.update);
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
  // No backend's template writes the update itself any more: C and Rust place the six parts
  // (Rust's views after the calls that fill CR); C++'s too (below).
  for (const char* name : {"c/sampled_filter.c.tmpl", "rust/sampled_filter.rs.tmpl"}) {
    INFO(name);
    const std::string tmpl = embedded_template(name);
    CHECK(tmpl.find("// A = Id - K C") == std::string::npos);
    CHECK(tmpl.find("packed_at(R, a, b)") == std::string::npos);
  }
  const std::string rust = embedded_template("rust/sampled_filter.rs.tmpl");
  CHECK(rust.find("{{update_solve}}{{update_views}}{{update_counter}}") != std::string::npos);
}

TEST_CASE("joseph update: C++'s text from the same statements, its parts in its own order", "[unit][codegen]") {
  // Byte for byte the update C++'s sampled_filter template has always written: std::arrays passed by
  // data(), the gain's solve in namespace detail, R's packed entries through a lambda R_at that the
  // packed view declares, P's two entries stored by one chained assignment, and the a/b loop's one
  // statement on its header's line (it fits in the width; C's, longer, goes below).
  const CppEmitter cpp(ScalarMode::Template);
  const JosephUpdate u = joseph_update_statements();
  const std::string text = cpp.block(u.arrays) + cpp.block(u.solve) + cpp.block(u.views) + cpp.block(u.matrices) +
                           cpp.block(u.counter) + cpp.block(u.update);
  CHECK(text ==
        "  std::array<Scalar, n * p + p * (p + 1) / 2> u{};\n"
        "  std::array<Scalar, p * n + p * (p + 1) / 2> CR{};\n"
        "  std::array<Scalar, n * p> K{};\n"
        "  std::array<Scalar, p> h{};\n"
        "  innovation_terms(t, state, params, u.data());\n"
        "  if (!detail::solve_gain(u.data(), u.data() + n * p, K.data())) return false;\n"
        "  observation_matrices(t, state, params, CR.data());\n"
        "  predicted_observation(t, state, params, h.data());\n"
        "  const Scalar* C = CR.data();\n"
        "  const Scalar* R = CR.data() + p * n;\n"
        "  auto R_at = [&](std::size_t a, std::size_t b) {\n"
        "    if (a > b) { const std::size_t c = a; a = b; b = c; }\n"
        "    return R[a * p - a * (a + 1) / 2 + b];\n"
        "  };\n"
        "  std::array<Scalar, n * n> P{}, A{}, AP{};\n"
        "  std::size_t k = n;\n"
        "  for (std::size_t i = 0; i < n; ++i)\n"
        "    for (std::size_t j = i; j < n; ++j) P[i * n + j] = P[j * n + i] = state[k++];\n"
        "  for (std::size_t i = 0; i < n; ++i)\n"
        "    for (std::size_t r = 0; r < p; ++r) state[i] += K[i * p + r] * (y[r] - h[r]);\n"
        "  // A = Id - K C\n"
        "  for (std::size_t i = 0; i < n; ++i)\n"
        "    for (std::size_t j = 0; j < n; ++j) {\n"
        "      Scalar sum = i == j ? Scalar(1) : Scalar(0);\n"
        "      for (std::size_t r = 0; r < p; ++r) sum -= K[i * p + r] * C[r * n + j];\n"
        "      A[i * n + j] = sum;\n"
        "    }\n"
        "  for (std::size_t i = 0; i < n; ++i)\n"
        "    for (std::size_t j = 0; j < n; ++j) {\n"
        "      Scalar sum = Scalar(0);\n"
        "      for (std::size_t l = 0; l < n; ++l) sum += A[i * n + l] * P[l * n + j];\n"
        "      AP[i * n + j] = sum;\n"
        "    }\n"
        "  k = n;\n"
        "  for (std::size_t i = 0; i < n; ++i)\n"
        "    for (std::size_t j = i; j < n; ++j) {\n"
        "      Scalar sum = Scalar(0);\n"
        "      for (std::size_t l = 0; l < n; ++l) sum += AP[i * n + l] * A[j * n + l];\n"
        "      for (std::size_t a = 0; a < p; ++a)\n"
        "        for (std::size_t b = 0; b < p; ++b) sum += K[i * p + a] * R_at(a, b) * K[j * p + b];\n"
        "      state[k++] = sum;\n"
        "    }\n"
        "  return true;\n");
  // The template places the parts and writes none of them.
  const std::string tmpl = embedded_template("cpp/sampled_filter.hpp.tmpl");
  CHECK(tmpl.find("// A = Id - K C") == std::string::npos);
  CHECK(tmpl.find("R_at") == std::string::npos);
  CHECK(tmpl.find("{{update_arrays}}{{update_solve}}{{update_views}}{{update_matrices}}{{update_counter}}{{update_body}}") !=
        std::string::npos);
}

TEST_CASE("joseph update's C++ nodes: a packed view and its entries, a symmetric store, a line that fits", "[unit][codegen]") {
  const CppEmitter cpp(ScalarMode::Double);
  const CEmitter c(ScalarMode::Float, "tmp", "ns_m_f", "ns_m_f_params");
  const RustEmitter rust(ScalarMode::Float, "tmp", "Params");
  const ir::Expr q = ir::name("q");
  const ir::Block block = {
      ir::packed_local_view("S", "W", ir::name("o"), q),
      ir::local_view("V", "W", ir::integer(0), q),
      ir::loop("j", ir::Type::Size, ir::integer(0), q,
               {ir::assign_symmetric(ir::element("X", ir::name("j")), ir::element("Y", ir::name("j")),
                                     ir::packed_entry("S", ir::name("j"), ir::integer(0)))}),
      ir::laid_out(ir::loop("j", ir::Type::Size, ir::integer(0), q, {ir::accumulate(ir::name("s"), ir::name("j"))}),
                   ir::Layout::Fit),
      ir::conditional(ir::logical_not(ir::internal_call("g", {ir::local_array("W", false)})), {ir::return_value(ir::boolean(false))}),
  };
  CHECK(cpp.block(block) ==
        "  const Scalar* S = W.data() + o;\n"
        "  auto S_at = [&](std::size_t a, std::size_t b) {\n"
        "    if (a > b) { const std::size_t c = a; a = b; b = c; }\n"
        "    return S[a * q - a * (a + 1) / 2 + b];\n"
        "  };\n"
        "  const Scalar* V = W.data();\n"
        "  for (std::size_t j = 0; j < q; ++j) X[j] = Y[j] = S_at(j, 0);\n"
        "  for (std::size_t j = 0; j < q; ++j) s += j;\n"
        "  if (!detail::g(W.data())) return false;\n");
  CHECK(c.block(block) ==
        "  const float* S = W + o;\n"
        "  const float* V = W;\n"
        "  for (size_t j = 0; j < q; ++j) {\n"
        "    X[j] = ns_m_f_packed_at(S, j, 0);\n"
        "    Y[j] = X[j];\n"
        "  }\n"
        "  for (size_t j = 0; j < q; ++j) s += j;\n"
        "  if (!ns_m_f_g(W)) return 0;\n");
  CHECK(rust_indent(rust.block(block)) ==
        "    let S = &W[o..o + q * (q + 1) / 2];\n"
        "    let V = &W[..q];\n"
        "    for j in 0..q {\n"
        "        Y[j] = packed_at(S, j, 0);\n"
        "        X[j] = Y[j];\n"
        "    }\n"
        "    for j in 0..q {\n"
        "        s += j;\n"
        "    }\n"
        "    if !g(&W) {\n"
        "        return false;\n"
        "    }\n");
  // A body that does not fit in the width goes on the next line.
  const std::string long_name(90, 'z');
  const ir::Block wide = {ir::laid_out(
      ir::loop("j", ir::Type::Size, ir::integer(0), q, {ir::accumulate(ir::name(long_name), ir::name("j"))}), ir::Layout::Fit)};
  CHECK(cpp.block(wide) == "  for (std::size_t j = 0; j < q; ++j)\n    " + long_name + " += j;\n");
}

TEST_CASE("sampled advance(): the sub-steps and the update as statements, each language's text as its template had it",
          "[unit][codegen]") {
  const ir::Block advance = advance_statements();
  // A conversion of an index to the scalar and the period, a function template of the scalar alone.
  CHECK(CppEmitter(ScalarMode::Template).block(advance) ==
        "  const Scalar dt = period<Scalar>() / Scalar(substeps);\n"
        "  for (std::size_t s = 0; s < substeps; ++s) predict(state, t + Scalar(s) * dt, dt, params);\n"
        "  return update(state, t + period<Scalar>(), y, params);\n");
  CHECK(CppEmitter(ScalarMode::Float).block(advance) ==
        "  const Scalar dt = period() / Scalar(substeps);\n"
        "  for (std::size_t s = 0; s < substeps; ++s) predict(state, t + Scalar(s) * dt, dt, params);\n"
        "  return update(state, t + period(), y, params);\n");
  CHECK(CEmitter(ScalarMode::Double, "tmp", "f", "f_params").block(advance) ==
        "  const double dt = f_period() / (double)f_substeps;\n"
        "  for (size_t s = 0; s < f_substeps; ++s) f_predict(state, t + (double)s * dt, dt, params);\n"
        "  return f_update(state, t + f_period(), y, params);\n");
  CHECK(rust_indent(RustEmitter(ScalarMode::Float, "tmp", "Params").block(advance)) ==
        "    let dt: Scalar = period() / SUBSTEPS as Scalar;\n"
        "    for s in 0..SUBSTEPS {\n"
        "        predict(state, t + s as Scalar * dt, dt, params);\n"
        "    }\n"
        "    return update(state, t + period(), y, params);\n");
  for (const char* name : {"cpp/sampled_filter.hpp.tmpl", "c/sampled_filter.c.tmpl", "rust/sampled_filter.rs.tmpl"}) {
    INFO(name);
    const std::string tmpl = embedded_template(name);
    CHECK(tmpl.find("{{advance_body}}") != std::string::npos);
    CHECK(tmpl.find("predict(state, t +") == std::string::npos);
  }
}
