// The filter variables' naming rule (pfgen_support/variable_names.hpp): the one place that
// decides P12 against P1_10, for text and LaTeX.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <vector>

#include "pfgen_support/variable_names.hpp"

using namespace pfgen_support;

TEST_CASE("support: filter variable names, m then P's upper triangle row by row", "[unit][support]") {
  CHECK(filter_variable_names(0).empty());
  CHECK(filter_variable_names(1) == std::vector<std::string>{"m1", "P11"});
  CHECK(filter_variable_names(2) == std::vector<std::string>{"m1", "m2", "P11", "P12", "P22"});
  const std::vector<std::string> nine = filter_variable_names(9);
  REQUIRE(nine.size() == 9 + 45);
  CHECK(nine[9] == "P11");
  CHECK(nine.back() == "P99");
  const std::vector<std::string> ten = filter_variable_names(10);
  REQUIRE(ten.size() == 10 + 55);
  CHECK(ten[9] == "m10");
  CHECK(ten[10] == "P1_1");
  CHECK(ten[10 + 9] == "P1_10");
  CHECK(ten.back() == "P10_10");
}

TEST_CASE("support: P indices run together below 10 states and are separated from 10 on", "[unit][support]") {
  CHECK_FALSE(separates_covariance_indices(9));
  CHECK(separates_covariance_indices(10));
  CHECK(covariance_name(0, 1, 2) == "P12");
  CHECK(covariance_name(1, 0, 2) == "P21");  // the name a model file may use for P12
  CHECK(covariance_name(9, 0, 10) == "P10_1");
  CHECK(covariance_name(0, 10, 11) == "P1_11");
  CHECK(mean_name(11) == "m12");
  CHECK(mean_latex_name(0) == "m_{1}");
  CHECK(covariance_latex_name(0, 1, 2) == "P_{12}");
  CHECK(covariance_latex_name(0, 9, 10) == "P_{1,10}");
  CHECK(covariance_latex_name(10, 10, 12) == "P_{11,11}");
}

TEST_CASE("support: no two filter variables share a name, lower-triangle spellings included", "[unit][support]") {
  // Without the separator n = 11 would give P1_11 and P11_1 the same name, P111.
  for (std::size_t n = 1; n <= 14; ++n) {
    std::set<std::string> text, latex;
    for (std::size_t i = 0; i < n; ++i) {
      CHECK(text.insert(mean_name(i)).second);
      CHECK(latex.insert(mean_latex_name(i)).second);
    }
    std::set<std::string> upper, lower;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) {
        INFO("n = " << n << ", P(" << i << ", " << j << ")");
        CHECK(text.insert(covariance_name(i, j, n)).second);
        CHECK(latex.insert(covariance_latex_name(i, j, n)).second);
        if (i != j) CHECK(lower.insert(covariance_name(j, i, n)).second);
      }
    for (const auto& name : lower) CHECK(text.count(name) == 0);
    CHECK(text.size() == filter_variable_names(n).size());
  }
}
