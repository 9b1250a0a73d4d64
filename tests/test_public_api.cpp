// The public C++ API (<pfgen/pfgen.hpp>) in process: a model built in code gives the model file's
// filter byte for byte, the one exception type carries the command's line, and handles stay valid
// when the model they came from is dropped. (Against the installed package: the package test.)
#include <catch2/catch.hpp>

#include "pfgen/pfgen.hpp"
#include "support/test_paths.hpp"

namespace api = pfgen::api;

TEST_CASE("public API: the cubic sensor built in code is the model file's", "[api][unit]") {
  api::ModelBuilder builder("cubic_sensor");
  const GiNaC::symbol x = builder.state("x");
  const GiNaC::symbol a = builder.parameter("a", 1), sigma = builder.parameter("sigma", 0.5),
                      rho = builder.parameter("rho", 0.5);
  builder.drift({-a * x}).diffusion({{sigma}}).additive_diffusion({{sigma}});
  builder.polynomial_observation({GiNaC::pow(x, 3)}, {{rho}});
  builder.initial({0.5}, {{0.5}});
  const api::Model built = builder.build();
  const api::Model file = api::Model::load(pfgen_test::example("polynomial/cubic_sensor.yaml"));
  CHECK(built.kinds() == file.kinds());
  for (const std::string& kind : file.kinds()) {
    INFO(kind);
    CHECK(built.derive(kind).text() == file.derive(kind).text());
    CHECK(built.derive(kind).json() == file.derive(kind).json());
  }
  api::Point point;
  point.m = {0.4};
  point.P = {{0.3}};
  const api::Evaluation value = file.derive("optimal").eval(point);
  REQUIRE(value.P_gain.size() == 1);
  CHECK(value.P_gain[0][0][0] == Approx(0.864).epsilon(1e-15));
  CHECK(file.derive("optimal").expressions().P_gain[0][0][0] == "6*m1*P11**2/rho**2");
}

TEST_CASE("public API: samples through a polynomial c built in code are the model file's", "[api][unit]") {
  api::ModelBuilder builder("range_squared_sampled");
  const GiNaC::symbol x1 = builder.state("x1"), x2 = builder.state("x2");
  const GiNaC::symbol s = builder.parameter("s", 0.3);
  builder.drift({0, 0}).diffusion({{s, 0}, {0, s}});
  builder.sampled_polynomial_observation(0.1, {x1 * x1 + x2 * x2}, {{0.2}}, 10);
  builder.initial({1, 0.5}, {{0.2, 0}, {0, 0.2}});
  const api::Model built = builder.build();
  const api::Model file = api::Model::load(pfgen_test::example("polynomial/range_squared_sampled.yaml"));
  CHECK(built.kinds() == file.kinds());
  for (const std::string& kind : file.kinds()) {
    INFO(kind);
    CHECK(built.derive(kind).text() == file.derive(kind).text());
    CHECK(built.derive(kind).json() == file.derive(kind).json());
  }
}

TEST_CASE("public API: one exception type, with the command's line", "[api][unit]") {
  const api::Model model = api::Model::load(pfgen_test::example("basin2006_quadratic.yaml"));
  try {
    model.derive("kalman");
    FAIL("derive accepted an unknown filter");
  } catch (const api::Error& e) {
    CHECK(e.report() ==
          "error: --filter: unknown filter 'kalman' (known: optimal, ekf, additive, ekf-additive, ukf, closure3, closure4, ekf-printed)");
  }
  CHECK_THROWS_AS(api::Model::from_yaml("name: x\n"), api::Error);
  api::CodegenOptions c;
  c.language = "fortran";
  CHECK_THROWS_WITH(model.codegen(c), "--language: fortran not in {cpp,c,rust}");
}

TEST_CASE("public API: a filter outlives its model's handle", "[api][unit]") {
  std::string text;
  {
    const api::Filter filter = api::Model::load(pfgen_test::example("van_der_pol.yaml")).derive("ekf");
    text = filter.text();
    CHECK(filter.name() == "ekf");
  }
  CHECK(text.find("filter: ekf") != std::string::npos);
}

TEST_CASE("public API: model text is bounded as a model file is", "[api][unit]") {
  // The YAML parser takes seconds per hundred megabytes: text beyond a model file's 64 MiB is
  // refused before it, with the file's message.
  const std::string text((std::size_t{64} << 20) + 1, '#');
  try {
    api::Model::from_yaml(text, "big.yaml");
    FAIL("from_yaml read text beyond 64 MiB");
  } catch (const api::Error& e) {
    CHECK(e.report() == "big.yaml: error: the model file is larger than 64 MiB: not a model file");
  }
}
