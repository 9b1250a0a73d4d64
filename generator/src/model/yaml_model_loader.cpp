#include "pfgen/model/yaml_model_loader.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "pfgen/model/decimal_literals.hpp"
#include "pfgen/model/expression_parser.hpp"
#include "pfgen/model/model_builder.hpp"
#include "pfgen/model/model_error.hpp"

namespace pfgen {
namespace {

const std::set<std::string> kTopLevelFields = {
    "name",      "states",      "parameters",         "time",
    "drift",     "diffusion",   "diffusion_covariance", "additive_diffusion",
    "additive_diffusion_covariance", "observation", "initial"};

// Where each field and matrix entry sits in the file, for error messages.
class LocationIndex {
 public:
  void record(const std::string& field, const YAML::Node& node, std::optional<int> row = {},
              std::optional<int> column = {}) {
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0) return;
    marks_[key(field, row, column)] = SourceLocation{mark.line + 1, mark.column + 1};
  }
  SourceLocation find(const ModelError& e) const {
    for (const auto& k : {key(e.field(), e.row(), e.column()), key(e.field(), e.row(), {}),
                          key(e.field(), {}, {}), key(top_field(e.field()), {}, {})}) {
      auto it = marks_.find(k);
      if (it != marks_.end()) return it->second;
    }
    return {};
  }

 private:
  static std::string key(const std::string& field, std::optional<int> row, std::optional<int> column) {
    return field + "#" + (row ? std::to_string(*row) : "") + "#" + (column ? std::to_string(*column) : "");
  }
  static std::string top_field(const std::string& field) { return field.substr(0, field.find('.')); }
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
                          "observation, initial)");
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
    read_observation(builder, parser);
    read_initial(builder);
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
    if (!node.IsScalar()) throw ModelError(field, "expected a single value", row, column);
    return node.Scalar();
  }

  YAML::Node sequence(const YAML::Node& node, const std::string& field, std::optional<int> row = {}) {
    index_.record(field, node, row);
    if (!node.IsSequence()) throw ModelError(field, row ? "expected a list (one row of the matrix)" : "expected a list", row);
    return node;
  }

  void read_symbols(ModelBuilder& builder) {
    YAML::Node states = sequence(required("states"), "states");
    for (std::size_t i = 0; i < states.size(); ++i)
      builder.state(scalar(states[i], "states", static_cast<int>(i + 1)));
    if (YAML::Node params = root_["parameters"]; params && !params.IsNull()) {
      index_.record("parameters", params);
      if (!params.IsMap()) throw ModelError("parameters", "expected a mapping name: default value");
      for (const auto& entry : params) {
        std::string name = scalar(entry.first, "parameters");
        std::string field = "parameters." + name;
        std::string text = scalar(entry.second, field);
        auto value = parse_exact_number(text);
        if (!value) throw ModelError(field, "default value '" + text + "' is not a number");
        builder.parameter(name, *value);
      }
    }
    if (YAML::Node time = root_["time"]; time && !time.IsNull()) builder.time(scalar(time, "time"));
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
    if (!obs.IsMap()) throw ModelError("observation", "expected a mapping with A0, A and B");
    for (const auto& entry : obs) {
      std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
      if (key != "A0" && key != "A" && key != "B") {
        index_.record("observation." + key, entry.first);
        throw ModelError("observation." + key, "unknown field (known: A0, A, B)");
      }
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
    builder.observation(A0, A, B);
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
    if (YAML::Node x0 = init["x0"]; x0 && !x0.IsNull()) ic.x0 = number_list(x0, "initial.x0");
    if (!init["m0"] || init["m0"].IsNull()) throw ModelError("initial.m0", "missing required field");
    if (!init["P0"] || init["P0"].IsNull()) throw ModelError("initial.P0", "missing required field");
    ic.m0 = number_list(init["m0"], "initial.m0");
    YAML::Node rows = sequence(init["P0"], "initial.P0");
    for (std::size_t i = 0; i < rows.size(); ++i)
      ic.P0.push_back(number_list(rows[i], "initial.P0", static_cast<int>(i + 1)));
    builder.initial(ic);
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

}  // namespace

Model load_model_text(const std::string& text, const std::string& path) {
  if (!is_text(text)) throw located(ModelError("", "not a model file: the file is binary, not UTF-8 text"), path, {});
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw located(ModelError("", "not valid YAML: " + e.msg), path, {e.mark.line + 1, e.mark.column + 1});
  }
  if (!root || root.IsNull()) throw located(ModelError("", "the model file is empty"), path, {});
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
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return load_model_text(buffer.str(), path);
}

}  // namespace pfgen
