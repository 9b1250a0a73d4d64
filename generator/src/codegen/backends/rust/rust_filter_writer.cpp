#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"

#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/backends/rust/rust_filter_code.hpp"
#include "pfgen/codegen/template_text.hpp"

namespace pfgen::codegen {
namespace {

std::string params_members(const Model& model, const RustEmitter& emitter) {
  std::string text;
  for (const auto& p : model.parameters) text += "    pub " + p.name + ": " + emitter.scalar_type() + ",\n";
  return text;
}

std::string params_defaults(const Model& model, const RustEmitter& emitter) {
  std::string text;
  for (const auto& p : model.parameters) text += "        " + p.name + ": " + emitter.literal_text(p.default_value) + ",\n";
  return text;
}

}  // namespace

RustFilterWriter::RustFilterWriter(const Model& m, const FilterEquations& e, const CodegenOptions& o)
    : model(m), eq(e), options(o), names(function_names(m)), emitter(o.scalar, names.temporary_prefix, "Params") {
  emitter.split_above(options.max_function_ops, names.shared);
  result.name = eq.name;
  for (const std::string& path : rust_filter_paths(model.name, eq.name)) result.files.push_back({path, ""});
}

std::map<std::string, std::string> RustFilterWriter::common_values(std::size_t p, std::size_t state_size,
                                                                   const std::string& extra) {
  // Without CSE every operation is a parenthesised expression, also where Rust needs none.
  const std::string allows = options.eliminate_common_subexpressions ? "non_snake_case" : "non_snake_case, unused_parens";
  return {
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen --language rust", extra)},
      {"allows", allows},
      {"scalar", RustEmitter::rust_scalar(options.scalar)},
      {"n", std::to_string(eq.n())},
      {"p", std::to_string(p)},
      {"state_size", std::to_string(state_size)},
      {"params_members", params_members(model, emitter)},
      {"params_defaults", params_defaults(model, emitter)},
      {"t", names.time},
      {"state", names.state},
      {"params", names.params},
      {"out", names.out},
      {"zero", emitter.literal_text(0)},
      {"one", emitter.literal_text(1)},
      {"two", emitter.literal_text(2)},
  };
}

void RustFilterWriter::add_function(std::map<std::string, std::string>& values, const std::string& key,
                                    const FunctionCode& code) {
  values[key + "_ops"] = ops_comment(code.stats);
  values[key + "_helpers"] = code.body.helpers;
  values[key + "_body"] = rust_indent(code.body.statements);
}

void RustFilterWriter::write(const std::string& kind, std::map<std::string, std::string> values) {
  const std::string name = "rust/" + kind + ".rs.tmpl";
  values["math"] = emitter.math_declarations();
  result.files.at(0).contents = filled_template(name, values);
}

GeneratedFilter write_rust_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                                  const CodegenOptions& options) {
  RustFilterWriter w(model, eq, options);
  FilterFile file = part.filter_file(model, eq, options, w.names, w.emitter);
  w.result.functions = std::move(file.stats);
  std::map<std::string, std::string> values = w.common_values(file.p, file.state_size, file.banner_extra);
  for (const auto& [key, code] : file.functions) RustFilterWriter::add_function(values, key, code);
  for (const auto& [key, block] : file.blocks) values.emplace(key, w.body(block));
  for (const auto& [key, number] : file.numbers) values.emplace(key, w.emitter.literal_text(number));
  for (const auto& [key, flag] : file.flags) values.emplace(key, w.emitter.boolean(flag));
  values.insert(file.words.begin(), file.words.end());
  // Each frame the layout's template has (rust/partials/<frame>.rs.tmpl).
  for (const auto& [key, frame] : file.frames)
    if (values_in_template("rust/" + file.layout + ".rs.tmpl", {{key, ""}}).count(key) != 0)
      values.emplace(key, frame.empty() ? "" : filled_template("rust/partials/" + frame + ".rs.tmpl", values));
  w.write(file.layout, std::move(values));
  return std::move(w.result);
}

}  // namespace pfgen::codegen
