// libFuzzer target (docs/development.md, "Fuzzing"): model file text -> load_model_text -> every filter the
// model offers (the opt-in ukf, risk-sensitive, user filters with define:, sampled and delayed kinds,
// Stratonovich models' Ito drift) derived, evaluated at the model's prior (m0, P0, t = 0: the
// deterministic numeric evaluation, the Cholesky entries, the sampled update) and generated as code
// (a delayed model's for its simulation dt: the whole-steps rule and the history's size come from
// the input). Refused input is expected (ModelError, or another std::exception that
// pfgen's main() would print as one line); a finding is a crash, a sanitizer report, a run
// beyond -timeout or memory beyond -rss_limit_mb. scripts/fuzz.sh builds and runs it.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  pfgen::Model model;
  try {
    model = pfgen::load_model_text(text, "fuzz.yaml");
  } catch (const std::exception&) {
    return 0;
  }
  for (const std::string& name : pfgen::available_filter_names(model)) {
    try {
      const pfgen::FilterEquations equations = pfgen::derive_named_filter(model, name);
      try {
        pfgen::EvaluationPoint point;  // the prior, or m = 0 and P = I where the model gives none
        const std::size_t n = model.n();
        point.m.assign(n, 0);
        point.P.assign(n, std::vector<GiNaC::numeric>(n, 0));
        for (std::size_t i = 0; i < n; ++i) point.P[i][i] = 1;
        if (model.initial && model.initial->m0.size() == n) point.m = model.initial->m0;
        if (model.initial && model.initial->P0.size() == n) point.P = model.initial->P0;
        (void)pfgen::evaluate_at(model, equations, point);
      } catch (const std::exception&) {
      }
      pfgen::codegen::CodegenOptions options;
      if (equations.observation == pfgen::ObservationKind::Delayed) options.grid_step = model.simulation.dt;
      (void)pfgen::codegen::generate_filter_code(model, equations, options);
      options.language = "c";  // the C99 backend, on the same equations
      options.scalar = pfgen::codegen::ScalarMode::Float;
      (void)pfgen::codegen::generate_filter_code(model, equations, options);
    } catch (const std::exception&) {
    }
  }
  return 0;
}
