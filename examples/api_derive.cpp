// pfgen's C++ API (<pfgen/pfgen.hpp>, docs/guide/cpp-api.md): a model built in code, its optimal
// filter derived and printed, evaluated at a point, and generated as C99 in memory.
// Basin, Perez & Skliar 2006's example (examples/basin2006_quadratic.yaml):
//   build/examples/api_derive                 the model built below
//   build/examples/api_derive MODEL.yaml      a model file's first filter instead
// Against an installed pfgen: examples/api_project/CMakeLists.txt.
#include <iostream>

#include <pfgen/pfgen.hpp>

namespace api = pfgen::api;

api::Model quadratic_model() {
  api::ModelBuilder builder("basin2006_quadratic");
  GiNaC::symbol x = builder.state("x");
  // C++ doubles such as 0.1 become the exact rational 1/10.
  builder.drift({0.1 * GiNaC::pow(x, 2)});
  builder.diffusion({{0.1 * GiNaC::pow(x, 2)}});
  builder.additive_diffusion({{0.1}});
  builder.observation({0}, {{1}}, {{1}});
  builder.initial({0.1}, {{1}}, {1.1});
  return builder.build();
}

int main(int argc, char** argv) {
  try {
    const api::Model model = argc > 1 ? api::Model::load(argv[1]) : quadratic_model();
    const api::Filter filter = model.derive(model.default_kinds().front());
    std::cout << filter.text();  // what `pfgen derive` prints

    api::Point point;
    point.m.assign(model.state_names().size(), 0.5);
    for (std::size_t i = 0; i < point.m.size(); ++i) {
      point.P.emplace_back(point.m.size(), 0.0);
      point.P[i][i] = 1;
    }
    std::cout << "eval at m = 0.5, P = I: " << filter.eval(point).json << "\n";

    api::CodegenOptions c;
    c.language = "c";
    c.filters = {filter.name()};
    for (const api::CodeFile& file : model.codegen(c)) std::cout << file.path << ": " << file.contents.size() << " bytes\n";
  } catch (const api::Error& e) {
    std::cerr << "api_derive: " << e.report() << "\n";  // the line `pfgen` would print
    return 1;
  }
  return 0;
}
