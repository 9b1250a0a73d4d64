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

namespace {

double terms_in(const std::vector<Polynomial>& polynomials) {
  double terms = 0;
  for (const Polynomial& p : polynomials) terms += static_cast<double>(p.terms().size());
  return terms;
}

}  // namespace

double moment_terms(const FilterEquations& eq) {
  double terms = terms_in(eq.higher_drift) + terms_in(eq.realisability) + terms_in(eq.update.joint);
  for (const auto& row : eq.higher_gain) terms += terms_in(row);
  return terms;
}

double codegen_load(const FilterEquations& eq) {
  return codegen_terms(eq) + (kMomentTermWeight - 1) * moment_terms(eq);
}

double codegen_terms(const FilterEquations& eq) {
  double terms = 0;
  auto add = [&terms](const std::vector<Polynomial>& polynomials) { terms += terms_in(polynomials); };
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
  return terms + moment_terms(eq);
}

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  if (const double load = codegen_load(eq); load > options.max_equation_terms) {
    const double terms = codegen_terms(eq), moments = moment_terms(eq);
    char text[500];
    if (moments == 0)
      std::snprintf(text, sizeof text,
                    "has %.0f terms in its equations; code generation holds at most %.0f "
                    "(about 0.2 kB each while it builds the code: this would need about %.1f GB); derive and eval "
                    "handle it, and a model with fewer states or a lower degree generates",
                    terms, options.max_equation_terms, terms * 0.2e3 / 1e9);
    else
      std::snprintf(text, sizeof text,
                    "has %.0f terms in its equations, %.0f of them its higher moments', which count %.1f each "
                    "(%.0f in all); code generation holds at most %.0f (about 0.2 kB each while it builds the "
                    "code: this would need about %.1f GB); derive and eval handle it, and a model with fewer "
                    "states, a lower degree or a lower order generates",
                    terms, moments, kMomentTermWeight, load, options.max_equation_terms, load * 0.2e3 / 1e9);
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
