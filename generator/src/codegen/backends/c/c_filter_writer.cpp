#include "pfgen/codegen/backends/c/c_filter_writer.hpp"

#include "pfgen/codegen/backends/c/c_backend.hpp"
#include "pfgen/codegen/backends/c_family/file_banner.hpp"
#include "pfgen/codegen/template_text.hpp"

namespace pfgen::codegen {
namespace {

std::string params_members(const Model& model, const CEmitter& emitter) {
  if (model.parameters.empty()) return "  char unused;  // C has no empty record\n";
  std::string text;
  for (const auto& p : model.parameters) text += "  " + emitter.scalar_type() + " " + p.name + ";\n";
  return text;
}

std::string params_defaults(const Model& model, const CEmitter& emitter) {
  if (model.parameters.empty()) return "  (void)params;\n";
  std::string text;
  for (const auto& p : model.parameters) text += "  params->" + p.name + " = " + emitter.literal(p.default_value) + ";\n";
  return text;
}

}  // namespace

CFilterWriter::CFilterWriter(const Model& m, const FilterEquations& e, const CodegenOptions& o)
    : model(m),
      eq(e),
      options(o),
      names(function_names(m)),
      prefix(c_symbol_prefix(o.name_space, m.name, e.name)),
      emitter(o.scalar, names.temporary_prefix, prefix, prefix + "_params") {
  emitter.split_above(options.max_function_ops, names.shared);
  result.name = eq.name;
  for (const std::string& path : c_filter_paths(model.name, eq.name)) result.files.push_back({path, ""});
}

std::map<std::string, std::string> CFilterWriter::common_values(std::size_t p, std::size_t state_size,
                                                                const std::string& extra) {
  const std::string header = result.files.at(0).relative_path;
  return {
      {"banner", filter_banner(model, eq, options, result, "pfgen codegen --language c", extra)},
      {"guard", prefix + "_h"},
      {"header", header.substr(header.find_last_of('/') + 1)},
      {"prefix", prefix},
      {"scalar", emitter.scalar_type()},
      {"n", std::to_string(eq.n())},
      {"p", std::to_string(p)},
      {"state_size", std::to_string(state_size)},
      {"params_members", params_members(model, emitter)},
      {"params_defaults", params_defaults(model, emitter)},
      {"t", names.time},
      {"state", names.state},
      {"params", names.params},
      {"out", names.out},
      {"zero", emitter.literal(0)},
      {"one", emitter.literal(1)},
  };
}

void CFilterWriter::write(const std::string& kind, std::map<std::string, std::string> values,
                          const std::map<std::string, std::string>& header_only,
                          const std::map<std::string, std::string>& source_only) {
  std::map<std::string, std::string> header_values = values, source_values = values;
  header_values.insert(header_only.begin(), header_only.end());
  source_values.insert(source_only.begin(), source_only.end());
  const std::string h = "c/" + kind + ".h.tmpl", c = "c/" + kind + ".c.tmpl";
  result.files.at(0).contents = filled_template(h, header_values);
  result.files.at(1).contents = filled_template(c, source_values);
}

GeneratedFilter write_c_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                               const CodegenOptions& options) {
  CFilterWriter w(model, eq, options);
  FilterFile file = part.filter_file(model, eq, options, w.names, w.emitter);
  w.result.functions = std::move(file.stats);
  std::map<std::string, std::string> values = w.common_values(file.p, file.state_size, file.banner_extra);
  add_filter_file_values(values, file, w.emitter);
  // A frame in each file whose template has its key: a function's definition in the .c
  // (c/partials/<frame>.c.tmpl), its declaration in the .h (.h.tmpl).
  const std::map<std::string, std::string> header_only =
      filter_file_frames(file, "c/" + file.layout + ".h.tmpl", values, "c/partials/", ".h.tmpl");
  const std::map<std::string, std::string> source_only =
      filter_file_frames(file, "c/" + file.layout + ".c.tmpl", values, "c/partials/", ".c.tmpl");
  w.write(file.layout, std::move(values), header_only, source_only);
  return std::move(w.result);
}

std::vector<std::string> c_module_templates(const ObservationCode& part) {
  std::vector<std::string> names;
  for (const std::string& layout : part.layouts())
    names.insert(names.end(), {"c/" + layout + ".h.tmpl", "c/" + layout + ".c.tmpl"});
  for (const std::string& frame : part.declaring_frames())
    names.insert(names.end(), {"c/partials/" + frame + ".h.tmpl", "c/partials/" + frame + ".c.tmpl"});
  return names;
}

}  // namespace pfgen::codegen
