// The scalar example of paper 000 (eqs 21-22) straight from the example model file.
#include <catch2/catch.hpp>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "support/test_paths.hpp"

using namespace pfgen;

TEST_CASE("paper 000 example file gives eqs 21-22", "[derivation][paper000][unit]") {
  Model model = load_model_file(pfgen_test::example("basin2006_quadratic.yaml"));
  FilterEquations eq = derive_filter(model, FilterKind::Optimal);
  GiNaC::symbol m("m"), P("P");
  std::vector<GiNaC::ex> vars{m, P};
  GiNaC::ex tenth = GiNaC::numeric(1, 10);
  GiNaC::ex m_drift = tenth * (m * m + P);
  GiNaC::ex P_drift = GiNaC::numeric(4, 10) * P * m + GiNaC::numeric(3, 100) * P * P +
                      GiNaC::numeric(6, 100) * P * m * m + GiNaC::numeric(1, 100) * GiNaC::pow(m, 4) - P * P;
  CHECK((eq.m_drift[0].to_ex(vars) - m_drift).expand().is_zero());
  CHECK((eq.P_drift(0, 0).to_ex(vars) - P_drift).expand().is_zero());
  CHECK((eq.gain[0][0].to_ex(vars) - P).expand().is_zero());
  CHECK(eq.exactness.exact);
  CHECK(eq.exactness.condition == "Basin-Perez-Skliar 2006");
}
