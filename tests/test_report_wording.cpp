// What the reports say about the equations they print: the extended filters' dP terms are J P +
// P J^T at m, not Gaussian expectations; the sampled update's innovation covariance has a name no
// model can take (Pyy11; as S11 it read as a state S's); and a sampled model's LaTeX display shows
// the samples' equation, not a continuous dy.
#include <catch2/catch.hpp>

#include <string>

#include "support/cli_helpers.hpp"

using namespace pfgen_test;

namespace {

std::string derived(const std::string& model, const std::string& filter) {
  const auto result = run_pfgen({"derive", model, "--filter", filter});
  INFO(result.err);
  REQUIRE(result.exit_code == 0);
  return result.out;
}

}  // namespace

TEST_CASE("the dP terms line names the Jacobian at m for the extended filters", "[report][integration]") {
  const std::string continuous = example("basin2006_quadratic.yaml");
  const std::string sampled = example("allahyani_date_example1_gamma05.yaml");
  const std::string jacobian = "J P + P J^T, J = df/dx at m", moments = "E[(x-m)f^T] + E[f(x-m)^T]";
  for (const auto& [model, filter] : {std::pair<std::string, std::string>{continuous, "ekf"},
                                      {continuous, "ekf-additive"},
                                      {sampled, "cd-ekf"}}) {
    INFO(filter);
    const std::string text = derived(model, filter);
    CHECK(text.find("dP terms: [" + jacobian + "] + [diffusion]") != std::string::npos);
    CHECK(text.find(moments) == std::string::npos);
  }
  for (const auto& [model, filter] :
       {std::pair<std::string, std::string>{continuous, "optimal"}, {sampled, "cd-optimal"}}) {
    INFO(filter);
    CHECK(derived(model, filter).find("dP terms: [" + moments + "] + [diffusion]") != std::string::npos);
  }
}

TEST_CASE("the sampled update's innovation covariance is printed under a name no model can take",
          "[report][integration]") {
  const std::string text = derived(example("allahyani_date_example1_gamma05.yaml"), "cd-optimal");
  CHECK(text.find("\nPyy11 = ") != std::string::npos);
  CHECK(text.find("K = PCt Pyy^-1\n") != std::string::npos);
  CHECK(text.find("S11") == std::string::npos);
  TempDir dir;
  for (const std::string name : {"Pyy11", "PCt1_2", "Pyy_1"}) {
    write_file(dir.file("m.yaml"), "name: m\nstates: [x]\nparameters: {a: 1, " + name +
                                       ": 2}\ndrift: [\"-a*x\"]\ndiffusion: [[\"1\"]]\n"
                                       "observation: {A: [[\"1\"]], B: [[\"1\"]]}\n");
    const auto result = run_pfgen({"derive", dir.file("m.yaml")});
    INFO(result.err);
    CHECK(result.exit_code == 1);
    CHECK(result.err.find("'" + name + "' is a name of the printed sampled update") != std::string::npos);
  }
}

TEST_CASE("latex of a sampled model shows the samples' equation in the model's display", "[report][integration]") {
  TempDir dir;
  for (const auto& [model, equation] :
       {std::pair<std::string, std::string>{example("allahyani_date_example1_gamma05.yaml"),
                                            "y_k = C_0 + C\\,x(t_k) + U_v v_k"},
        {example("polynomial/range_squared_sampled.yaml"), "y_k = c(x(t_k)) + U_v v_k"}}) {
    const auto result = run_pfgen({"latex", model, "-o", dir.file("m.tex")});
    INFO(result.err);
    REQUIRE(result.exit_code == 0);
    const std::string tex = read_file(dir.file("m.tex"));
    CHECK(tex.find("dW_1, \\qquad " + equation + " \\]") != std::string::npos);
    CHECK(tex.find("dW_2") == std::string::npos);
  }
}
