#pragma once
// The Rust backend's writer of a filter's module: any observation module's description of the
// file (filter_file.hpp) into the backend's template rust/<layout>.rs.tmpl (with the partial
// rust/partials/head.rs.tmpl), with what every module has: the banner, the crate attributes, the
// scalar type and dimensions, the parameter record, the <math.h> declarations the bodies need;
// the functions' bodies and statements in Rust's indentation.
#include <map>
#include <string>
#include <vector>

#include "pfgen/codegen/backends/rust/rust_emitter.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/codegen/filter_functions.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {

struct RustFilterWriter {
  const Model& model;
  const FilterEquations& eq;
  const CodegenOptions& options;
  FunctionNames names;
  RustEmitter emitter;
  GeneratedFilter result;

  RustFilterWriter(const Model& m, const FilterEquations& e, const CodegenOptions& o);

  // The placeholders every Rust filter template has (its head partial's among them).
  std::map<std::string, std::string> common_values(std::size_t p, std::size_t state_size, const std::string& extra = "");

  // Statements as a function's body: the emitter's text, indented as Rust's.
  std::string body(const ir::Block& statements) const { return rust_indent(emitter.block(statements)); }

  // A function's ops comment, its helpers (a split body's parts) and its body, under `key`_ops etc.
  static void add_function(std::map<std::string, std::string>& values, const std::string& key, const FunctionCode& code);

  // Fills rust/<kind>.rs.tmpl with `values` and the math declarations the bodies call (so every
  // body is written before this).
  void write(const std::string& kind, std::map<std::string, std::string> values);
};

// The filter's module from `part`'s description of its file.
GeneratedFilter write_rust_filter(const ObservationCode& part, const Model& model, const FilterEquations& eq,
                                  const CodegenOptions& options);

}  // namespace pfgen::codegen
