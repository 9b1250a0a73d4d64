// The kind registry (kinds/filter_kinds.hpp) is the one list of built-in filter kinds: every
// other list a user or a test sees must agree with it, and these tests fail when one does not.
// The same holds for the truth schemes' table (pfgen_support/truth_schemes.hpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include "pfgen/derivation/filter_equations.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model_filters.hpp"
#include "pfgen/model/yaml_model_loader.hpp"
#include "pfgen_runtime/schemes.hpp"
#include "pfgen_support/truth_schemes.hpp"
#include "support/cli_helpers.hpp"

using namespace pfgen;
using namespace pfgen_test;

namespace {

// The rows of the table in docs/guide/filter-kinds.md: the cells of each row, backticks removed.
std::vector<std::vector<std::string>> readme_kind_table() {
  const std::string readme = read_file(source_dir() + "/docs/guide/filter-kinds.md");
  const std::size_t header = readme.find("| `--filter` | expectations |");
  REQUIRE(header != std::string::npos);
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(readme.substr(header));
  std::string line;
  std::getline(in, line);  // header
  std::getline(in, line);  // |---|
  while (std::getline(in, line) && !line.empty() && line[0] == '|') {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream cells_in(line.substr(1));
    while (std::getline(cells_in, cell, '|')) {
      cell.erase(std::remove(cell.begin(), cell.end(), '`'), cell.end());
      const auto first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
      cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    }
    rows.push_back(cells);
  }
  return rows;
}

std::string expectation_words(ExpectationRule rule) {
  switch (rule) {
    case ExpectationRule::Gaussian: return "Gaussian";
    case ExpectationRule::AtMean: return "at the mean";
    case ExpectationRule::SigmaPoints: return "sigma points";
    case ExpectationRule::CumulantNeglect: return "cumulant neglect";
  }
  return "";
}

std::string drift_words(ExpectationRule rule) {
  switch (rule) {
    case ExpectationRule::Gaussian: return "E[f]";
    case ExpectationRule::AtMean: return "f(m)";
    case ExpectationRule::SigmaPoints: return "Σ wᵢ f(Xᵢ)";
    case ExpectationRule::CumulantNeglect: return "E[f]";
  }
  return "";
}

std::string diffusion_words(DiffusionSource source) {
  return source == DiffusionSource::Model ? "model" : "additive";
}

std::string observation_words(const std::vector<ObservationKind>& kinds) {
  std::string out;
  for (ObservationKind kind : kinds) out += (out.empty() ? "" : ", ") + observation_kind_info(kind).name;
  return out;
}

}  // namespace

TEST_CASE("kind registry: names are unique, valid, and parse back to their kind", "[unit][kinds]") {
  std::set<std::string> names, identifiers;
  REQUIRE(!filter_kinds().empty());
  for (const auto& info : filter_kinds()) {
    INFO(info.name);
    CHECK(std::regex_match(info.name, std::regex("^[a-z][a-z0-9-]*$")));
    CHECK(names.insert(info.name).second);
    CHECK(identifiers.insert(filter_identifier(info.name)).second);  // generated file and namespace
    CHECK(parse_filter_kind(info.name) == info.kind);
    CHECK(&filter_kind_info(info.kind) == &info);
    CHECK(!info.description.empty());
    CHECK(info.description.find('\n') == std::string::npos);
    CHECK(!info.observations.empty());
  }
  REQUIRE(filter_kind_names().size() == filter_kinds().size());
  for (std::size_t k = 0; k < filter_kinds().size(); ++k) CHECK(filter_kind_names()[k] == filter_kinds()[k].name);
  CHECK(!parse_filter_kind("Optimal"));
  CHECK(!parse_filter_kind(""));
}

TEST_CASE("kind registry: the guide's table is the registry written out", "[unit][kinds]") {
  const auto rows = readme_kind_table();
  REQUIRE(rows.size() == filter_kinds().size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const FilterKindInfo& info = filter_kinds()[k];
    INFO("docs/guide/filter-kinds.md row " << k + 1 << ", kind " << info.name);
    REQUIRE(rows[k].size() >= 7);
    CHECK(rows[k][0] == info.name);
    CHECK(rows[k][1] == expectation_words(info.expectation));
    CHECK(rows[k][2] == diffusion_words(info.diffusion));
    CHECK(rows[k][3] == observation_words(info.observations));
    // The formula columns follow the two axes.
    const std::string drift = drift_words(info.expectation);
    // The risk-sensitive kind follows the information state's mode (docs/theory.md §2.7).
    CHECK(rows[k][4] == (info.criterion == Criterion::RiskSensitive ? drift + " − P ∇(div f)(m)" : drift));
    CHECK((rows[k][6].find("additive") != std::string::npos) == (info.diffusion == DiffusionSource::Additive));
  }
}

TEST_CASE("kind registry: the model room and the derivation offer exactly the kinds the registry allows",
          "[unit][kinds]") {
  // basin2006_quadratic gives additive_diffusion; basin_skliar_partial does not.
  for (const std::string file : {"basin2006_quadratic.yaml", "basin_skliar_partial.yaml"}) {
    INFO(file);
    const Model model = load_model_file(example(file));
    std::vector<std::string> expected;
    for (const auto& info : filter_kinds()) {
      const bool supported = !unsupported_reason(info, filter_kind_needs(model));
      if (supported) expected.push_back(info.name);
      // Deriving an unsupported kind fails with the registry's reason; a supported one follows
      // the registry's axes.
      if (!supported) {
        CHECK_THROWS_WITH(derive_filter(model, info.kind), Catch::Contains(*unsupported_reason(model, info.kind)));
        continue;
      }
      const FilterEquations eq = derive_filter(model, info.kind);
      CHECK(eq.name == info.name);
      CHECK(eq.description == info.description);
      CHECK(eq.observation == model.observation.kind());
      CHECK(eq.predicted_observation.size() == model.p());
    }
    std::size_t for_observation = 0;
    for (const auto& info : filter_kinds())
      for (ObservationKind o : info.observations)
        for_observation += o == model.observation.kind() && info.criterion == Criterion::MeanSquare ? 1 : 0;
    const bool needs_additive = model.observation.kind() == ObservationKind::Continuous;  // some continuous kinds do
    CHECK((model.additive_diffusion.has_value() || !needs_additive ? expected.size() == for_observation
                                                                   : expected.size() < for_observation));
    for (const auto& filter : model.user_filters) expected.push_back(filter.name);
    CHECK(available_filter_names(model) == expected);
    // The defaults leave out exactly the registry's opt-in kinds (in_defaults = false: the ukf).
    std::vector<std::string> defaults;
    for (const auto& name : expected)
      if (!parse_filter_kind(name) || filter_kind_info(*parse_filter_kind(name)).in_defaults) defaults.push_back(name);
    CHECK(default_filter_names(model) == defaults);
    CHECK(defaults.size() < expected.size());  // the ukf is offered, but not by default
  }
}

TEST_CASE("kind registry: a moment filter needs a positive definite P0, where its runs would not stop at once",
          "[unit][kinds]") {
  // basin_skliar_partial's P0 = [[1, 1], [1, 1]] is singular: its realisability stop (P not positive definite)
  // would end every run at t = 0.
  const Model singular = load_model_file(example("basin_skliar_partial.yaml"));
  CHECK_FALSE(filter_kind_needs(singular).prior_positive_definite);
  for (FilterKind kind : {FilterKind::Closure3, FilterKind::Closure4}) {
    const auto reason = unsupported_reason(singular, kind);
    REQUIRE(reason);
    CHECK_THAT(*reason, Catch::Contains("needs a positive definite initial.P0"));
  }
  CHECK_FALSE(unsupported_reason(singular, FilterKind::Optimal));
  const Model regular = load_model_file(example("basin2006_quadratic.yaml"));
  CHECK(filter_kind_needs(regular).prior_positive_definite);
  CHECK_FALSE(unsupported_reason(regular, FilterKind::Closure4));
}

TEST_CASE("kind registry: command-line help, errors and defaults list the registry's kinds", "[integration][kinds]") {
  const std::string model = example("basin2006_quadratic.yaml");  // every mean-square continuous kind
  std::string bar, comma;
  for (const auto& name : filter_kind_names()) bar += (bar.empty() ? "" : " | ") + name;
  for (const auto& info : filter_kinds())
    if (info.observations.front() == ObservationKind::Continuous && info.criterion == Criterion::MeanSquare)
      comma += (comma.empty() ? "" : ", ") + info.name;
  for (const char* command : {"derive", "eval"}) {
    ProcessResult help = run_pfgen({command, "--help"});
    INFO(command << " --help: " << help.out);
    CHECK(help.out.find(bar) != std::string::npos);
  }
  ProcessResult unknown = run_pfgen({"codegen", model, "--stats", "--filter", "no-such-kind"});
  CHECK(unknown.exit_code != 0);
  CHECK(unknown.err.find("(known: " + comma) != std::string::npos);

  // Defaults of latex and codegen: every kind the model supports but the opt-in ones (the ukf), then
  // its own filters.
  const Model loaded = load_model_file(model);
  TempDir dir;
  ProcessResult codegen = run_pfgen({"codegen", model, "-o", dir.path()});
  REQUIRE(codegen.exit_code == 0);
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir.file(loaded.name)))
    files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  std::vector<std::string> expected;
  for (const auto& name : default_filter_names(loaded)) expected.push_back(filter_identifier(name) + ".hpp");
  std::sort(expected.begin(), expected.end());
  CHECK(files == expected);

  ProcessResult latex = run_pfgen({"latex", model, "-o", dir.file("doc.tex")});
  REQUIRE(latex.exit_code == 0);
  const std::string document = read_file(dir.file("doc.tex"));
  std::size_t last = 0;
  for (const auto& name : default_filter_names(loaded)) {
    INFO("latex section for " << name);
    const std::size_t at = document.find("\\section*{Filter \\texttt{" + name + "}}");
    REQUIRE(at != std::string::npos);
    CHECK(at >= last);  // in the registry's order
    last = at;
  }
}

TEST_CASE("scheme registry: the runtime, the model file, the command line and the guide name the same schemes",
          "[integration][kinds]") {
  namespace rt = pfgen_runtime;
  const auto& schemes = pfgen_support::truth_schemes();
  REQUIRE(!schemes.empty());
  // A scalar SDE every scheme can step (rk4 needs q = 0).
  rt::SdeSystem noisy;
  noisy.n = 1;
  noisy.q = 1;
  noisy.drift = [](double, const double* x, double* f) { f[0] = -x[0]; };
  noisy.diffusion = [](double, const double* x, double* g) { g[0] = 0.1 * x[0]; };
  noisy.diffusion_jacobian = [](double, const double*, double* dg) { dg[0] = 0.1; };
  rt::SdeSystem deterministic = noisy;
  deterministic.q = 0;
  for (std::size_t k = 0; k < schemes.size(); ++k) {
    INFO(schemes[k].name);
    const rt::SchemeKind kind = rt::scheme_kind_from_string(schemes[k].name);
    CHECK(static_cast<std::size_t>(kind) == k);
    CHECK(rt::to_string(kind) == schemes[k].name);
    const auto scheme = rt::make_scheme(kind, schemes[k].name == "rk4" ? deterministic : noisy);
    CHECK(scheme->name() == schemes[k].name);  // each scheme class's own name agrees
  }
  CHECK_THROWS(rt::scheme_kind_from_string("auto"));  // auto is pfgen's choice, not a scheme

  const std::vector<std::string> choices = pfgen_support::truth_scheme_choices();
  CHECK(simulation_schemes() == choices);
  std::string bar, readme_cell;
  for (const auto& name : choices) {
    bar += (bar.empty() ? "" : " | ") + name;
    readme_cell += (readme_cell.empty() ? "" : ", ") + ("`" + name + "`");
  }
  const ProcessResult help = run_pfgen({"simulate", "--help"});
  CHECK(help.out.find(bar) != std::string::npos);
  const std::string readme = read_file(source_dir() + "/docs/guide/model-file.md");
  CHECK(readme.find("| `scheme` | truth scheme | " + readme_cell + " |") != std::string::npos);
}
