// Building a model in C++ instead of a model file, then deriving and printing
// its optimal filter. This is Basin, Perez & Skliar 2006's example (examples/basin2006_quadratic.yaml).
//   build/examples/api_derive
#include <iostream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/printing/equation_report.hpp"

int main() {
  pfgen::ModelBuilder builder("basin2006_quadratic");
  GiNaC::symbol x = builder.state("x");
  // C++ doubles such as 0.1 become the exact rational 1/10.
  builder.drift({0.1 * GiNaC::pow(x, 2)});
  builder.diffusion({{0.1 * GiNaC::pow(x, 2)}});
  builder.additive_diffusion({{0.1}});
  builder.observation({0}, {{1}}, {{1}});
  pfgen::Model model = builder.build();

  pfgen::FilterEquations optimal = pfgen::derive_filter(model, pfgen::FilterKind::Optimal);
  std::cout << pfgen::equations_text(model, optimal);
  return 0;
}
