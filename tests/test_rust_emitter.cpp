// RustEmitter (codegen/backends/rust/rust_emitter.hpp): the same graph as the C backend's in Rust:
// `let` declarations of the module's Scalar, literals that read back to the same f32 or f64 with
// no suffix and no parentheses, <math.h>'s functions through the module's extern declarations,
// parameters through a reference; no templates; the names Rust code cannot bind refused when a
// model is read; and on the command line the options Rust has no use for.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/codegen/codegen_error.hpp"
#include "pfgen/codegen/graph_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/refusal.hpp"
#include "support/test_paths.hpp"

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

}  // namespace

TEST_CASE("rust emitter: let declarations, <math.h> through extern declarations, parameters by reference",
          "[unit][codegen]") {
  ExpressionGraph graph;
  const FilterVariables vars(1);
  GraphBuilder builder(graph, model(), vars);
  const GiNaC::ex a = model().parameters.at(0).symbol;
  const std::vector<std::size_t> roots = {builder.polynomial(var(vars.m(0), 2).scaled(a)),
                                          builder.expression(GiNaC::sin(model().time) + GiNaC::abs(model().time))};
  const FunctionSignature signature{"derivatives", "t", {"state"}, "params", "out"};
  const RustEmitter emitter(ScalarMode::Float, "tmp", "Params");
  const FunctionBody body = emitter.function_body(graph, roots, signature, builder.declaration_order(), true);
  CHECK(body.helpers.empty());
  CHECK(body.statements ==
        "  let m1: Scalar = state[0];\n"
        "  let a: Scalar = params.a;\n"
        "  let tmp0: Scalar = m1 * m1;\n"
        "  let tmp1: Scalar = a * tmp0;\n"
        "  let tmp2: Scalar = unsafe { c_math::fabsf(t) };\n"
        "  let tmp3: Scalar = unsafe { c_math::sinf(t) };\n"
        "  let tmp4: Scalar = tmp2 + tmp3;\n"
        "  out[0] = tmp1;\n"
        "  out[1] = tmp4;\n");
  // Only what the bodies call is declared, in f32.
  CHECK(emitter.math_declarations() ==
        "// The C library's <math.h> functions the bodies call (libm; newlib on a microcontroller): core\n"
        "// has none without std, and these give the C backend's numbers bit for bit.\n"
        "mod c_math {\n    extern \"C\" {\n        pub fn fabsf(x: f32) -> f32;\n        pub fn sinf(x: f32) -> f32;\n"
        "    }\n}\n\n");
  // An argument the body does not read is bound to `_`.
  const FunctionBody unused = emitter.function_body(graph, {roots[0]}, signature, builder.declaration_order(), true);
  CHECK(unused.statements.rfind("  let _ = t;\n", 0) == 0);
}

TEST_CASE("rust emitter: literals read back to the same value, without suffix or parentheses", "[unit][codegen]") {
  const RustEmitter f64(ScalarMode::Double, "tmp", "Params"), f32(ScalarMode::Float, "tmp", "Params");
  CHECK(f64.literal_text(GiNaC::numeric(1, 10)) == "0.1");
  CHECK(f64.literal_text(GiNaC::numeric(-1, 2)) == "-0.5");  // Rust's unary minus binds tighter than *
  CHECK(f64.literal_text(GiNaC::numeric(2)) == "2.0");
  CHECK(f32.literal_text(GiNaC::numeric(1, 10)) == "0.1");
  CHECK(f32.literal_text(GiNaC::numeric(-1, 3)) == "-0.33333334");
  // Every digit string reads back to the scalar it stands for.
  for (const auto& value : {GiNaC::numeric(1, 3), GiNaC::numeric(-7, 1000000), GiNaC::numeric(123456789, 7)}) {
    CHECK(std::strtod(f64.literal_text(value).c_str(), nullptr) == value.to_double());
    CHECK(std::strtof(f32.literal_text(value).c_str(), nullptr) == static_cast<float>(value.to_double()));
  }
  CHECK(f64.zero_where_zero("g", "v") == "if g == 0.0 { 0.0 } else { v }");
  CHECK_THROWS_AS(RustEmitter(ScalarMode::Template, "tmp", "Params"), CodegenError);
}

TEST_CASE("rust emitter: names Rust code cannot bind are refused when the model is read", "[unit][codegen]") {
  for (const std::string name : {"type", "fn", "None", "STATE_SIZE"}) {
    INFO(name);
    const std::string text = "name: rust_names\nstates: [x]\nparameters: {" + name + ": 0.5}\ndrift: [\"-" + name +
                             "*x\"]\ndiffusion: [[\"1\"]]\nobservation: {A: [[\"1\"]], B: [[\"1\"]]}\n";
    CHECK_THROWS_WITH(load_model_text(text, "rust_names.yaml"), Catch::Matchers::Contains("Rust"));
  }
}

TEST_CASE("pfgen codegen --language rust refuses what Rust has no use for", "[integration][codegen]") {
  const pfgen_test::TempDir dir;
  const std::string model = pfgen_test::example("van_der_pol.yaml");
  pfgen_test::check_refused_in_one_line({"codegen", model, "--language", "rust", "--scalar", "template", "-o", dir.path()},
                                        "--scalar template: Rust has no templates; give float or double");
  pfgen_test::check_refused_in_one_line({"codegen", model, "--language", "rust", "--eigen", "-o", dir.path()},
                                        "--eigen: the Eigen wrappers are C++; drop --eigen for --language rust");
}
