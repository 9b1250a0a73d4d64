#pragma once
// What every C filter's .h/.c pair shares, whatever its observation (each observation module's
// <kind>_c_filter fills its own c/ pair of templates with these and its functions' bodies): the
// writer of both files (the names C cannot declare are the kind registry's, refused when the model is read).
#include <map>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/c/c_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"

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

}  // namespace pfgen::codegen
