// libFuzzer target (README, "Fuzzing"): model file text -> load_model_text -> every filter the
// model offers derived; a delayed model's filters are also generated for its simulation dt (the
// whole-steps rule and the history's size come from the input). Refused input is expected (ModelError, or another std::exception that
// pfgen's main() would print as one line); a finding is a crash, a sanitizer report, a run
// beyond -timeout or memory beyond -rss_limit_mb. scripts/fuzz.sh builds and runs it.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/filter_equations.hpp"
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
      if (equations.is_delayed()) {
        pfgen::codegen::CodegenOptions options;
        options.grid_step = model.simulation.dt;
        (void)pfgen::codegen::generate_filter_code(model, equations, options);
      }
    } catch (const std::exception&) {
    }
  }
  return 0;
}
