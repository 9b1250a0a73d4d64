#pragma once
// The sampled observation y_k = C0 + C x(t_k) + Uv v_k in code generation: SampledCode, its
// methods by file (sampled_code.cpp: its filter's file, layout "sampled_filter", described in no
// language; sampled_plugin.cpp: the truth's sampled observation and the plugin's table), and the
// functions its filters consist of.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

// A sampled filter's update writes its Cholesky solve out for every output, O(r^3) straight-line
// code: 1.2 MB of C++ at r = 64, 4 MB at r = 100 and 27 MB at r = 200, which a compiler takes
// minutes over. Code generation takes at most this many outputs (derive and eval take any).
inline constexpr std::size_t kMaxSampledOutputs = 64;

class SampledCode final : public ObservationCode {
 public:
  void check_size(const Model& model, const FilterEquations& eq) const override;  // kMaxSampledOutputs
  FilterFile filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                         const FunctionNames& names, const StatementEmitter& emitter) const override;
  std::vector<std::string> layouts() const override { return {"sampled_filter"}; }
  // cd-euler's, and a moment filter's (cd-closure3, cd-closure4; joint_moments() with a polynomial c)
  std::vector<std::string> declaring_frames() const override {
    return {"euler_square", "realisability_margins", "joint_moments"};
  }
  std::string plugin_wrappers(const Model& model, const std::vector<std::string>& names,
                              const std::vector<PluginFilterFacts>& facts) const override;
  std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>& names,
                                                  const std::vector<std::string>& labels,
                                                  std::optional<double> grid_step,
                                                  const std::vector<PluginFilterFacts>& facts) const override;
};

// The functions of a filter for sampled observations: the prediction's derivatives() (and
// cd-euler's euler_square(), its dt^2 term), the update's polynomial parts innovation_terms()
// (P C^T and S) and observation_matrices() (C and R), and predicted_observation(), the predicted
// sample.
struct SampledFunctions {
  FunctionCode derivatives;
  std::optional<FunctionCode> euler_square;
  FunctionCode innovation, matrices, observation;
  std::optional<FunctionCode> joint;  // a moment filter's joint_moments() with samples through a polynomial c
  // Their statistics in the order of the file's banner and --stats (euler_square() after
  // derivatives(), for cd-euler).
  std::vector<FunctionStats> stats() const;
};
SampledFunctions sampled_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                   const FunctionNames& names, const StatementEmitter& emitter);

// What the templates' comments say observation_matrices(), predicted_observation() and the
// innovation are (matrices_meaning, sample_meaning, innovation_meaning): C0 + C m's, or a
// polynomial c's moment-matching terms.
void add_sample_meanings(std::map<std::string, std::string>& values, const SampledUpdate& update);

}  // namespace pfgen::codegen
