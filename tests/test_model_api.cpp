// The C++ API and the model file build the same model.
#include <catch2/catch.hpp>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

TEST_CASE("ModelBuilder with C++ doubles matches the YAML example exactly", "[model][api][unit]") {
  ModelBuilder builder("basin2006_quadratic");
  GiNaC::symbol x = builder.state("x");
  builder.drift({0.1 * GiNaC::pow(x, 2)});
  builder.diffusion({{0.1 * GiNaC::pow(x, 2)}});
  builder.additive_diffusion({{0.1}});
  builder.observation({0}, {{1}}, {{1}});
  Model from_api = builder.build();
  Model from_file = load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  for (FilterKind kind : supported_filter_kinds(from_file)) {
    FilterEquations a = derive_filter(from_api, kind);
    FilterEquations b = derive_filter(from_file, kind);
    CHECK(equations_json(from_api, a).dump() == equations_json(from_file, b).dump());
  }
}

TEST_CASE("ModelBuilder validates like the loader", "[model][api][unit]") {
  ModelBuilder builder("bad");
  GiNaC::symbol x = builder.state("x");
  builder.drift({GiNaC::sin(x)});
  builder.diffusion({{0}});
  builder.observation({0}, {{1}}, {{1}});
  try {
    builder.build();
    FAIL("a non-polynomial drift was accepted");
  } catch (const ModelError& e) {
    CHECK(e.field() == "drift");
    CHECK(e.row() == 1);
    CHECK(std::string(e.what()).find("not polynomial") != std::string::npos);
  }
}

TEST_CASE("parameters and time stay symbolic", "[model][api][unit]") {
  ModelBuilder builder("symbolic");
  GiNaC::symbol x = builder.state("x");
  GiNaC::symbol a = builder.parameter("a", GiNaC::numeric(1, 5));
  GiNaC::symbol t = builder.time();
  builder.drift({a * GiNaC::sin(t) * GiNaC::pow(x, 3)});
  builder.diffusion({{0}});
  builder.observation({0}, {{1}}, {{1}});
  Model model = builder.build();
  FilterEquations eq = derive_filter(model, FilterKind::Optimal);
  // E[x^3] = m^3 + 3 m P
  CHECK(equations_json(model, eq).dump().find("\"a*sin(t)*m1^3 + 3*a*sin(t)*m1*P11\"") != std::string::npos);
}
