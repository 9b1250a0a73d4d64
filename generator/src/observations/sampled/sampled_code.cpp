// The sampled module's code generation: its filters' functions and file, language-neutral, its
// size limit, and its part.
#include "pfgen/observations/sampled/sampled_code.hpp"

#include "pfgen/observations/sampled/cholesky_solve.hpp"
#include "pfgen/observations/sampled/joseph_update.hpp"
#include "pfgen/observations/sampled/sampled_moment_update.hpp"
#include "pfgen/observations/sampled/sampled_predict.hpp"

namespace pfgen::codegen {

void SampledCode::check_size(const Model& model, const FilterEquations& eq) const {
  if (eq.update.r() <= kMaxSampledOutputs) return;
  throw CodegenError(source_place(model) + "filter '" + eq.name + "' of model " + model.name + " samples " + std::to_string(eq.update.r()) +
                     " outputs; its generated update writes the Cholesky solve out for every output (O(r^3) "
                     "code: 1.2 MB of C++ at r = 64, 27 MB at r = 200, which a compiler takes minutes over), so "
                     "code generation takes at most " + std::to_string(kMaxSampledOutputs) +
                     " outputs; derive and eval take any");
}

std::vector<FunctionStats> SampledFunctions::stats() const {
  std::vector<FunctionStats> all = {derivatives.stats};
  if (euler_square) all.push_back(euler_square->stats);
  for (const FunctionCode* code : {&innovation, &matrices, &observation}) all.push_back(code->stats);
  if (joint) all.push_back(joint->stats);
  return all;
}

SampledFunctions sampled_functions(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                   const FunctionNames& names, const StatementEmitter& emitter) {
  const SampledUpdate& u = eq.update;
  SampledFunctions f;
  f.derivatives = derivatives_code(model, eq, options, names, emitter);
  if (!eq.P_euler.empty())
    f.euler_square = function_code("euler_square", eq.P_euler, names.out, model, eq, options, names, emitter);
  std::vector<Polynomial> innovation;
  for (const auto& row : u.PCt) innovation.insert(innovation.end(), row.begin(), row.end());
  innovation.insert(innovation.end(), u.S.begin(), u.S.end());
  f.innovation = function_code("innovation_terms", innovation, names.out, model, eq, options, names, emitter);
  std::vector<Polynomial> matrices;
  for (const auto& row : u.C) matrices.insert(matrices.end(), row.begin(), row.end());
  matrices.insert(matrices.end(), u.R.begin(), u.R.end());
  f.matrices = function_code("observation_matrices", matrices, names.out, model, eq, options, names, emitter);
  f.observation =
      function_code("predicted_observation", eq.predicted_observation, names.h, model, eq, options, names, emitter);
  if (u.closed_law) f.joint = function_code("joint_moments", u.joint, names.out, model, eq, options, names, emitter);
  return f;
}

FilterFile SampledCode::filter_file(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                    const FunctionNames& names, const StatementEmitter& emitter) const {
  SampledFunctions f = sampled_functions(model, eq, options, names, emitter);
  const bool euler = f.euler_square.has_value(), joint = f.joint.has_value();
  FilterFile file;
  file.layout = "sampled_filter";
  file.p = eq.update.r();
  file.state_size = eq.variables.count();
  file.stats = f.stats();
  file.add_function("derivatives", std::move(f.derivatives));
  if (euler) file.add_function("euler", std::move(*f.euler_square));
  file.add_function("innovation", std::move(f.innovation));
  file.add_function("matrices", std::move(f.matrices));
  file.add_function("observation", std::move(f.observation));
  if (joint) file.add_function("joint", std::move(*f.joint));
  // cd-euler's Cov(f) dt^2 function, and the prediction sub-step's comment and signature, are each
  // framed by a partial of the backend's; the sub-step's body is statements.
  file.frames = {{"euler_function", euler ? "euler_square" : ""},
                 {"predict_function", euler ? "predict_euler" : "predict_heun"},
                 {"joint_function", joint ? "joint_moments" : ""}};
  file.blocks.emplace("initial_body", initial_state_statements(initial_values(model, eq.variables)));
  file.blocks.emplace("solve_body", cholesky_gain_statements(file.p));
  file.blocks.emplace("predict_body", predict_statements(euler));
  file.blocks.emplace("advance_body", advance_statements());
  JosephUpdate update = joint ? joint_moment_update_statements(eq.variables, eq.update.r(), eq.update.joint_indices)
                              : joseph_update_statements();
  // A moment filter's higher moments after m and P, before the update returns (with samples through C0 + C x).
  if (!joint) {
    ir::Block moments = moment_update_statements(eq.variables);
    update.update.insert(update.update.end() - 1, std::make_move_iterator(moments.begin()), std::make_move_iterator(moments.end()));
  }
  file.blocks.emplace("update_arrays", std::move(update.arrays));
  file.blocks.emplace("update_matrices", std::move(update.matrices));
  file.blocks.emplace("update_views", std::move(update.views));
  file.blocks.emplace("update_counter", std::move(update.counter));
  file.blocks.emplace("update_solve", std::move(update.solve));
  file.blocks.emplace("update_body", std::move(update.update));
  file.numbers.emplace("period", eq.update.period);
  file.words = {{"h", names.h},
                {"substeps", std::to_string(eq.update.substeps)},
                {"predict_meaning", euler ? "cd-euler's exact moments of one Euler step." : "Heun's scheme on the prediction ODEs."}};
  add_sample_meanings(file.words, eq.update);
  if (joint) {
    file.words["joint_count"] = std::to_string(eq.update.joint.size());
    file.words["joint_fourth"] = eq.variables.order() >= 4 ? ", then Z4_ijlq" : "";
  }
  // A moment filter's margins, after the other functions in the banner.
  std::optional<FunctionCode> margins = realisability_code(model, eq, options, names, emitter);
  if (margins) file.stats.push_back(margins->stats);
  add_realisability_function(file, eq, std::move(margins));
  return file;
}

const ObservationCode& sampled_observation_code() {
  static const SampledCode part;
  return part;
}

void add_sample_meanings(std::map<std::string, std::string>& values, const SampledUpdate& update) {
  // The file's first line: C0 + C x's words for every filter but a moment filter's through a polynomial c (the
  // Gaussian kinds' files keep them, unchanged).
  values["samples_equation"] = update.closed_law ? "c(x(t_k)) + Uv v_k" : "C0 + C x(t_k) + Uv v_k";
  values["innovation_terms_meaning"] = "P C^T (n x p, row-major), S = C P C^T + Uv Uv^T (upper triangle, row by row)";
  values["covariance_update"] = "P = (Id - K C) P (Id - K C)^T + K R K^T, Id the identity (Joseph form: P stays symmetric "
                                "and positive\n// semi-definite under rounding)";
  if (update.closed_law) {
    values["innovation_terms_meaning"] = "Cov(x, c) (n x p, row-major), S = Cov(c) + Uv Uv^T (upper triangle, row by "
                                         "row); both under\n// the filter's closed law";
    values["covariance_update"] = "P and the higher moments those of x+ - m+ = Abar z - K v, Abar = [Id - K C, -K], z "
                                  "= (x - m, d)\n// (joint_moments()), P C^T read as Cov(x, c)";
    values["matrices_meaning"] = "out = [C = E[J_c] (p x n, row-major), R = Uv Uv^T (upper triangle, row by row)], E under the\n"
                                 "// filter's closed law.";
    values["sample_meaning"] = "E[c]";
    values["innovation_meaning"] = "y - h";
    return;
  }
  if (!update.polynomial_samples) {
    values["matrices_meaning"] =
        "out = [C (p x n, row-major), R = Uv Uv^T (upper triangle, row by row)]; they do not depend on\n// the filter state.";
    values["sample_meaning"] = "C0 + C m";
    values["innovation_meaning"] = "y - C0 - C m";
    return;
  }
  values["matrices_meaning"] =
      update.at_mean ? "out = [C = J_c(m) (p x n, row-major), R = Uv Uv^T (upper triangle, row by row)]: c linearised at m."
                     : "out = [C = E[J_c] (p x n, row-major), R = Cov(c) - C P C^T + Uv Uv^T (upper triangle, row by\n"
                       "// row)]: with them the Joseph form below is the moment-matching update P - K S K^T.";
  values["sample_meaning"] = update.at_mean ? "c(m)" : "E[c]";
  values["innovation_meaning"] = "y - h";
}

}  // namespace pfgen::codegen
