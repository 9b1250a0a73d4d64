#include "pfgen/codegen/filter_codegen.hpp"

#include <cstdio>

#include "pfgen/codegen/backends/c/c_filter_code.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_code.hpp"

namespace pfgen::codegen {

std::vector<std::string> filter_file_paths(const std::string& model_name, const std::string& filter_name,
                                           const CodegenOptions& options) {
  switch (options.language) {
    case Language::Cpp: return cpp_filter_paths(model_name, filter_name, options.eigen_wrapper);
    case Language::C: return c_filter_paths(model_name, filter_name);
  }
  return {};
}

OpCounts GeneratedFilter::naive_total() const {
  OpCounts total;
  for (const auto& f : functions) total += f.naive;
  return total;
}

OpCounts GeneratedFilter::cse_total() const {
  OpCounts total;
  for (const auto& f : functions) total += f.cse;
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
  return terms;
}

DelaySteps filter_delay_steps(const FilterEquations& eq, const CodegenOptions& options) {
  if (!options.grid_step)
    throw CodegenError("filter '" + eq.name + "': a filter for delayed observations steps on a fixed grid: give --dt "
                       "(or simulation: dt in the model file)");
  const DelaySteps steps = delay_steps(eq.delay, *options.grid_step);
  if (!steps.problem.empty()) throw CodegenError("filter '" + eq.name + "': " + steps.problem);
  return steps;
}

std::string gain_meaning(const FilterEquations& eq) {
  if (eq.is_user_filter()) return "as given in the model file";
  if (eq.uses_x_star()) return "P Phi*^T A^T (B B^T)^-1, Phi* = diag(phi)";
  return "P A^T (B B^T)^-1";
}

GeneratedFilter generate_filter_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options) {
  if (const double terms = codegen_terms(eq); terms > kMaxCodegenTerms) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "filter '%s' of model %s has %.0f terms in its equations; code generation holds at most %.0f "
                  "(about 1.1 kB each while it builds the code: this would need about %.1f GB); derive and eval "
                  "handle it, and a model with fewer states or a lower degree generates",
                  eq.name.c_str(), model.name.c_str(), terms, kMaxCodegenTerms, terms * 1.1e3 / 1e9);
    throw CodegenError(text);
  }
  if (eq.is_sampled() && eq.update.r() > kMaxSampledOutputs)
    throw CodegenError("filter '" + eq.name + "' of model " + model.name + " samples " +
                       std::to_string(eq.update.r()) +
                       " outputs; its generated update writes the Cholesky solve out for every output (O(r^3) "
                       "code: 1.2 MB of C++ at r = 64, 27 MB at r = 200, which a compiler takes minutes over), so "
                       "code generation takes at most " + std::to_string(kMaxSampledOutputs) +
                       " outputs; derive and eval take any");
  switch (options.language) {
    case Language::Cpp: return cpp_filter_code(model, eq, options);
    case Language::C: return c_filter_code(model, eq, options);
  }
  throw CodegenError("unknown output language");
}

}  // namespace pfgen::codegen
