#include "pfgen/codegen/backends/cpp/cpp_filter_writer.hpp"

#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/cpp/cpp_backend.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_parts.hpp"
#include "pfgen/codegen/template_text.hpp"

namespace pfgen::codegen {

GeneratedFilter write_cpp_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                                 const CodegenOptions& options) {
  const FunctionNames names = function_names(model);
  CppEmitter emitter(options.scalar, names.temporary_prefix);
  emitter.split_above(options.max_function_ops, names.shared);
  FilterFile file = part.filter_file(model, eq, options, names, emitter);
  const bool eigen = options.eigen_wrapper && file.state_is_m_and_P;

  GeneratedFilter result;
  result.name = eq.name;
  for (const std::string& path : cpp_filter_paths(model.name, eq.name, eigen)) result.files.push_back({path, ""});
  result.functions = std::move(file.stats);

  std::map<std::string, std::string> values = cpp_template_values(model, filter_identifier(eq.name), options, eq.n(),
                                                                  file.p, file.state_size, names, emitter);
  values.emplace("banner", filter_banner(model, eq, options, result, "pfgen codegen", file.banner_extra));
  // A call of a function template of the scalar (`period<Scalar>()`), or of the alias's.
  values.emplace("scalar_call", options.scalar == ScalarMode::Template ? "<Scalar>" : "");
  for (const auto& [key, code] : file.functions) {
    values.emplace(key + "_ops", ops_comment(code.stats));
    values.emplace(key + "_body", code.body.statements);
  }
  for (const auto& [key, block] : file.blocks) values.emplace(key, emitter.block(block));
  for (const auto& [key, number] : file.numbers) values.emplace(key, emitter.literal(number));
  for (const auto& [key, flag] : file.flags) values.emplace(key, emitter.boolean(flag));
  values.insert(file.words.begin(), file.words.end());
  // Each frame the layout's template has (cpp/partials/<frame>.hpp.tmpl).
  for (const auto& [key, frame] : file.frames)
    if (values_in_template("cpp/" + file.layout + ".hpp.tmpl", {{key, ""}}).count(key) != 0)
      values.emplace(key, frame.empty() ? "" : filled_template("cpp/partials/" + frame + ".hpp.tmpl", values));

  const std::string name = "cpp/" + file.layout + ".hpp.tmpl";
  result.files.at(0).contents = filled_template(name, values);
  if (eigen) add_eigen_layer(result, "cpp/" + file.layout + "_eigen.hpp.tmpl", model, eq, options, values);
  return result;
}

}  // namespace pfgen::codegen
