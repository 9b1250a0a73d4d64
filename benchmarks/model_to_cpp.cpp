// Types a model's drift f and diffusion g as plain C++ functions, the way one
// writes a polynomial model by hand (`0.3*x[0]*x[0]*x[1] - 0.7*x[2] + ...`),
// for the quadrature baseline of bench_codegen: what a user without pfgen would
// hand to a generic Gauss-Hermite runtime. No expectation, derivative or common
// subexpression is computed here; each entry is the model's polynomial, expanded,
// term by term.
//
// Usage: model_to_cpp MODEL.yaml > typed_<name>.hpp
// Writes namespace pfgen_bench::typed::<name> with
//   void f(const double* x, double* out);  // n entries
//   void g(const double* x, double* out);  // n x q, row-major
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/notation/number_format.hpp"

namespace {

// The shortest decimal that reads back as `value`, as one would type it.
std::string number(double value) {
  std::string text = pfgen::shortest_double(value);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string polynomial(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& states) {
  pfgen::Polynomial p = pfgen::Polynomial::from_ex(GiNaC::expand(e), states);
  std::string text;
  for (const auto& [m, c] : p.ordered_terms()) {
    if (!GiNaC::is_exactly_a<GiNaC::numeric>(c)) throw std::runtime_error("model_to_cpp: non-numeric coefficient");
    double value = GiNaC::ex_to<GiNaC::numeric>(c).to_double();
    text += text.empty() ? (value < 0 ? "-" : "") : (value < 0 ? " - " : " + ");
    text += number(value < 0 ? -value : value);
    for (const auto& [variable, exponent] : m.factors())
      for (std::uint32_t k = 0; k < exponent; ++k) text += "*x[" + std::to_string(variable) + "]";
  }
  return text.empty() ? "0.0" : text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: model_to_cpp MODEL.yaml\n");
    return 2;
  }
  try {
    pfgen::Model model = pfgen::load_model_file(argv[1]);
    if (!model.diffusion.g) throw std::runtime_error("model_to_cpp: the model gives G, not g");
    std::printf("// Written by benchmarks/model_to_cpp from %s; do not edit.\n", argv[1]);
    std::printf("// The model's f and g typed as plain C++, as by hand.\n#pragma once\n\n");
    std::printf("namespace pfgen_bench::typed::%s {\n\n", model.name.c_str());
    std::printf("inline void f(const double* x, double* out) {\n  (void)x;\n");
    for (std::size_t i = 0; i < model.n(); ++i)
      std::printf("  out[%zu] = %s;\n", i, polynomial(model.drift[i], model.states).c_str());
    std::printf("}\n\ninline void g(const double* x, double* out) {\n  (void)x;\n");
    std::size_t k = 0;
    for (const auto& row : *model.diffusion.g)
      for (const auto& entry : row) std::printf("  out[%zu] = %s;\n", k++, polynomial(entry, model.states).c_str());
    std::printf("}\n\n}  // namespace pfgen_bench::typed::%s\n", model.name.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
