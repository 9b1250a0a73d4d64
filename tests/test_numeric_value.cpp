// numeric_value (pfgen/algebra/numeric_value.hpp): an expression's value at numbers that depends
// only on the expression and the numbers, not on where GiNaC's hash order (which moves with the
// process's address layout) puts the operands of a sum or product.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <sstream>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/algebra/numeric_value.hpp"

namespace {

std::string digits(const GiNaC::ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

}  // namespace

TEST_CASE("numeric_value: a sum or product of floats is the same whichever operand holds which value",
          "[numeric_value][unit]") {
  // Floats whose sum at GiNaC's 17 digits depends on the order of the additions.
  const std::vector<GiNaC::ex> floats = {GiNaC::ex(GiNaC::numeric(1, 3)).evalf(), GiNaC::numeric("1e17"),
                                         GiNaC::ex(GiNaC::numeric(-2, 7)).evalf(), GiNaC::numeric("-1e17"),
                                         GiNaC::ex(GiNaC::numeric(5, 11)).evalf()};
  std::vector<GiNaC::symbol> s;
  for (int k = 0; k < 5; ++k) s.emplace_back("s" + std::to_string(k));
  const GiNaC::ex sum = s[0] + s[1] + s[2] + s[3] + s[4];
  const GiNaC::ex product = s[0] * s[1] * s[2] * s[3] * s[4] * (s[0] + 3 * s[2]);
  std::vector<int> order = {0, 1, 2, 3, 4};
  std::set<std::string> sums, products, substituted;
  do {
    GiNaC::exmap values;
    for (int k = 0; k < 5; ++k) values[s[static_cast<std::size_t>(k)]] = floats[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
    sums.insert(digits(pfgen::numeric_value(sum, values)));
    products.insert(digits(pfgen::numeric_value(product.subs(GiNaC::lst{s[0] + 3 * s[2] == 1}), values)));
    substituted.insert(digits(sum.subs(values).evalf()));
  } while (std::next_permutation(order.begin(), order.end()));
  CHECK(sums.size() == 1);
  CHECK(products.size() == 1);
  // What subs() then evalf() gave: a value per order of the operands (not asserted; GiNaC's).
  INFO("subs + evalf gave " << substituted.size() << " different sums");
  CHECK(GiNaC::is_a<GiNaC::numeric>(pfgen::numeric_value(sum, {{s[0], 1}, {s[1], 2}, {s[2], 3}, {s[3], 4}, {s[4], 5}})));
}

TEST_CASE("numeric_value: exact where the inputs are, functions and roots evaluated, free symbols kept",
          "[numeric_value][unit]") {
  const GiNaC::symbol a("a"), b("b"), t("t");
  const GiNaC::exmap values = {{a, GiNaC::numeric(1, 3)}, {b, GiNaC::numeric(2)}, {t, 0}};
  CHECK(pfgen::numeric_value(a * b + b * b, values) == GiNaC::numeric(14, 3));  // exact rational
  CHECK(pfgen::numeric_value(GiNaC::abs(a - b), values) == GiNaC::numeric(5, 3));
  CHECK(pfgen::numeric_value(GiNaC::sin(t) + GiNaC::cos(t), values) == 1);
  const GiNaC::ex root = pfgen::numeric_value(GiNaC::sqrt(b), values);
  REQUIRE(GiNaC::is_a<GiNaC::numeric>(root));
  CHECK(GiNaC::ex_to<GiNaC::numeric>(root).to_double() == Approx(1.4142135623730951).epsilon(1e-16));
  CHECK(GiNaC::is_a<GiNaC::numeric>(pfgen::numeric_value(GiNaC::Pi * a, values)));
  const GiNaC::symbol free("free");
  CHECK_FALSE(GiNaC::is_a<GiNaC::numeric>(pfgen::numeric_value(a + free, values)));
  CHECK_THROWS(pfgen::numeric_value(1 / (b - 2), values));
}
