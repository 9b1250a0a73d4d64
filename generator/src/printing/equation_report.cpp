#include "pfgen/printing/equation_report.hpp"

#include <ostream>

#include "pfgen/printing/observation_report.hpp"

namespace pfgen {

std::string equations_text(const Model& model, const FilterEquations& eq) {
  return observation_report(model.observation).text(model, eq, nullptr);
}

void write_equations_text(std::ostream& out, const Model& model, const FilterEquations& eq) {
  const std::string rest = observation_report(model.observation).text(model, eq, &out);
  out.write(rest.data(), static_cast<std::streamsize>(rest.size()));
}

std::string equations_latex(const Model& model, const FilterEquations& eq) { return observation_report(model.observation).latex(model, eq); }

Json equations_json(const Model& model, const FilterEquations& eq) {
  return observation_report(model.observation).json(model, eq);
}

}  // namespace pfgen
