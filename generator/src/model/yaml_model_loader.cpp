#include "pfgen/model/yaml_model_loader.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/expression_parser.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"
#include "pfgen/model/model_validator.hpp"
#include "pfgen/model/yaml_alias_bound.hpp"
#include "pfgen/model/yaml_documents.hpp"
#include "pfgen_support/quoted_text.hpp"

namespace pfgen {
namespace {

const std::set<std::string> kTopLevelFields = {
    "name",      "states",      "parameters",         "time",
    "drift",     "diffusion",   "diffusion_covariance", "additive_diffusion",
    "additive_diffusion_covariance", "noise", "observation", "initial", "risk", "filters", "simulation", "bounds"};

const char* const kSampledFields = "period, C or c, Uv, C0, substeps";
const char* const kUserFilterFields = "m_drift, P_drift, gain, define, description";
const char* const kSimulationFields =
    "T, dt, runs, seed, filters, scheme, report_times, windows, record_points, bound, shown_run";

// Where each field and matrix entry sits in the file, for error messages.
class LocationIndex {
 public:
  void record(const std::string& field, const YAML::Node& node, std::optional<int> row = {},
              std::optional<int> column = {}) {
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0) return;
    marks_[key(field, row, column)] = SourceLocation{mark.line + 1, mark.column + 1};
  }
  // The entry itself, else its row, else the field, else the field's enclosing fields
  // ("filters.mine.gain", then "filters.mine", then "filters").
  SourceLocation find(const ModelError& e) const {
    std::vector<std::string> keys = {key(e.field(), e.row(), e.column()), key(e.field(), e.row(), {})};
    for (std::string field = e.field();; field = field.substr(0, field.rfind('.'))) {
      keys.push_back(key(field, {}, {}));
      if (field.find('.') == std::string::npos) break;
    }
    for (const auto& k : keys) {
      auto it = marks_.find(k);
      if (it != marks_.end()) return it->second;
    }
    return {};
  }

 private:
  static std::string key(const std::string& field, std::optional<int> row, std::optional<int> column) {
    return field + "#" + (row ? std::to_string(*row) : "") + "#" + (column ? std::to_string(*column) : "");
  }
  std::map<std::string, SourceLocation> marks_;
};

class Loader {
 public:
  Loader(const YAML::Node& root, const std::string& path) : root_(root), path_(path) {}

  Model load() {
    if (!root_.IsMap())
      throw ModelError("", "the top level of a model file must be a mapping of fields (name, states, drift, ...)");
    for (const auto& entry : root_) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      if (!kTopLevelFields.count(key)) {
        ModelError e(key, "unknown field (known: name, states, parameters, time, drift, diffusion, "
                          "diffusion_covariance, additive_diffusion, additive_diffusion_covariance, "
                          "observation, initial, risk, filters, simulation)");
        e.set_location(SourceLocation{entry.first.Mark().line + 1, entry.first.Mark().column + 1});
        throw e;
      }
      index_.record(key, entry.first);
    }
    ModelBuilder builder(scalar(required("name"), "name"), path_);
    read_symbols(builder);
    ExpressionParser parser(builder.symbols());
    builder.drift(vector_field(required("drift"), "drift", parser));
    read_diffusion(builder, parser, "diffusion", "diffusion_covariance", true);
    read_diffusion(builder, parser, "additive_diffusion", "additive_diffusion_covariance", false);
    read_noise(builder);
    read_observation(builder, parser);
    read_initial(builder);
    read_risk(builder, parser);
    read_bounds(builder);
    read_filters(builder);
    read_simulation(builder);
    return builder.build();
  }

  const LocationIndex& index() const { return index_; }

 private:
  YAML::Node required(const std::string& field) {
    YAML::Node node = root_[field];
    if (!node || node.IsNull()) throw ModelError(field, "missing required field");
    return node;
  }

  std::string scalar(const YAML::Node& node, const std::string& field, std::optional<int> row = {},
                     std::optional<int> column = {}) {
    index_.record(field, node, row, column);
    // YAML reads an empty entry, ~, null, Null and NULL as no value at all.
    if (node.IsNull())
      throw ModelError(field, "expected a single value, found none (YAML reads ~ and null, Null or NULL as no value: "
                              "quote it, \"NULL\", to mean the text)", row, column);
    if (!node.IsScalar()) throw ModelError(field, "expected a single value", row, column);
    return node.Scalar();
  }

  // A state's, parameter's or time's name, checked as it is read: the expressions that use it
  // come later, and a name that is no identifier would otherwise be reported there first.
  std::string name(const YAML::Node& node, const std::string& field, std::optional<int> row = {}) {
    std::string text = scalar(node, field, row);
    if (auto problem = identifier_problem(text)) throw ModelError(field, *problem, row);
    return text;
  }

  YAML::Node sequence(const YAML::Node& node, const std::string& field, std::optional<int> row = {}) {
    index_.record(field, node, row);
    if (!node.IsSequence()) throw ModelError(field, row ? "expected a list (one row of the matrix)" : "expected a list", row);
    return node;
  }

  void read_symbols(ModelBuilder& builder) {
    YAML::Node states = sequence(required("states"), "states");
    for (std::size_t i = 0; i < states.size(); ++i)
      builder.state(name(states[i], "states", static_cast<int>(i + 1)));
    if (YAML::Node params = root_["parameters"]; params && !params.IsNull()) {
      index_.record("parameters", params);
      if (!params.IsMap()) throw ModelError("parameters", "expected a mapping name: default value");
      for (const auto& entry : params) {
        std::string parameter = name(entry.first, "parameters");
        std::string field = "parameters." + parameter;
        std::string text = scalar(entry.second, field);
        auto value = parse_exact_number(text);
        if (!value) throw ModelError(field, "default value '" + text + "' is not a number");
        builder.parameter(parameter, *value);
      }
    }
    if (YAML::Node time = root_["time"]; time && !time.IsNull()) builder.time(name(time, "time"));
  }

  ExVector vector_field(const YAML::Node& node, const std::string& field, const ExpressionParser& parser) {
    YAML::Node list = sequence(node, field);
    ExVector out;
    for (std::size_t i = 0; i < list.size(); ++i) {
      int row = static_cast<int>(i + 1);
      out.push_back(parser.parse(scalar(list[i], field, row), ExpressionSite{field, row, std::nullopt}));
    }
    return out;
  }

  ExMatrix matrix_field(const YAML::Node& node, const std::string& field, const ExpressionParser& parser) {
    YAML::Node rows = sequence(node, field);
    ExMatrix out;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      int row = static_cast<int>(i + 1);
      YAML::Node entries = sequence(rows[i], field, row);
      ExVector values;
      for (std::size_t j = 0; j < entries.size(); ++j) {
        int column = static_cast<int>(j + 1);
        values.push_back(parser.parse(scalar(entries[j], field, row, column), ExpressionSite{field, row, column}));
      }
      out.push_back(values);
    }
    return out;
  }

  void read_diffusion(ModelBuilder& builder, const ExpressionParser& parser, const std::string& g_field,
                      const std::string& G_field, bool required_field) {
    YAML::Node g = root_[g_field];
    YAML::Node G = root_[G_field];
    bool has_g = g && !g.IsNull();
    bool has_G = G && !G.IsNull();
    if (has_g && has_G) throw ModelError(G_field, "give either " + g_field + " or " + G_field + ", not both");
    if (!has_g && !has_G) {
      if (required_field) throw ModelError(g_field, "missing required field (give " + g_field + " or " + G_field + ")");
      return;
    }
    bool additive = g_field == "additive_diffusion";
    if (has_g) {
      ExMatrix m = matrix_field(g, g_field, parser);
      additive ? builder.additive_diffusion(m) : builder.diffusion(m);
    } else {
      ExMatrix m = matrix_field(G, G_field, parser);
      additive ? builder.additive_diffusion_covariance(m) : builder.diffusion_covariance(m);
    }
  }

  void read_observation(ModelBuilder& builder, const ExpressionParser& parser) {
    YAML::Node obs = required("observation");
    if (!obs.IsMap()) throw ModelError("observation", "expected a mapping with A0, A and B (or sampled: {...})");
    if (YAML::Node sampled = obs["sampled"]; sampled) {
      for (const auto& entry : obs) {
        std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
        if (key != "sampled") {
          index_.record("observation." + key, entry.first);
          throw ModelError("observation." + key, "a sampled observation has only the field sampled: {period, C or c, Uv, C0, substeps}");
        }
        index_.record("observation.sampled", entry.first);
      }
      read_sampled_observation(builder, parser, sampled);
      return;
    }
    // observation: {h: [...], B: [[...]]}: dy = h(x, t) dt + B dW2 with h polynomial in the states.
    if (YAML::Node h_node = obs["h"]; h_node) {
      for (const auto& entry : obs) {
        std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
        index_.record("observation." + key, entry.first);
        if (key != "h" && key != "B")
          throw ModelError("observation." + key,
                           std::string("a polynomial observation dy = h(x, t) dt + B dW2 has the fields h and B only") +
                               (key == "A0" || key == "A" ? " (A0 + A x is h written as a linear polynomial)"
                                                          : key == "delay" ? " (a delayed observation is A0 + A x(t - h))"
                                                                           : ""));
      }
      YAML::Node B_node = obs["B"];
      if (!B_node || B_node.IsNull()) throw ModelError("observation.B", "missing required field");
      builder.polynomial_observation(vector_field(h_node, "observation.h", parser),
                                     matrix_field(B_node, "observation.B", parser));
      return;
    }
    for (const auto& entry : obs) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      index_.record("observation." + key, entry.first);
      if (key != "A0" && key != "A" && key != "B" && key != "delay")
        throw ModelError("observation." + key,
                         "unknown field (known: A0, A, B, delay), or sampled: {period, C, Uv} for sampled measurements");
    }
    YAML::Node A_node = obs["A"];
    YAML::Node B_node = obs["B"];
    if (!A_node || A_node.IsNull()) throw ModelError("observation.A", "missing required field");
    if (!B_node || B_node.IsNull()) throw ModelError("observation.B", "missing required field");
    ExMatrix A = matrix_field(A_node, "observation.A", parser);
    ExMatrix B = matrix_field(B_node, "observation.B", parser);
    ExVector A0(A.size(), GiNaC::ex(0));
    if (YAML::Node A0_node = obs["A0"]; A0_node && !A0_node.IsNull())
      A0 = vector_field(A0_node, "observation.A0", parser);
    // The delay is a plain number, like a sampled period: the history the filters keep and the
    // simulator's delayed truth need its value whatever the parameters are set to. `delay: 0` is
    // today's undelayed model, with its filters.
    if (YAML::Node delay_node = obs["delay"]; delay_node && !delay_node.IsNull()) {
      const std::string text = scalar(delay_node, "observation.delay");
      auto delay = parse_exact_number(text);
      if (!delay) throw ModelError("observation.delay", pfgen_support::quoted(text) + " is not a number: the delay h is a plain number of "
                                                                   "time units (no parameters or expressions)");
      if (auto problem = double_range_problem(*delay))
        throw ModelError("observation.delay", pfgen_support::quoted(text) + " " + *problem);
      if (!delay->is_zero()) {
        builder.delayed_observation(*delay, A0, A, B);
        return;
      }
    }
    builder.observation(A0, A, B);
  }

  // observation: {sampled: {period: T, C: [[...]], Uv: [[...]], C0: [...], substeps: N}}
  void read_sampled_observation(ModelBuilder& builder, const ExpressionParser& parser, const YAML::Node& sampled) {
    const std::string field = "observation.sampled";
    if (!sampled.IsMap()) throw ModelError(field, std::string("expected a mapping with ") + kSampledFields);
    for (const auto& entry : sampled) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      index_.record(field + "." + key, entry.first);
      if (key != "period" && key != "C" && key != "c" && key != "Uv" && key != "C0" && key != "substeps")
        throw ModelError(field + "." + key, std::string("unknown field (known: ") + kSampledFields + ")");
    }
    // y_k = c(x) + Uv v_k (c polynomial) or C0 + C x + Uv v_k: one of the two forms.
    const bool polynomial = sampled["c"] && !sampled["c"].IsNull();
    if (polynomial)
      for (const char* key : {"C", "C0"})
        if (sampled[key])
          throw ModelError(field + "." + key, "samples given by c: y = c(x) + Uv v has no C0 or C (C0 + C x is c "
                                              "written as a linear polynomial)");
    for (const char* key : {"period", polynomial ? "c" : "C", "Uv"})
      if (!sampled[key] || sampled[key].IsNull()) throw ModelError(field + "." + key, "missing required field");
    // The period is a plain number, not an expression: the generated code and the simulator's
    // sample grid need its value, whatever the parameters are set to.
    const std::string period_text = scalar(sampled["period"], field + ".period");
    auto period = parse_exact_number(period_text);
    if (!period) throw ModelError(field + ".period", pfgen_support::quoted(period_text) + " is not a number");
    if (auto problem = double_range_problem(*period))
      throw ModelError(field + ".period", pfgen_support::quoted(period_text) + " " + *problem);
    std::optional<std::size_t> substeps;  // absent: each filter chooses (substep_choice.hpp)
    if (YAML::Node s = sampled["substeps"]; s && !s.IsNull())
      substeps = static_cast<std::size_t>(whole_number(s, field + ".substeps", 1000000));
    if (polynomial) {
      const ExVector c = vector_field(sampled["c"], field + ".c", parser);
      if (c.empty()) throw ModelError(field + ".c", "at least one observation is required");
      builder.sampled_polynomial_observation(*period, c, matrix_field(sampled["Uv"], field + ".Uv", parser), substeps);
      return;
    }
    ExMatrix C = matrix_field(sampled["C"], field + ".C", parser);
    ExMatrix Uv = matrix_field(sampled["Uv"], field + ".Uv", parser);
    ExVector C0(C.size(), GiNaC::ex(0));
    if (YAML::Node C0_node = sampled["C0"]; C0_node && !C0_node.IsNull())
      C0 = vector_field(C0_node, field + ".C0", parser);
    builder.sampled_observation(*period, C0, C, Uv, substeps);
  }

  std::vector<GiNaC::numeric> number_list(const YAML::Node& node, const std::string& field,
                                          std::optional<int> row = {}) {
    YAML::Node list = sequence(node, field, row);
    std::vector<GiNaC::numeric> out;
    for (std::size_t j = 0; j < list.size(); ++j) {
      std::optional<int> r = row ? row : std::optional<int>(static_cast<int>(j + 1));
      std::optional<int> c = row ? std::optional<int>(static_cast<int>(j + 1)) : std::nullopt;
      std::string text = scalar(list[j], field, r, c);
      auto value = parse_exact_number(text);
      if (!value) throw ModelError(field, "'" + text + "' is not a number", r, c);
      out.push_back(*value);
    }
    return out;
  }

  void read_initial(ModelBuilder& builder) {
    YAML::Node init = root_["initial"];
    if (!init || init.IsNull()) return;
    if (!init.IsMap()) throw ModelError("initial", "expected a mapping with x0, m0 and P0");
    for (const auto& entry : init) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      if (key != "x0" && key != "m0" && key != "P0") {
        index_.record("initial." + key, entry.first);
        throw ModelError("initial." + key, "unknown field (known: x0, m0, P0)");
      }
    }
    InitialConditions ic;
    if (YAML::Node x0 = init["x0"]; x0 && !x0.IsNull()) {
      if (x0.IsScalar() && x0.Scalar() == "prior")
        ic.x0_from_prior = true;  // drawn per run from N(m0, P0) by simulate
      else
        ic.x0 = number_list(x0, "initial.x0");
    }
    if (!init["m0"] || init["m0"].IsNull()) throw ModelError("initial.m0", "missing required field");
    if (!init["P0"] || init["P0"].IsNull()) throw ModelError("initial.P0", "missing required field");
    ic.m0 = number_list(init["m0"], "initial.m0");
    YAML::Node rows = sequence(init["P0"], "initial.P0");
    for (std::size_t i = 0; i < rows.size(); ++i)
      ic.P0.push_back(number_list(rows[i], "initial.P0", static_cast<int>(i + 1)));
    builder.initial(ic);
  }

  // bounds: {NAME: [low, high], ...}: where `pfgen fit` may look for each parameter; an end given
  // as ~ (null) is unbounded. The validator checks the names and the order.
  void read_bounds(ModelBuilder& builder) {
    YAML::Node bounds = root_["bounds"];
    if (!bounds || bounds.IsNull()) return;
    if (!bounds.IsMap()) throw ModelError("bounds", "expected a mapping of parameters to [low, high]");
    std::vector<ParameterBound> out;
    for (const auto& entry : bounds) {
      const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      const std::string field = "bounds." + name;
      index_.record(field, entry.first);
      YAML::Node ends = entry.second;
      if (!ends.IsSequence() || ends.size() != 2)
        throw ModelError(field, "expected [low, high] (an end may be ~ for none)");
      ParameterBound bound{name, std::nullopt, std::nullopt};
      for (std::size_t k = 0; k < 2; ++k) {
        if (ends[k].IsNull()) continue;
        const std::string text = scalar(ends[k], field, std::nullopt, static_cast<int>(k + 1));
        auto value = parse_exact_number(text);
        if (!value) throw ModelError(field, "'" + text + "' is not a number", std::nullopt, static_cast<int>(k + 1));
        (k == 0 ? bound.low : bound.high) = *value;
      }
      out.push_back(bound);
    }
    builder.parameter_bounds(out);
  }

  // risk: {epsilon: EXPR, weight: [[...]]}: the exponential criterion J (RiskCriterion).
  void read_risk(ModelBuilder& builder, const ExpressionParser& parser) {
    YAML::Node risk = root_["risk"];
    if (!risk || risk.IsNull()) return;
    if (!risk.IsMap()) throw ModelError("risk", "expected a mapping with epsilon and, optionally, weight");
    for (const auto& entry : risk) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      if (key != "epsilon" && key != "weight") {
        index_.record("risk." + key, entry.first);
        throw ModelError("risk." + key, "unknown field (known: epsilon, weight)");
      }
    }
    if (!risk["epsilon"] || risk["epsilon"].IsNull()) throw ModelError("risk.epsilon", "missing required field");
    GiNaC::ex epsilon = parser.parse(scalar(risk["epsilon"], "risk.epsilon"), ExpressionSite{"risk.epsilon", {}, {}});
    ExMatrix weight;
    if (YAML::Node w = risk["weight"]; w && !w.IsNull()) weight = matrix_field(w, "risk.weight", parser);
    builder.risk_criterion(epsilon, weight);
  }

  // define: {NAME: "expression", ...}, in file order: each expression may read the filter's
  // variables, the parameters, t and the names defined above it, which is why each is parsed
  // with a table that grows by one name at a time. The names join `symbols` for the equations.
  std::vector<FilterDefinition> read_definitions(const YAML::Node& define, const std::string& field,
                                                 GiNaC::symtab& symbols) {
    std::vector<FilterDefinition> definitions;
    if (!define || define.IsNull()) return definitions;
    if (!define.IsMap())
      throw ModelError(field, "expected a mapping of names to expressions, e.g. {D: \"1/(P11*P22 - P12^2)\"}");
    for (const auto& item : define) {
      if (!item.first.IsScalar()) {
        index_.record(field, item.first);
        throw ModelError(field, "a definition's name must be a single value");
      }
      const std::string name = item.first.Scalar();
      const std::string entry_field = field + "." + name;
      index_.record(entry_field, item.first);
      if (symbols.count(name))
        throw ModelError(entry_field, "'" + name + "' is already a name of the model or of this filter (a state, "
                                      "parameter, the time, m1, P11, ... or an earlier definition); give the "
                                      "definition another name");
      GiNaC::ex value;
      try {
        value = ExpressionParser(symbols).parse(scalar(item.second, entry_field), ExpressionSite{entry_field, {}, {}});
      } catch (const ModelError& e) {
        if (e.message().rfind("unknown symbol", 0) != 0) throw;
        throw ModelError(e.field(), e.message() + " (a definition reads the filter's m and P, the parameters, the time "
                                                  "and the names defined above it)");
      }
      const GiNaC::symbol symbol(name);
      symbols[name] = symbol;
      definitions.push_back(FilterDefinition{symbol, value});
    }
    return definitions;
  }

  // noise: ito | stratonovich (default ito).
  void read_noise(ModelBuilder& builder) {
    YAML::Node node = root_["noise"];
    if (!node || node.IsNull()) return;
    const std::string value = scalar(node, "noise");
    if (value == "stratonovich") {
      builder.noise(NoiseCalculus::Stratonovich);
    } else if (value != "ito") {
      throw ModelError("noise", "must be ito or stratonovich, found '" + value + "'");
    }
  }

  // filters: {NAME: {m_drift: [...], P_drift: [[...]], gain: [[...]], define: {...}, description: "..."}}
  void read_filters(ModelBuilder& builder) {
    YAML::Node filters = root_["filters"];
    if (!filters || filters.IsNull()) return;
    if (!filters.IsMap())
      throw ModelError("filters", "expected a mapping of filter names to {m_drift, P_drift, gain}");
    const GiNaC::symtab filter_symbols = builder.filter_symbols();
    for (const auto& entry : filters) {
      if (!entry.first.IsScalar()) {
        index_.record("filters", entry.first);
        throw ModelError("filters", "a filter's name must be a single value");
      }
      const std::string name = entry.first.Scalar();
      const std::string field = "filters." + name;
      index_.record(field, entry.first);
      const YAML::Node body = entry.second;
      if (!body.IsMap())
        throw ModelError(field, std::string("expected a mapping with ") + kUserFilterFields);
      for (const auto& item : body) {
        std::string key = item.first.IsScalar() ? item.first.Scalar() : "?";
        if (key != "m_drift" && key != "P_drift" && key != "gain" && key != "define" && key != "description") {
          index_.record(field + "." + key, item.first);
          throw ModelError(field + "." + key, std::string("unknown field (known: ") + kUserFilterFields + ")");
        }
        index_.record(field + "." + key, item.first);
      }
      for (const char* key : {"m_drift", "P_drift", "gain"})
        if (!body[key] || body[key].IsNull()) throw ModelError(field + "." + key, "missing required field");
      std::string description;
      if (YAML::Node d = body["description"]; d && !d.IsNull()) description = scalar(d, field + ".description");
      GiNaC::symtab symbols = filter_symbols;
      const std::vector<FilterDefinition> definitions = read_definitions(body["define"], field + ".define", symbols);
      const ExpressionParser parser(symbols);
      ExVector m_drift = vector_field(body["m_drift"], field + ".m_drift", parser);
      ExMatrix P_drift = matrix_field(body["P_drift"], field + ".P_drift", parser);
      ExMatrix gain = matrix_field(body["gain"], field + ".gain", parser);
      builder.user_filter(name, m_drift, P_drift, gain, description, definitions);
    }
  }

  // A plain real number (double) of the simulation section.
  double real_number(const YAML::Node& node, const std::string& field, std::optional<int> row = {},
                     std::optional<int> column = {}) {
    std::string text = scalar(node, field, row, column);
    // parse_exact_number decides what a number is (no nan, inf, hex); strtod rounds it.
    if (!parse_exact_number(text)) throw ModelError(field, "'" + text + "' is not a number", row, column);
    double value = std::strtod(text.c_str(), nullptr);
    if (!std::isfinite(value)) throw ModelError(field, "'" + text + "' is out of range", row, column);
    return value;
  }

  std::uint64_t whole_number(const YAML::Node& node, const std::string& field, std::uint64_t max) {
    std::string text = scalar(node, field);
    static const std::regex digits("^[0-9]+$");
    if (!std::regex_match(text, digits))
      throw ModelError(field, "'" + text + "' is not a whole number (0, 1, 2, ...)");
    std::uint64_t value = 0;
    for (char c : text) {
      const std::uint64_t digit = static_cast<std::uint64_t>(c - '0');
      if (value > (max - digit) / 10) throw ModelError(field, "'" + text + "' is too large");
      value = value * 10 + digit;
    }
    return value;
  }

  void read_simulation(ModelBuilder& builder) {
    YAML::Node sim = root_["simulation"];
    if (!sim || sim.IsNull()) return;
    if (!sim.IsMap()) throw ModelError("simulation", std::string("expected a mapping of settings (") + kSimulationFields + ")");
    SimulationSection s;
    s.source = path_;
    const auto size_max = static_cast<std::uint64_t>(std::numeric_limits<std::size_t>::max());
    for (const auto& entry : sim) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      const std::string field = "simulation." + key;
      index_.record(field, entry.first);
      s.locations[key] = SourceLocation{entry.first.Mark().line + 1, entry.first.Mark().column + 1};
      const YAML::Node value = entry.second;
      if (!value || value.IsNull()) throw ModelError(field, "missing value");
      if (key == "T") {
        s.T = real_number(value, field);
      } else if (key == "dt") {
        s.dt = real_number(value, field);
      } else if (key == "bound") {
        s.bound = real_number(value, field);
      } else if (key == "runs") {
        s.runs = static_cast<std::size_t>(whole_number(value, field, size_max));
      } else if (key == "record_points") {
        s.record_points = static_cast<std::size_t>(whole_number(value, field, size_max));
      } else if (key == "shown_run") {
        s.shown_run = static_cast<std::size_t>(whole_number(value, field, size_max));
      } else if (key == "seed") {
        s.seed = whole_number(value, field, std::numeric_limits<std::uint64_t>::max());
      } else if (key == "scheme") {
        s.scheme = scalar(value, field);
      } else if (key == "filters") {
        YAML::Node list = sequence(value, field);
        s.filters.emplace();
        for (std::size_t k = 0; k < list.size(); ++k) s.filters->push_back(scalar(list[k], field, static_cast<int>(k + 1)));
      } else if (key == "report_times") {
        YAML::Node list = sequence(value, field);
        for (std::size_t k = 0; k < list.size(); ++k)
          s.report_times.push_back(real_number(list[k], field, static_cast<int>(k + 1)));
      } else if (key == "windows") {
        YAML::Node list = sequence(value, field);
        for (std::size_t k = 0; k < list.size(); ++k) {
          const int row = static_cast<int>(k + 1);
          YAML::Node pair = sequence(list[k], field, row);
          if (pair.size() != 2)
            throw ModelError(field, "a window is [start, end], found " + std::to_string(pair.size()) + " values", row);
          s.windows.emplace_back(real_number(pair[0], field, row, 1), real_number(pair[1], field, row, 2));
        }
      } else {
        throw ModelError(field, std::string("unknown field (known: ") + kSimulationFields + ")");
      }
    }
    builder.simulation(s);
  }

  YAML::Node root_;
  std::string path_;
  LocationIndex index_;
};

bool is_text(const std::string& bytes) {
  // Valid UTF-8 without NUL bytes: binary files are refused before YAML sees them.
  std::size_t i = 0;
  while (i < bytes.size()) {
    unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c == 0) return false;
    std::size_t extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : 99;
    if (extra == 99 || i + extra >= bytes.size()) return false;
    for (std::size_t k = 1; k <= extra; ++k)
      if ((static_cast<unsigned char>(bytes[i + k]) >> 6) != 0x2) return false;
    i += extra + 1;
  }
  return true;
}

ModelError located(ModelError e, const std::string& path, SourceLocation where) {
  e.set_file(path);
  if (e.location().line == 0) e.set_location(where);
  return e;
}

// yaml-cpp keeps the first of two equal keys in a mapping and drops the second without a word
// (a second `drift:` was ignored), and YAML::Load reads only the first document of a file. Both
// would run a model other than the one written: refuse them. `field` is the dotted path so far.
void refuse_duplicate_keys(const YAML::Node& node, const std::string& field, const std::string& path, int depth) {
  if (depth > 64) return;  // no model is this deep; the loader refuses such a file on its own terms
  if (node.IsSequence()) {
    for (const auto& item : node) refuse_duplicate_keys(item, field, path, depth + 1);
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, YAML::Mark> seen;
  for (const auto& entry : node) {
    const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
    const std::string here = field.empty() ? key : field + "." + key;
    const auto [first, inserted] = seen.emplace(key, entry.first.Mark());
    if (!inserted)
      throw located(ModelError(here, "given twice in one mapping (first at line " +
                                         std::to_string(first->second.line + 1) + "); keep one"),
                    path, {entry.first.Mark().line + 1, entry.first.Mark().column + 1});
    refuse_duplicate_keys(entry.second, here, path, depth + 1);
  }
}

void refuse_second_document(const std::string& text, const std::string& path) {
  const YamlDocuments documents = count_yaml_documents(text);
  if (documents.parse_error) return;  // the first document's parse reports it
  const SourceLocation where{documents.line + 1, documents.column + 1};
  if (documents.stuck)
    throw located(ModelError("", "not valid YAML from here on: the text after the first document does not parse "
                                 "(an unclosed [ or a stray ] or quote before it?)"),
                  path, where);
  if (documents.count > 1)
    throw located(ModelError("", "the file holds " + std::string(documents.count >= 1000 ? "at least " : "") +
                                     std::to_string(documents.count) +
                                     " YAML documents (separated by ---); a model file is one document"),
                  path, where);
}

// A model's text beyond the bound of a model file: the file read in memory (the API's from_yaml)
// is refused as the file is, before its parse takes seconds per hundred megabytes.
void refuse_oversized(const std::string& text, const std::string& path) {
  if (text.size() > kMaxModelFileBytes)
    throw located(
        ModelError("", "the model file is larger than " + std::to_string(kMaxModelFileBytes >> 20) + " MiB: not a model file"),
        path, {});
}

}  // namespace

Model load_model_text(const std::string& text, const std::string& path) {
  refuse_oversized(text, path);
  if (!is_text(text)) throw located(ModelError("", "not a model file: the file is binary, not UTF-8 text"), path, {});
  const YamlAliasExpansion expansion = expand_yaml_aliases(text);
  if (expansion.exceeded)
    throw located(ModelError("", "its aliases expand to more than " + std::to_string(kMaxYamlNodes) +
                                     " YAML nodes (nested aliases of aliases); a model file needs far fewer"),
                  path, {expansion.line + 1, expansion.column + 1});
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own bound on its recursion (a few hundred nested collections); its message is
    // only "bad file".
    throw located(ModelError("", "not valid YAML: collections nest too deeply"), path,
                  {e.mark.line + 1, e.mark.column + 1});
  } catch (const YAML::Exception& e) {
    throw located(ModelError("", "not valid YAML: " + e.msg), path, {e.mark.line + 1, e.mark.column + 1});
  }
  if (!root || root.IsNull()) throw located(ModelError("", "the model file is empty"), path, {});
  refuse_second_document(text, path);
  refuse_duplicate_keys(root, "", path, 0);
  Loader loader(root, path);
  try {
    return loader.load();
  } catch (const ModelError& e) {
    throw located(e, path, loader.index().find(e));
  } catch (const YAML::Exception& e) {
    throw located(ModelError("", "malformed model: " + e.msg), path, {e.mark.line + 1, e.mark.column + 1});
  }
}

Model load_model_file(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored))
    throw located(ModelError("", "cannot read the model file: it is a directory"), path, {});
  std::ifstream in(path, std::ios::binary);
  if (!in) throw located(ModelError("", "cannot open the model file"), path, {});
  // Read in pieces up to a bound: /dev/zero, or a file as large as the disk, is refused at the
  // bound instead of filling the memory (the dense cubic n = 20 model is under 3 MB).
  std::string text;
  char piece[65536];
  while (in.read(piece, sizeof piece) || in.gcount() > 0) {
    text.append(piece, static_cast<std::size_t>(in.gcount()));
    refuse_oversized(text, path);
  }
  return load_model_text(text, path);
}

}  // namespace pfgen
