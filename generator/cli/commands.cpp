#include "commands.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "cli_options.hpp"
#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/evaluation/point_evaluator.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen/printing/equation_report.hpp"
#include "pfgen/printing/json_writer.hpp"
#include "pfgen/printing/latex_document.hpp"

namespace pfgen::cli {
namespace {

FilterKind single_filter(const std::string& name, const Model& model) {
  std::vector<FilterKind> kinds = parse_filter_list(name, model);
  if (kinds.size() != 1) throw CliValueError("--filter: give exactly one filter kind");
  return kinds.front();
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& contents) {
  const std::string temporary = path + ".pfgen-tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw CliValueError("-o: cannot write '" + path + "'");
    out << contents;
    out.close();
    if (!out) {
      std::remove(temporary.c_str());
      throw CliValueError("-o: cannot write '" + path + "'");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw CliValueError("-o: cannot write '" + path + "'");
  }
}

int run_derive(const DeriveOptions& options) {
  Model model = load_model_file(options.model_path);
  FilterEquations eq = derive_filter(model, single_filter(options.filter, model));
  if (options.format == "text") {
    std::cout << equations_text(model, eq);
  } else if (options.format == "latex") {
    std::cout << equations_latex(model, eq);
  } else {
    std::cout << equations_json(model, eq).dump();
  }
  return 0;
}

int run_latex(const LatexOptions& options) {
  Model model = load_model_file(options.model_path);
  std::vector<FilterEquations> filters;
  for (FilterKind kind : parse_filter_list(options.filters, model)) filters.push_back(derive_filter(model, kind));
  write_file_atomically(options.output_path, latex_document(model, filters));
  return 0;
}

int run_eval(const EvalOptions& options) {
  Model model = load_model_file(options.model_path);
  FilterEquations eq = derive_filter(model, single_filter(options.filter, model));
  EvaluationPoint point;
  point.t = parse_number("--t", options.t);
  point.m = parse_number_list("--m", options.m);
  point.P = parse_number_matrix("--P", options.P);
  for (const auto& assignment : options.assignments) point.parameters.insert(parse_assignment("--set", assignment));
  EvaluatedFilter value = evaluate_at(model, eq, point);

  auto vector_json = [](const std::vector<double>& v) {
    Json a = Json::array();
    for (double x : v) a.push(Json::number(x));
    return a;
  };
  auto matrix_json = [&](const std::vector<std::vector<double>>& m) {
    Json a = Json::array();
    for (const auto& row : m) a.push(vector_json(row));
    return a;
  };
  Json out = Json::object();
  out.add("model", Json::string(model.name));
  out.add("filter", Json::string(filter_kind_name(eq.kind)));
  out.add("m_drift", vector_json(value.m_drift));
  out.add("gain", matrix_json(value.gain));
  out.add("P_drift", matrix_json(value.P_drift));
  std::cout << out.dump();
  return 0;
}

}  // namespace pfgen::cli
