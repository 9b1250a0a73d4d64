// The C++ backend: its name, file layout and scalar modes; a filter's files are its observation
// module's description written by cpp_filter_writer.
#include "pfgen/codegen/backends/cpp/cpp_backend.hpp"

#include "pfgen/codegen/backend.hpp"
#include "pfgen/codegen/backends/cpp/cpp_filter_writer.hpp"
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {
namespace {

class CppBackend final : public Backend {
 public:
  std::string name() const override { return "cpp"; }
  std::string summary() const override { return "header-only C++"; }
  std::vector<std::string> filter_paths(const std::string& model_name, const std::string& filter_name,
                                        const CodegenOptions& options) const override {
    return cpp_filter_paths(model_name, filter_name, options.eigen_wrapper);
  }
  std::string file_role(std::size_t k) const override { return k == 0 ? "" : ", --eigen"; }
  ScalarMode default_scalar() const override { return ScalarMode::Template; }
  GeneratedFilter filter_code(const Model& model, const FilterEquations& eq,
                              const CodegenOptions& options) const override {
    return write_cpp_filter(observation_code(model.observation), model, eq, options);
  }
};

}  // namespace

std::vector<std::string> cpp_filter_paths(const std::string& model_name, const std::string& filter_name,
                                          bool eigen_wrapper) {
  const std::string stem = model_name + "/" + filter_identifier(filter_name);
  if (!eigen_wrapper) return {stem + ".hpp"};
  return {stem + ".hpp", stem + "_eigen.hpp"};
}

const Backend& cpp_backend() {
  static const CppBackend backend;
  return backend;
}

}  // namespace pfgen::codegen
