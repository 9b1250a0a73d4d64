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
  };
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
  add_filter_file_values(values, file, w.emitter, &rust_indent);
  // Each frame the layout's template has (rust/partials/<frame>.rs.tmpl).
  const std::map<std::string, std::string> frames =
      filter_file_frames(file, "rust/" + file.layout + ".rs.tmpl", values, "rust/partials/", ".rs.tmpl");
  values.insert(frames.begin(), frames.end());
  w.write(file.layout, std::move(values));
  return std::move(w.result);
}

}  // namespace pfgen::codegen
