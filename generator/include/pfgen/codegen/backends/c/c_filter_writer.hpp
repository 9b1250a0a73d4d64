#pragma once
// The C backend's writer of a filter's .h/.c pair: any observation module's description of the
// file (filter_file.hpp) into the backend's templates c/<layout>.h.tmpl and .c.tmpl, with what
// every C file has (the names' prefix, the scalar, the parameter record). The names C cannot
// declare are the kind registry's, refused when the model is read.
#include <map>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

// What a C filter's .h and .c share: the writer of both files. Constructing it refuses (CodegenError)
// a model whose parameter or time names C cannot declare.
struct CFilterWriter {
  const Model& model;
  const FilterEquations& eq;
  const CodegenOptions& options;
  FunctionNames names;
  std::string prefix;
  CEmitter emitter;
  GeneratedFilter result;

  CFilterWriter(const Model& m, const FilterEquations& e, const CodegenOptions& o);

  // The placeholders of every C filter template and partial.
  std::map<std::string, std::string> common_values(std::size_t p, std::size_t state_size, const std::string& extra = "");

  // A function's ops comment, helpers (a split body's parts) and body, under `key`_ops etc.
  static void add_function(std::map<std::string, std::string>& values, const std::string& key, const FunctionCode& code);

  // Fills the .h and .c templates (c/<kind>.h.tmpl and .c.tmpl, a module's): `values` holds what both
  // need; header_only and source_only what one of them has alone (every value must meet its
  // placeholder).
  void write(const std::string& kind, std::map<std::string, std::string> values,
             const std::map<std::string, std::string>& header_only, const std::map<std::string, std::string>& source_only);

};

// The filter's .h and .c from `part`'s description of its file.
GeneratedFilter write_c_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                               const CodegenOptions& options);

// The templates of these layouts (c/<layout>.h.tmpl and .c.tmpl), whose declared names the
// model's C names are checked against.
std::vector<std::string> c_layout_templates(const std::vector<std::string>& layouts);

// The C templates whose declared names the model's are checked against for `part`: its layouts'
// and its declaring frames' (c/partials/<frame>.h.tmpl and .c.tmpl), and any c_templates().
std::vector<std::string> c_module_templates(const ObservationCode& part);

}  // namespace pfgen::codegen
