#pragma once
// What a filter's file holds, in no language: an observation module's description of it
// (ObservationCode::filter_file), which each backend's writer (codegen/backends/<language>/
// <language>_filter_writer) turns into its files by filling its templates for the file's layout.
// The module chooses the layout, the functions and the statements; the backend owns every word of
// its language (names' prefixes, types, the scalar's literals, how a function is framed). The
// functions' bodies are already written by the backend's emitter, which the backend passes to the
// module: each body is lowered once, in the backend's language.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ginac/ginac.h>

#include "pfgen/codegen/filter_functions.hpp"
#include "pfgen/codegen/ir/statement_emitter.hpp"
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

struct FilterFile {
  // Which frame the file has: a backend writes it from its templates of this name
  // (backends/<language>/templates/<layout>.*): "filter" (a rate's Heun step), "polynomial_filter",
  // "sampled_filter", "delayed_filter".
  std::string layout;
  // The file's sizes beyond the model's n: p (observations, or a sample's outputs) and the entries
  // of the filter's state.
  std::size_t p = 0, state_size = 0;
  // Lines the banner has after its first (each ending in a newline): a delayed filter's grid.
  std::string banner_extra;
  // Whether the state is m and P's upper triangle alone, so that a layer may view it as a vector
  // and a matrix (C++'s --eigen wrappers); false for a state with more (x*) and a history.
  bool state_is_m_and_P = true;

  // The functions, under their templates' keys (`<key>_ops`, `<key>_body`, and where the language
  // splits a body into functions of its own, `<key>_helpers`).
  std::vector<std::pair<std::string, FunctionCode>> functions;
  // Statements under their templates' keys (`initial_body`, the step's loops), each written by the
  // backend's emitter as a block of the function the template puts it in.
  std::map<std::string, ir::Block> blocks;
  // Text the same in every language: comments' words (`gain_meaning`), the output arrays' names
  // (`K`, `h`), counts.
  std::map<std::string, std::string> words;
  // Numbers of the scalar type (a sampling period, a delay), written as the language's literals.
  std::map<std::string, GiNaC::numeric> numbers;
  // Text the backend holds for each language, chosen by the module, under their templates' keys:
  // key -> the name of a partial of the backend's ("" for none). A function framed by its comment
  // and signature (euler_square() of a cd-euler filter, the body inside), or a comment's words
  // that differ by language in more than names (a delayed filter's state_x_star).
  // Each backend fills <language>/partials/<name>.* with the file's values into every template of
  // the layout that has `key` (C: the .c.tmpl into the source, the .h.tmpl into the header).
  std::map<std::string, std::string> frames;
  // Truth values (`uses_x_star`), written as the language's.
  std::map<std::string, bool> flags;
  // The functions' statistics in the order of the banner and --stats.
  std::vector<FunctionStats> stats;

  // Adds a function under `key`.
  void add_function(const std::string& key, FunctionCode code) { functions.emplace_back(key, std::move(code)); }
};

// function(t, state, [delayed,] params, out): a call of one of the file's functions of the filter state
// (derivatives, gain, rates, observation_matrices, ...), which write the local array `out`; a delayed
// filter's read its delayed inputs after the state.
ir::Statement state_function_call(const std::string& function, ir::Expr t, ir::Expr state, const std::string& out,
                                  std::optional<ir::Expr> delayed = std::nullopt);

// What every backend's writer does with a description, its language given by `emitter` (the one
// the module wrote the bodies with): adds to `values`, without replacing any, each function's
// `<key>_ops`, `<key>_helpers` and `<key>_body`, each block as the emitter writes it, each number as
// its constant, each flag as its truth value, and the words. `indent` turns a body's text (the
// IR's two-space blocks) into the language's indentation; none keeps it.
using BodyIndent = std::string (*)(const std::string&);
void add_filter_file_values(std::map<std::string, std::string>& values, const FilterFile& file,
                            const StatementEmitter& emitter, BodyIndent indent = nullptr);

// Each frame of `file` whose key the template `template_name` has: the backend's partial
// <partial_prefix><frame><partial_suffix> filled with `values`, or "" where the module chose none.
std::map<std::string, std::string> filter_file_frames(const FilterFile& file, const std::string& template_name,
                                                      const std::map<std::string, std::string>& values,
                                                      const std::string& partial_prefix,
                                                      const std::string& partial_suffix);

// A moment filter's realisability margins (derivation/moment_closure.hpp) as a function of its file, whatever its
// observation: the function's code (nothing for another filter), then its frame (each language's partial
// realisability_margins, an empty frame without margins), words and function in the file.
std::optional<FunctionCode> realisability_code(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                                               const FunctionNames& names, const StatementEmitter& emitter);
void add_realisability_function(FilterFile& file, const FilterEquations& eq, std::optional<FunctionCode> code);

}  // namespace pfgen::codegen
