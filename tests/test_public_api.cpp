// The public C++ API (<pfgen/pfgen.hpp>) in process: a model built in code gives the model file's
// filter byte for byte, the one exception type carries the command's line, and handles stay valid
// when the model they came from is dropped. (Against the installed package: the package test.)
#include <algorithm>

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

TEST_CASE("public API: a moment filter takes its moments and gives theirs", "[api][unit]") {
  // closure3 of the quadratic example at m = -1.5, P = 0.5, M3_111 = 0.2 (tests/test_cli.cpp's hand values):
  // dP = 0.2 (2 m P + M3) + 0.01 (m^4 + 6 m^2 P + 4 m M3 + 3 P^2) - P^2, dP's dy term M3, dM3's drift
  // 0.3 (2 m M3 + 2 P^2) + 0.03 (4 m^3 P + 6 m^2 M3 + 12 m P^2 + 10 P M3) - 3 M3 P and dy term M4 - 3 P^2 = 0.
  const api::Filter closure3 = api::Model::load(pfgen_test::example("basin2006_quadratic.yaml")).derive("closure3");
  api::Point point;
  point.m = {-1.5};
  point.P = {{0.5}};
  point.moments = {{"M3_111", 0.2}};
  const api::Evaluation value = closure3.eval(point);
  CHECK(value.P_drift[0][0] == Approx(-0.396375).epsilon(1e-14));
  REQUIRE(value.P_gain.size() == 1);
  CHECK(value.P_gain[0][0][0] == Approx(0.2).epsilon(1e-14));
  CHECK(value.moment_names == std::vector<std::string>{"M3_111"});
  REQUIRE(value.moment_drift.size() == 1);
  CHECK(value.moment_drift[0] == Approx(-0.5565).epsilon(1e-14));
  CHECK(value.moment_gain == api::Matrix{{0}});
  CHECK(value.json.find("\"moments\": [\"M3_111\"]") != std::string::npos);  // the command's JSON
  // Left out, M3 takes its Gaussian value 0: dP's dy term is then 0.
  point.moments.clear();
  CHECK(closure3.eval(point).P_gain[0][0][0] == 0);

  const api::Expressions e = closure3.expressions();
  CHECK(e.moment_names == std::vector<std::string>{"M3_111"});
  CHECK(e.moment_drift.size() == 1);
  CHECK(e.moment_gain == std::vector<std::vector<std::string>>{{"0"}});
  REQUIRE(e.P_gain.size() == 1);
  CHECK(e.P_gain[0][0][0] == "M3_111");
  CHECK(std::find(e.names.begin(), e.names.end(), "M3_111") != e.names.end());
  const api::Expressions optimal =
      api::Model::load(pfgen_test::example("basin2006_quadratic.yaml")).derive("optimal").expressions();
  CHECK(optimal.moment_names.empty());
  CHECK(optimal.moment_drift.empty());
  CHECK(optimal.moment_gain.empty());
}

TEST_CASE("public API: a moment the filter does not carry is refused with the command's line", "[api][unit]") {
  const api::Model model = api::Model::load(pfgen_test::example("basin2006_quadratic.yaml"));
  api::Point point;
  point.m = {1};
  point.P = {{1}};
  point.moments = {{"M4_1111", 1}};
  CHECK_THROWS_WITH(model.derive("closure3").eval(point),
                    "--moment: filter closure3 has no central moment 'M4_1111' (its one is M3_111)");
  CHECK_THROWS_WITH(model.derive("optimal").eval(point),
                    "--moment: filter optimal carries no central moments above P (the closure kinds do)");
  // A name holding '=' is refused as one, not split by the command's NAME=VALUE into M3_111 and "1=2".
  point.moments = {{"M3_111=1", 2}};
  CHECK_THROWS_WITH(model.derive("closure3").eval(point), "--moment: 'M3_111=1' is not a name: it holds '='");
  point.moments.clear();
  point.parameters = {{"a=1", 2}};
  CHECK_THROWS_WITH(model.derive("closure3").eval(point), "--set: 'a=1' is not a name: it holds '='");
}
