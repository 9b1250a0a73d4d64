// A filter for sampled observations in Rust (templates/rust/sampled_filter.rs.tmpl, with the
// partials of cd-euler's dt^2 term and of the prediction sub-step).
#include "pfgen/codegen/backends/rust/rust_filter_code.hpp"
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/codegen/template_text.hpp"
#include "pfgen/observations/sampled/sampled_code.hpp"

namespace pfgen::codegen {
namespace {

std::string L(std::size_t a, std::size_t b) { return "L" + std::to_string(a) + "_" + std::to_string(b); }

std::string packed(std::size_t a, std::size_t b, std::size_t r) {
  return std::to_string(a * r - a * (a + 1) / 2 + b);  // a <= b
}

// solve_gain's body: the C backend's Cholesky solve (observations/sampled/cholesky_solve.cpp),
// the same operations in the same order, in Rust.
std::string cholesky_gain_body(std::size_t r, const RustEmitter& emitter) {
  const std::string& scalar = emitter.scalar_type();
  const std::string zero = emitter.literal_text(0);
  std::string body;
  for (std::size_t j = 0; j < r; ++j) {
    std::string pivot = "S[" + packed(j, j, r) + "]";
    for (std::size_t k = 0; k < j; ++k) pivot += " - " + L(j, k) + " * " + L(j, k);
    const std::string d = "d" + std::to_string(j);
    body += "    let " + d + ": " + scalar + " = " + pivot + ";\n";
    body += "    if !(" + d + " > " + zero + ") {\n        return false;\n    }\n";
    body += "    let " + L(j, j) + ": " + scalar + " = " + emitter.call(Function::Sqrt, {d}) + ";\n";
    for (std::size_t i = j + 1; i < r; ++i) {
      std::string entry = "S[" + packed(j, i, r) + "]";
      for (std::size_t k = 0; k < j; ++k) entry += " - " + L(i, k) + " * " + L(j, k);
      body += "    let " + L(i, j) + ": " + scalar + " = (" + entry + ") / " + L(j, j) + ";\n";
    }
  }
  // Each row k of K solves S k = b (b the row of PCt): L z = b, then L^T k = z.
  body += "    for i in 0..STATES {\n";
  body += "        let b = &PCt[i * OBSERVATIONS..(i + 1) * OBSERVATIONS];\n";
  body += "        let k = &mut K[i * OBSERVATIONS..(i + 1) * OBSERVATIONS];\n";
  for (std::size_t a = 0; a < r; ++a) {
    std::string z = "b[" + std::to_string(a) + "]";
    for (std::size_t c = 0; c < a; ++c) z += " - " + L(a, c) + " * z" + std::to_string(c);
    body += "        let z" + std::to_string(a) + ": " + scalar + " = (" + z + ") / " + L(a, a) + ";\n";
  }
  for (std::size_t a = r; a-- > 0;) {
    std::string x = "z" + std::to_string(a);
    for (std::size_t c = a + 1; c < r; ++c) x += " - " + L(c, a) + " * k[" + std::to_string(c) + "]";
    body += "        k[" + std::to_string(a) + "] = (" + x + ") / " + L(a, a) + ";\n";
  }
  body += "    }\n    true\n";
  return body;
}

std::string filled_partial(const std::string& name, const std::map<std::string, std::string>& values) {
  const std::string text = expanded_template(name);
  std::map<std::string, std::string> used;
  for (const auto& [key, value] : values)
    if (text.find("{{" + key + "}}") != std::string::npos) used.emplace(key, value);
  return fill_template(name, embedded_template(name), used);
}

}  // namespace

GeneratedFilter rust_sampled_filter(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  RustFilterWriter w(model, eq, options);
  const SampledFunctions f = sampled_functions(model, eq, options, w.names, w.emitter);
  const bool euler = f.euler_square.has_value();
  w.result.functions = {f.derivatives.stats};
  if (euler) w.result.functions.push_back(f.euler_square->stats);
  w.result.functions.push_back(f.innovation.stats);
  w.result.functions.push_back(f.matrices.stats);
  w.result.functions.push_back(f.observation.stats);
  const std::size_t r = eq.update.r();
  std::map<std::string, std::string> values = w.common_values(r, eq.variables.count());
  RustFilterWriter::add_function(values, "derivatives", f.derivatives);
  RustFilterWriter::add_function(values, "innovation", f.innovation);
  RustFilterWriter::add_function(values, "matrices", f.matrices);
  RustFilterWriter::add_function(values, "observation", f.observation);
  values.insert({{"h", w.names.h}, {"substeps", std::to_string(eq.update.substeps)}});
  add_sample_meanings(values, eq.update);
  std::string euler_function;
  if (euler) {
    std::map<std::string, std::string> euler_values = values;
    RustFilterWriter::add_function(euler_values, "euler", *f.euler_square);
    euler_function = filled_partial("rust/partials/euler_square.rs.tmpl", euler_values);
  }
  const std::string predict = euler ? "rust/partials/predict_euler.rs.tmpl" : "rust/partials/predict_heun.rs.tmpl";
  values.insert({{"period", w.emitter.literal_text(eq.update.period)},
                 {"euler_function", euler_function},
                 {"predict_function", filled_partial(predict, values)},
                 {"initial_body", rust_initial_body(initial_values(model, eq.variables), w.emitter)},
                 {"solve_body", cholesky_gain_body(r, w.emitter)},
                 {"one", w.emitter.literal_text(1)}});
  w.write("sampled_filter", values);
  return w.result;
}

}  // namespace pfgen::codegen
