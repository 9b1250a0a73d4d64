#pragma once
// The subcommands of `pfgen`. Each returns the process exit code; problems with
// the model or the options are thrown and reported by main().
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

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
int run_derive(const DeriveOptions& options);
int run_latex(const LatexOptions& options);
int run_eval(const EvalOptions& options);

// Writes `contents` to `path` through a temporary file and a rename, so that a
// failure never leaves a partial output file behind (pfgen_support::write_file_atomically;
// concurrent writers of one path each use their own temporary). A failure is a CliValueError
// naming `option`, the option that gave the path.
void write_file_atomically(const std::string& option, const std::string& path, const std::string& contents);

}  // namespace pfgen::cli
