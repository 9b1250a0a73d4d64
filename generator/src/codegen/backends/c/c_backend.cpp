// The C99 backend: its name, file layout, scalar modes and the check of the model's C names; a
// filter's files are its observation module's description written by c_filter_writer.
#include "pfgen/codegen/backends/c/c_backend.hpp"

#include <regex>

#include "pfgen/codegen/backend.hpp"
#include "pfgen/codegen/backends/c/c_filter_writer.hpp"
#include "pfgen/codegen/backends/c/c_names.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {
namespace {

class CBackend final : public Backend {
 public:
  std::string name() const override { return "c"; }
  std::string summary() const override { return "C99 .h/.c pairs"; }
  std::vector<std::string> filter_paths(const std::string& model_name, const std::string& filter_name,
                                        const CodegenOptions&) const override {
    return c_filter_paths(model_name, filter_name);
  }
  // C's scalar defaults to double: `template` is C++'s.
  ScalarMode default_scalar() const override { return ScalarMode::Double; }
  std::optional<std::string> scalar_problem(ScalarMode mode) const override {
    if (mode == ScalarMode::Template) return "C has no templates; give float or double";
    return std::nullopt;
  }
  std::optional<std::string> eigen_problem() const override {
    return "the Eigen wrappers are C++; drop --eigen for --language c";
  }
  void check_model(const Model& model, const std::string& name_space) const override {
    check_c_names(model, name_space);
  }
  GeneratedFilter filter_code(const Model& model, const FilterEquations& eq,
                              const CodegenOptions& options) const override {
    try {
      return write_c_filter(observation_code(model.observation), model, eq, options);
    } catch (const CPartNameError& e) {
      throw CodegenError(source_place(model) + e.what());
    }
  }
};

}  // namespace

std::vector<std::string> c_filter_paths(const std::string& model_name, const std::string& filter_name) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  return {stem + ".h", stem + ".c"};
}

std::string c_symbol_prefix(const std::string& name_space, const std::string& model_name, const std::string& filter_name) {
  return std::regex_replace(name_space, std::regex("::"), "_") + "_" + model_name + "_" + filter_identifier(filter_name);
}

const Backend& c_backend() {
  static const CBackend backend;
  return backend;
}

}  // namespace pfgen::codegen
