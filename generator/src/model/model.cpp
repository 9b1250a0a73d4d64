#include "pfgen/model/model.hpp"

#include "pfgen/algebra/coefficient.hpp"
#include "pfgen_support/truth_schemes.hpp"

#include <algorithm>

namespace pfgen {

ExMatrix multiply_by_transpose(const ExMatrix& g) {
  ExMatrix G(g.size(), ExVector(g.size(), 0));
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (std::size_t j = 0; j < g.size(); ++j) {
      GiNaC::ex sum = 0;
      // Rows of unequal length are reported by validate_model(); never read past a row.
      for (std::size_t k = 0; k < std::min(g[i].size(), g[j].size()); ++k) sum += g[i][k] * g[j][k];
      G[i][j] = sum.expand();
    }
  }
  return G;
}

ExMatrix inverse_noise_covariance(const ExMatrix& B) {
  const ExMatrix R = multiply_by_transpose(B);
  GiNaC::matrix matrix(static_cast<unsigned>(R.size()), static_cast<unsigned>(R.size()));
  for (unsigned i = 0; i < matrix.rows(); ++i)
    for (unsigned j = 0; j < matrix.cols(); ++j) matrix(i, j) = R[i][j];
  const GiNaC::matrix inverse = matrix.inverse();
  ExMatrix out(R.size(), ExVector(R.size()));
  for (unsigned i = 0; i < inverse.rows(); ++i)
    for (unsigned j = 0; j < inverse.cols(); ++j) out[i][j] = normalize_coefficient(inverse(i, j));
  return out;
}

std::string filter_identifier(const std::string& name) {
  std::string out = name;
  std::replace(out.begin(), out.end(), '-', '_');
  std::replace(out.begin(), out.end(), '@', '_');  // cd-euler@5 (model_filters.hpp)
  return out;
}

std::string source_place(const Model& model) { return model.source.empty() ? "" : model.source + ": "; }

std::string SimulationSection::location_of(const std::string& field) const {
  std::string out = source.empty() ? std::string("<model>") : source;
  auto it = locations.find(field);
  if (it != locations.end() && it->second.line > 0) {
    out += ":" + std::to_string(it->second.line);
    if (it->second.column > 0) out += ":" + std::to_string(it->second.column);
  }
  return out;
}

const std::vector<std::string>& simulation_schemes() {
  static const std::vector<std::string> schemes = pfgen_support::truth_scheme_choices();
  return schemes;
}

bool depends_on_states(const Model& model, const GiNaC::ex& e) {
  for (const auto& s : model.states)
    if (e.has(s)) return true;
  return false;
}

}  // namespace pfgen
