#pragma once
// The subcommands of `pfgen`. Each returns the process exit code; problems with
// the model or the options are thrown and reported by main().
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen::cli {

struct DeriveOptions {
  std::string model_path;
  std::string filter;  // empty: the model's first filter in the registry's order
  std::string format = "text";
  bool coefficients = false;  // the model's coefficient form A..A3, E, E1 instead of a filter
  std::string timing_path;    // --timing: the phases' seconds as JSON, written after the report
};

struct LatexOptions {
  std::string model_path;
  std::string output_path;
  std::string filters;  // comma-separated; empty: every kind the model supports
  bool coefficients = false;  // add a section with the model's coefficient form
};

struct EvalOptions {
  std::string model_path;
  std::string filter;
  std::string t = "0";
  std::string m;
  std::string P;
  std::vector<std::string> assignments;
  // Delayed observations only (empty: the default, point_evaluator.hpp).
  std::string m_delayed, x_star, x_star_delayed, phi;
  std::vector<std::string> moments;  // moment filters: NAME=VALUE of a central moment above P
};

struct CodegenCliOptions {
  std::string model_path;
  std::string output_dir;  // may be empty with --stats
  std::string filters;     // comma-separated; empty: every kind the model supports
  std::string language = "cpp";
  std::string scalar = "template";
  bool scalar_given = false;  // --scalar was on the command line (C's default scalar is double)
  std::string name_space = "pfgen_models";
  bool stats = false;
  bool no_cse = false;     // benchmark baseline only
  bool eigen = false;      // also write <kind>_eigen.hpp
  std::optional<double> dt;  // delayed observations: the filters' grid step (else simulation: dt)
  std::optional<std::uint64_t> max_function_ops;  // else CodegenOptions' default; 0: never split
};

int run_codegen(const CodegenCliOptions& options);

// codegen's steps, which the API takes one by one too. codegen_job: the options checked and made
// the generator's (--namespace, --language with --scalar and --eigen, --dt) and the filters named
// (--filter); a note on stderr when --eigen has nothing to wrap. check_code_paths: no file would
// replace the model file (model_path, when not empty) or another filter's file. generate_code: every
// filter's files, in memory. write_code: all of them under output_dir, or none.
struct CodegenJob {
  codegen::CodegenOptions options;
  std::vector<std::string> names;
};
CodegenJob codegen_job(const CodegenCliOptions& options, const Model& model);
void check_code_paths(const Model& model, const CodegenJob& job, const std::string& output_dir,
                      const std::string& model_path);
std::vector<codegen::GeneratedFilter> generate_code(const Model& model, const CodegenJob& job);
void write_code(const std::string& output_dir, const std::vector<codegen::GeneratedFilter>& files);
int run_derive(const DeriveOptions& options);
int run_latex(const LatexOptions& options);
int run_eval(const EvalOptions& options);
// eval's work once the model is read: --set applied (the model checked again), the filter
// derived, or `derived` taken when it is that filter and nothing is --set, and evaluated at the point.
struct EvalOutcome {
  EvaluatedFilter value;
  std::string json;  // what `pfgen eval` prints
};
EvalOutcome evaluate_filter(Model model, const EvalOptions& options, const FilterEquations* derived = nullptr);
// What `pfgen eval` prints: the model's and the filter's names, then the values as the filter's
// observation module lays them out.
std::string eval_json(const Model& model, const FilterEquations& eq, const EvaluatedFilter& value);

// Writes `contents` to `path` through a temporary file and a rename, so that a
// failure never leaves a partial output file behind (pfgen_support::write_file_atomically;
// concurrent writers of one path each use their own temporary). A failure is a CliValueError
// naming `option`, the option that gave the path.
void write_file_atomically(const std::string& option, const std::string& path, const std::string& contents);

}  // namespace pfgen::cli
