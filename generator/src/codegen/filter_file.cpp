#include "pfgen/codegen/filter_file.hpp"

#include "pfgen/codegen/template_text.hpp"

namespace pfgen::codegen {

void add_filter_file_values(std::map<std::string, std::string>& values, const FilterFile& file,
                            const StatementEmitter& emitter, BodyIndent indent) {
  auto indented = [indent](std::string text) { return indent ? indent(text) : text; };
  for (const auto& [key, code] : file.functions) {
    values.emplace(key + "_ops", ops_comment(code.stats));
    values.emplace(key + "_helpers", code.body.helpers);
    values.emplace(key + "_body", indented(code.body.statements));
  }
  for (const auto& [key, block] : file.blocks) values.emplace(key, indented(emitter.block(block)));
  for (const auto& [key, number] : file.numbers) values.emplace(key, emitter.constant(number));
  for (const auto& [key, flag] : file.flags) values.emplace(key, emitter.boolean(flag));
  values.insert(file.words.begin(), file.words.end());
}

std::map<std::string, std::string> filter_file_frames(const FilterFile& file, const std::string& template_name,
                                                      const std::map<std::string, std::string>& values,
                                                      const std::string& partial_prefix,
                                                      const std::string& partial_suffix) {
  std::map<std::string, std::string> frames;
  for (const auto& [key, frame] : file.frames)
    if (values_in_template(template_name, {{key, ""}}).count(key) != 0)
      frames.emplace(key, frame.empty() ? "" : filled_template(partial_prefix + frame + partial_suffix, values));
  return frames;
}

ir::Statement state_function_call(const std::string& function, ir::Expr t, ir::Expr state, const std::string& out,
                                  std::optional<ir::Expr> delayed) {
  std::vector<ir::Expr> arguments = {std::move(t), std::move(state)};
  if (delayed) arguments.push_back(std::move(*delayed));
  arguments.push_back(ir::name("params"));
  arguments.push_back(ir::local_array(out, true));
  return ir::call_file_function(function, std::move(arguments));
}

std::optional<FunctionCode> realisability_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                               const FunctionNames& names, const StatementEmitter& emitter) {
  if (eq.realisability.empty()) return std::nullopt;
  return function_code("realisability_margins", eq.realisability, names.out, model, eq, options, names, emitter);
}

void add_realisability_function(FilterFile& file, const FilterEquations& eq, std::optional<FunctionCode> code) {
  file.frames["realisability_function"] = code ? "realisability_margins" : "";
  if (!code) return;
  file.words.emplace("margin_count", std::to_string(eq.realisability.size()));
  file.words.emplace("moment_order", std::to_string(eq.variables.order()));
  file.words.emplace("higher_orders",
                     eq.variables.order() == 3 ? "of order 3" : "of orders 3 to " + std::to_string(eq.variables.order()));
  file.add_function("realisability", std::move(*code));
}

}  // namespace pfgen::codegen
