// The polynomial observation in code generation: not generated. Its filters' dP has a dy term and
// their gain depends on m, so the generated step needs the Ito-Stratonovich correction
// (observations/polynomial/ito_stratonovich_correction.hpp) and the runtime needs h(x) for the
// truth and the particle reference; until those are written, codegen and simulate refuse these
// filters at once, with derive, latex and eval named as what handles them.
#include "pfgen/codegen/observation_code.hpp"

namespace pfgen::codegen {
namespace {

class PolynomialCode final : public ObservationCode {
 public:
  void check_size(const Model& model, const FilterEquations& eq) const override { refuse(model, eq.name); }
  GeneratedFilter cpp_filter(const Model& model, const FilterEquations& eq, const CodegenOptions&) const override {
    refuse(model, eq.name);
  }
  GeneratedFilter c_filter(const Model& model, const FilterEquations& eq, const CodegenOptions&) const override {
    refuse(model, eq.name);
  }
  void truth_observation(const Model& model, TruthNames&, TruthCode&) const override { refuse(model, ""); }
  std::string plugin_wrappers(const Model& model, const std::vector<std::string>&) const override {
    refuse(model, "");
  }
  std::map<std::string, std::string> plugin_table(const Model& model, const std::vector<std::string>&,
                                                  const std::vector<std::string>&, std::optional<double>) const override {
    refuse(model, "");
  }

 private:
  [[noreturn]] static void refuse(const Model& model, const std::string& filter) {
    throw CodegenError((filter.empty() ? "model " : "filter '" + filter + "' of model ") + model.name +
                       ": code generation and simulation of a polynomial observation dy = h(x, t) dt + B dW2 are not "
                       "available in this version; derive, latex and eval handle its filters");
  }
};

}  // namespace

const ObservationCode& polynomial_observation_code() {
  static const PolynomialCode part;
  return part;
}

}  // namespace pfgen::codegen
