// polynomial_shape's one walk against GiNaC's is_polynomial(list) and degree(v), which walk the
// expression once per variable; and the degree cap where GiNaC's own int degree would wrap.
#include <catch2/catch.hpp>

#include "pfgen/model/polynomial_shape.hpp"

namespace {

GiNaC::lst as_list(const std::vector<GiNaC::symbol>& variables) {
  GiNaC::lst list;
  for (const auto& v : variables) list.append(v);
  return list;
}

}  // namespace

TEST_CASE("polynomial shape: agrees with GiNaC's is_polynomial and degree", "[model_validation][unit]") {
  const GiNaC::symbol x("x"), y("y"), z("z"), p("p"), t("t");
  const std::vector<GiNaC::symbol> states = {x, y, z};
  const std::vector<GiNaC::ex> cases = {
      x, 3, p, GiNaC::numeric(1, 3) * p * x * x * y, GiNaC::pow(x + 1, 3) * y, GiNaC::pow(x * y + z, 4) + x,
      GiNaC::sin(t) * GiNaC::pow(x, 2), GiNaC::pow(p, 7) * z, GiNaC::pow(2, p) * x, GiNaC::exp(t) + GiNaC::pow(y, 5),
      // not polynomial in the states:
      GiNaC::sin(x), 1 / x, GiNaC::pow(x, GiNaC::numeric(1, 2)), GiNaC::pow(2, x), GiNaC::pow(x, p),
      GiNaC::pow(x + y, -2) * z, GiNaC::exp(y) * x, GiNaC::pow(GiNaC::sin(x), 2), x + GiNaC::cos(z * t),
      GiNaC::pow(p, x) + 1};
  for (const GiNaC::ex& e : cases) {
    const pfgen::PolynomialShape shape = pfgen::polynomial_shape(e, states, 1000);
    INFO(e);
    CHECK(shape.polynomial == e.is_polynomial(as_list(states)));
    if (!shape.polynomial) continue;
    REQUIRE(shape.degrees.size() == states.size());
    for (std::size_t k = 0; k < states.size(); ++k) CHECK(shape.degrees[k] == e.degree(states[k]));
  }
}

TEST_CASE("polynomial shape: degrees beyond the cap read cap + 1, also where int would wrap", "[model_validation][unit]") {
  const GiNaC::symbol x("x"), y("y"), p("p");
  const std::vector<GiNaC::symbol> states = {x, y};
  auto degrees = [&](const GiNaC::ex& e) { return pfgen::polynomial_shape(e, states, 1000).degrees; };
  CHECK(degrees(GiNaC::pow(x, 1000)) == std::vector<std::int64_t>{1000, 0});
  CHECK(degrees(GiNaC::pow(x, 1001)) == std::vector<std::int64_t>{1001, 0});
  CHECK(degrees(GiNaC::pow(GiNaC::pow(x, 2) + y, 600)) == std::vector<std::int64_t>{1001, 600});
  CHECK(degrees(GiNaC::pow(x * y, GiNaC::pow(GiNaC::numeric(83), 10))) == std::vector<std::int64_t>{1001, 1001});
  CHECK(degrees(GiNaC::pow(p, 5000) * y) == std::vector<std::int64_t>{0, 1});  // a parameter's power is no degree
  CHECK(degrees(GiNaC::pow(x, 999) * GiNaC::pow(x + 1, 999)) == std::vector<std::int64_t>{1001, 0});
}
