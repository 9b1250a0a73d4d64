// The Rust backend's config: its name, file layout and scalar modes; a filter's module by its
// observation module's description written by rust_filter_writer.
#include "pfgen/codegen/backend.hpp"
#include "pfgen/codegen/backends/rust/rust_filter_code.hpp"
#include "pfgen/codegen/backends/rust/rust_filter_writer.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {
namespace {

class RustBackend final : public Backend {
 public:
  std::string name() const override { return "rust"; }
  std::string summary() const override { return "no_std Rust modules"; }
  std::vector<std::string> filter_paths(const std::string& model_name, const std::string& filter_name,
                                        const CodegenOptions&) const override {
    return rust_filter_paths(model_name, filter_name);
  }
  ScalarMode default_scalar() const override { return ScalarMode::Double; }
  std::optional<std::string> scalar_problem(ScalarMode mode) const override {
    if (mode == ScalarMode::Template) return "Rust has no templates; give float or double";
    return std::nullopt;
  }
  std::optional<std::string> eigen_problem() const override {
    return "the Eigen wrappers are C++; drop --eigen for --language rust";
  }
  GeneratedFilter filter_code(const Model& model, const FilterEquations& eq,
                              const CodegenOptions& options) const override {
    return write_rust_filter(observation_code(model.observation), model, eq, options);
  }
};

}  // namespace

std::vector<std::string> rust_filter_paths(const std::string& model_name, const std::string& filter_name) {
  return {model_name + "/" + filter_identifier(filter_name) + ".rs"};
}

const Backend& rust_backend() {
  static const RustBackend backend;
  return backend;
}

}  // namespace pfgen::codegen
