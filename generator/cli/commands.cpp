#include "commands.hpp"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <regex>
#include <fstream>
#include <iostream>

#include "cli_options.hpp"
#include "observation_command.hpp"
#include "output_paths.hpp"
#include "pfgen/codegen/backend.hpp"
#include "pfgen/codegen/filter_codegen.hpp"
#include "pfgen/derivation/drift_coefficients.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/reserved_names.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/coefficient_report.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen/printing/latex_document.hpp"
#include "pfgen/printing/noise_report.hpp"
#include "pfgen_support/atomic_file.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace pfgen::cli {
namespace {

// Wall-clock seconds of a command's phases, one after the other, for --timing.
class PhaseTimer {
 public:
  void end_phase(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    phases_.emplace_back(name, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }
  std::string json() const {
    Json out = Json::object();
    for (const auto& [name, seconds] : phases_) out.add(name, Json::number(seconds));
    return out.dump_line();
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> phases_;
};

std::string single_filter(const std::string& name, const Model& model) {
  std::vector<std::string> names = parse_filter_list("--filter", name, model);
  if (names.size() != 1) throw CliValueError("--filter: give exactly one filter");
  return names.front();
}

}  // namespace

void write_file_atomically(const std::string& option, const std::string& path, const std::string& contents) {
  try {
    pfgen_support::write_file_atomically(path, contents);
  } catch (const pfgen_support::AtomicWriteError& e) {
    throw CliValueError(option + ": " + e.what());  // "cannot write 'PATH': the reason"
  }
}

CodegenJob codegen_job(const CodegenCliOptions& options, const Model& model) {
  if (!std::regex_match(options.name_space, std::regex("[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*")))
    throw CliValueError("--namespace: '" + options.name_space + "' is not a C++ namespace name");
  for (const auto& part : split(std::regex_replace(options.name_space, std::regex("::"), ":"), ':'))
    if (auto problem = namespace_name_problem(part)) throw CliValueError("--namespace: " + *problem);
  if (options.name_space.front() == '_')
    throw CliValueError("--namespace: '" + options.name_space + "' starts with '_', which C++ reserves for the "
                        "implementation in the global namespace, and C at file scope");
  CodegenJob job;
  codegen::CodegenOptions& codegen_options = job.options;
  // Everything that depends on the language is its backend's (codegen/backend.hpp).
  const codegen::Backend& backend = codegen::backend(options.language);
  codegen_options.language = backend.name();
  // --scalar's default `template` is C++'s: without --scalar each language has its own.
  codegen_options.scalar = options.scalar == "float"    ? codegen::ScalarMode::Float
                           : options.scalar == "double" ? codegen::ScalarMode::Double
                           : options.scalar_given       ? codegen::ScalarMode::Template
                                                        : backend.default_scalar();
  if (options.scalar_given)
    if (auto problem = backend.scalar_problem(codegen_options.scalar))
      throw CliValueError("--scalar " + options.scalar + ": " + *problem);
  backend.check_model(model, options.name_space);
  if (options.eigen)
    if (auto problem = backend.eigen_problem()) throw CliValueError("--eigen: " + *problem);
  codegen_options.name_space = options.name_space;
  codegen_options.eliminate_common_subexpressions = !options.no_cse;
  if (options.max_function_ops) codegen_options.max_function_ops = static_cast<std::size_t>(*options.max_function_ops);
  // An observation whose filters have no Eigen layer (a delayed one's) gets none, and --eigen says so.
  const std::string without_eigen =
      options.eigen ? observation_command(model.observation.kind()).without_eigen_layer(model) : "";
  const bool eigen = options.eigen && without_eigen.empty();
  if (options.eigen && !eigen) std::cerr << "pfgen: note: --eigen: " << without_eigen << "\n";
  codegen_options.eigen_wrapper = eigen;
  codegen_options.grid_step = options.dt ? options.dt : model.simulation.dt;
  if (options.dt && !(*options.dt > 0 && std::isfinite(*options.dt)))
    throw CliValueError("--dt: the step must be positive and finite");
  job.names = parse_filter_list("--filter", options.filters, model);
  return job;
}

void check_code_paths(const Model& model, const CodegenJob& job, const std::string& output_dir,
                      const std::string& model_path) {
  // The files' names follow from the model's and the filters' names (filter_file_paths), so
  // they are checked before any derivation: a file must not replace the model file, nor one
  // filter's file another's (a user filter `optimal-eigen` and optimal's Eigen wrapper are both
  // optimal_eigen.hpp).
  const codegen::Backend& backend = codegen::backend(job.options.language);
  std::vector<NamedPath> written;
  for (const std::string& name : job.names) {
    const std::vector<std::string> paths = codegen::filter_file_paths(model.name, name, job.options);
    for (std::size_t k = 0; k < paths.size(); ++k)
      written.push_back({"-o (filter " + name + backend.file_role(k) + ")",
                         (std::filesystem::path(output_dir) / paths[k]).string()});
  }
  std::vector<NamedPath> read;
  if (!model_path.empty()) read.push_back({"the model file", model_path});
  check_distinct_outputs(read, written);
  // A 300-character model name failed as "cannot create directory", after making the ones above.
  for (const NamedPath& file : written)
    if (auto name = too_long_name(file.path)) {
      const bool from_model = name->name.find(model.name) != std::string::npos;
      throw CliValueError(file.role + ": the name " + pfgen_support::quoted(name->name) +
                          " is longer than the file system takes (" +
                          std::to_string(name->limit) + " bytes a name)" +
                          (from_model ? "; the model's name (" + std::to_string(model.name.size()) +
                                            " characters) makes it: give the model a shorter name"
                                      : ""));
    }
}

std::vector<codegen::GeneratedFilter> generate_code(const Model& model, const CodegenJob& job) {
  std::vector<codegen::GeneratedFilter> files;
  for (const std::string& name : job.names)
    files.push_back(codegen::generate_filter_code(model, derive_named_filter(model, name), job.options));
  return files;
}

void write_code(const std::string& output_dir, const std::vector<codegen::GeneratedFilter>& files) {
  // All the files or none: a directory in the way of the last file left the first ones
  // written. Checked, then every temporary written, then renamed (write_files_together).
  std::vector<std::pair<std::string, std::string>> outputs;
  for (const auto& filter : files)
    for (const auto& file : filter.files)
      outputs.emplace_back((std::filesystem::path(output_dir) / file.relative_path).string(), file.contents);
  for (const auto& output : outputs) {  // one directory, DIR/<model>
    const std::filesystem::path directory = std::filesystem::path(output.first).parent_path();
    std::error_code error;
    if (!create_directories_or_none(directory, error))
      throw CliValueError("-o: cannot create directory '" + directory.string() + "': " + error.message());
  }
  try {
    pfgen_support::write_files_together(outputs);
  } catch (const pfgen_support::AtomicWriteError& e) {
    const bool none_written = e.stage() != pfgen_support::AtomicWriteError::Stage::rename;
    throw CliValueError(std::string("-o: ") + e.what() + (none_written ? "; no header was written" : ""));
  }
}

int run_codegen(const CodegenCliOptions& options) {
  if (options.output_dir.empty() && !options.stats) throw CliValueError("-o: give an output directory (or --stats)");
  Model model = load_model_file(options.model_path);
  const CodegenJob job = codegen_job(options, model);
  if (!options.output_dir.empty()) check_code_paths(model, job, options.output_dir, options.model_path);
  // Everything is generated in memory first: a failure leaves no partial output.
  const std::vector<codegen::GeneratedFilter> files = generate_code(model, job);
  if (!options.output_dir.empty()) write_code(options.output_dir, files);
  if (options.stats) {
    auto counts = [](const codegen::OpCounts& c) {
      Json o = Json::object();
      o.add("adds", Json::integer(c.adds));
      o.add("muls", Json::integer(c.muls));
      o.add("divs", Json::integer(c.divs));
      o.add("calls", Json::integer(c.calls));
      o.add("total", Json::integer(c.total()));
      return o;
    };
    for (const auto& file : files) {
      Json functions = Json::array();
      for (const auto& f : file.functions) {
        Json entry = Json::object();
        entry.add("function", Json::string(f.function));
        entry.add("naive", counts(f.naive));
        entry.add("cse", counts(f.cse));
        // rates() computes what derivatives(), gain() and predicted_observation() do: not in the totals.
        if (!f.in_totals) entry.add("in_totals", Json::boolean(false));
        functions.push(entry);
      }
      Json out = Json::object();
      out.add("model", Json::string(model.name));
      out.add("filter", Json::string(file.name));
      out.add("ops_naive", Json::integer(file.naive_total().total()));
      out.add("ops_cse", Json::integer(file.cse_total().total()));
      out.add("naive", counts(file.naive_total()));
      out.add("cse", counts(file.cse_total()));
      out.add("functions", functions);
      std::cout << out.dump_line();
    }
  }
  return 0;
}

int run_derive(const DeriveOptions& options) {
  if (!options.timing_path.empty()) {
    check_distinct_outputs({{"the model file", options.model_path}}, {{"--timing", options.timing_path}});
    check_output_file({"--timing", options.timing_path});
  }
  PhaseTimer timer;
  Model model = load_model_file(options.model_path);
  timer.end_phase("read_seconds");
  if (options.coefficients) {
    if (!options.filter.empty())
      throw CliValueError("--coefficients: shows the model's coefficient form, not a filter's equations; drop --filter");
    const DriftCoefficients drift = extract_drift_coefficients(model);
    const ObservationCoefficients observation = extract_observation_coefficients(model);
    timer.end_phase("derive_seconds");
    if (options.format == "text") {
      std::cout << coefficients_text(model, drift, observation);
    } else if (options.format == "latex") {
      std::cout << coefficients_latex(model, drift, observation);
    } else {
      std::cout << coefficients_json(model, drift, observation).dump();
    }
  } else {
    // Without --filter: the model's first filter (optimal, cd-optimal or delay-optimal).
    const std::string name =
        options.filter.empty() ? default_filter_names(model).front() : single_filter(options.filter, model);
    // Kept, never freed: the process ends after printing, and freeing a big filter's millions of terms
    // one by one (dense cubic n = 20: 3.3 million) costs a tenth of the whole command. A static pointer
    // keeps them reachable, so leak checkers do not report them; volatile, because the optimiser
    // drops a store to a static nobody reads, and LeakSanitizer then reported the filter as leaked.
    static const FilterEquations* volatile kept_until_exit = nullptr;
    kept_until_exit = new FilterEquations(derive_named_filter(model, name));
    const FilterEquations& eq = *kept_until_exit;
    timer.end_phase("derive_seconds");
    if (options.format == "text") {
      write_equations_text(std::cout, model, eq);
    } else if (options.format == "latex") {
      std::cout << noise_latex(model) << equations_latex(model, eq);
    } else {
      equations_json(model, eq).dump(std::cout);
    }
  }
  std::cout.flush();
  timer.end_phase("print_seconds");
  if (!options.timing_path.empty()) write_file_atomically("--timing", options.timing_path, timer.json());
  return 0;
}

int run_latex(const LatexOptions& options) {
  check_distinct_outputs({{"the model file", options.model_path}}, {{"-o", options.output_path}});
  // The document is LaTeX source: a name such as x.pdf would hold text that no PDF viewer opens.
  if (std::filesystem::path(options.output_path).extension() != ".tex")
    throw CliValueError("-o: '" + options.output_path + "' must end in .tex (pdflatex makes the PDF from it)");
  Model model = load_model_file(options.model_path);
  // Before the filters are derived: a drift the form cannot hold is refused at once.
  if (options.coefficients) check_coefficient_form_degree(model);
  std::vector<FilterEquations> filters;
  for (const std::string& name : parse_filter_list("--filter", options.filters, model))
    filters.push_back(derive_named_filter(model, name));
  write_file_atomically("-o", options.output_path, latex_document(model, filters, options.coefficients));
  return 0;
}

int run_eval(const EvalOptions& options) {
  std::cout << evaluate_filter(load_model_file(options.model_path), options).json;
  return 0;
}

EvalOutcome evaluate_filter(Model model, const EvalOptions& options, const FilterEquations* derived) {
  apply_parameter_assignments(model, options.assignments);
  // Without --set the model is the one `derived` (the caller's) was derived from: no need to derive again.
  const std::string name = single_filter(options.filter, model);
  const bool reuse = derived && options.assignments.empty() && derived->name == name;
  const FilterEquations eq = reuse ? *derived : derive_named_filter(model, name);
  EvaluationPoint point;
  point.t = parse_number("--t", options.t);
  point.m = parse_number_list("--m", options.m);
  point.P = parse_number_matrix("--P", options.P);
  auto optional_list = [](const std::string& option, const std::string& text) {
    return text.empty() ? std::vector<GiNaC::numeric>{} : parse_number_list(option, text);
  };
  point.m_delayed = optional_list("--m-delayed", options.m_delayed);
  point.x_star = optional_list("--x-star", options.x_star);
  point.x_star_delayed = optional_list("--x-star-delayed", options.x_star_delayed);
  point.phi = optional_list("--phi", options.phi);
  for (const std::string& text : options.moments) {
    auto [name, value] = parse_assignment("--moment", text);
    if (!point.moments.emplace(name, value).second) throw CliValueError("--moment: " + name + " is given twice");
  }
  EvalOutcome outcome;
  outcome.value = evaluate_at(model, eq, point);
  outcome.json = eval_json(model, eq, outcome.value);
  return outcome;
}

std::string eval_json(const Model& model, const FilterEquations& eq, const EvaluatedFilter& value) {
  Json out = Json::object();
  out.add("model", Json::string(model.name));
  out.add("filter", Json::string(eq.name));
  observation_command(eq.observation).add_eval_json(eq, value, out);
  if (!value.moment_names.empty()) add_moment_eval_json(value, out);
  return out.dump();
}

}  // namespace pfgen::cli
