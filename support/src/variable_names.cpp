#include "pfgen_support/variable_names.hpp"

namespace pfgen_support {
namespace {

std::string one_based(std::size_t i) { return std::to_string(i + 1); }

}  // namespace

bool separates_covariance_indices(std::size_t n) { return n >= 10; }

std::string mean_name(std::size_t i) { return "m" + one_based(i); }

std::string mean_latex_name(std::size_t i) { return "m_{" + one_based(i) + "}"; }

std::string covariance_name(std::size_t i, std::size_t j, std::size_t n) {
  return "P" + one_based(i) + (separates_covariance_indices(n) ? "_" : "") + one_based(j);
}

std::string covariance_latex_name(std::size_t i, std::size_t j, std::size_t n) {
  return "P_{" + one_based(i) + (separates_covariance_indices(n) ? "," : "") + one_based(j) + "}";
}

std::vector<std::string> filter_variable_names(std::size_t n) {
  std::vector<std::string> names;
  names.reserve(n + n * (n + 1) / 2);
  for (std::size_t i = 0; i < n; ++i) names.push_back(mean_name(i));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) names.push_back(covariance_name(i, j, n));
  return names;
}

std::string central_moment_name(const std::vector<std::size_t>& indices, std::size_t n) {
  std::string name = "M" + std::to_string(indices.size()) + "_";
  for (std::size_t k = 0; k < indices.size(); ++k)
    name += (k && separates_covariance_indices(n) ? "_" : "") + one_based(indices[k]);
  return name;
}

std::string central_moment_latex_name(const std::vector<std::size_t>& indices, std::size_t n) {
  std::string name = "\\mu_{";
  for (std::size_t k = 0; k < indices.size(); ++k)
    name += (k && separates_covariance_indices(n) ? "," : "") + one_based(indices[k]);
  return name + "}";
}

}  // namespace pfgen_support
