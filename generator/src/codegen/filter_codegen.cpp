#include "pfgen/codegen/filter_codegen.hpp"

#include <cstdio>

#include "pfgen/codegen/backend.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

std::vector<std::string> filter_file_paths(const std::string& model_name, const std::string& filter_name,
                                           const CodegenOptions& options) {
  return backend(options.language).filter_paths(model_name, filter_name, options);
}

OpCounts GeneratedFilter::naive_total() const {
  OpCounts total;
  for (const auto& f : functions)
    if (f.in_totals) total += f.naive;
  return total;
}

OpCounts GeneratedFilter::cse_total() const {
  OpCounts total;
  for (const auto& f : functions)
    if (f.in_totals) total += f.cse;
  return total;
}

double codegen_terms(const FilterEquations& eq) {
  double terms = 0;
  auto add = [&terms](const std::vector<Polynomial>& polynomials) {
    for (const Polynomial& p : polynomials) terms += static_cast<double>(p.terms().size());
  };
  add(eq.m_drift);
  for (const auto& row : eq.gain) add(row);
  add(eq.predicted_observation);
  for (const auto& row : eq.jacobian_term) add(row);
  add(eq.P_moment);
  add(eq.P_diffusion);
  add(eq.P_correction);
  add(eq.P_euler);
  add(eq.x_star_drift);
  for (const auto& row : eq.P_gain) add(row);  // a polynomial observation's dP dy term (empty otherwise)
  return terms;
}

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  if (const double terms = codegen_terms(eq); terms > options.max_equation_terms) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "has %.0f terms in its equations; code generation holds at most %.0f "
                  "(about 0.2 kB each while it builds the code: this would need about %.1f GB); derive and eval "
                  "handle it, and a model with fewer states or a lower degree generates",
                  terms, options.max_equation_terms, terms * 0.2e3 / 1e9);
    throw CodegenError(source_place(model) + "filter '" + eq.name + "' of model " + model.name + " " + text);
  }
  observation_code(model.observation).check_size(model, eq);
  try {
    return backend(options.language).filter_code(model, eq, options);
  } catch (const CodegenError& e) {
    // What the code of one equation refuses (a constant out of the scalar's range, ...) knows
    // neither the filter nor the model: say which, as the checks above do.
    const std::string what = e.what();
    if (what.rfind("filter '", 0) == 0) throw;
    throw CodegenError("filter '" + eq.name + "' of model " + model.name + " (" + model.source + "): " + what);
  }
}

}  // namespace pfgen::codegen
