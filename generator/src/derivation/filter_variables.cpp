#include "pfgen/derivation/filter_variables.hpp"

#include <algorithm>
#include <stdexcept>

#include "pfgen/model/model.hpp"
#include "pfgen_support/variable_names.hpp"

namespace pfgen {

namespace {

void append_ascending(std::size_t n, std::size_t order, std::vector<std::size_t>& prefix,
                      std::vector<std::vector<std::size_t>>& out) {
  if (prefix.size() == order) {
    out.push_back(prefix);
    return;
  }
  for (std::size_t i = prefix.empty() ? 0 : prefix.back(); i < n; ++i) {
    prefix.push_back(i);
    append_ascending(n, order, prefix, out);
    prefix.pop_back();
  }
}

}  // namespace

std::vector<std::vector<std::size_t>> ascending_indices(std::size_t n, std::size_t order) {
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::size_t> prefix;
  append_ascending(n, order, prefix, out);
  return out;
}

FilterVariables::FilterVariables(std::size_t n, bool delayed, std::size_t order)
    : n_(n), delayed_(delayed), order_(order), text_names_(filter_variable_names(n)) {
  if (order < 2 || (delayed && order > 2)) throw std::invalid_argument("FilterVariables: no such moment order");
  // The naming rule (P1_10 and P_{1,10} from n = 10 on) is pfgen_support's.
  for (std::size_t i = 0; i < n; ++i) latex_names_.push_back(pfgen_support::mean_latex_name(i));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      latex_names_.push_back(pfgen_support::covariance_latex_name(i, j, n));
      P_entries_.emplace_back(i, j);
    }
  }
  for (std::size_t r = 3; r <= order; ++r)
    for (auto& indices : ascending_indices(n, r)) moments_.push_back(std::move(indices));
  for (const auto& indices : moments_) {
    text_names_.push_back(pfgen_support::central_moment_name(indices, n));
    latex_names_.push_back(pfgen_support::central_moment_latex_name(indices, n));
  }
  if (delayed) {
    for (std::size_t i = 0; i < n; ++i) {
      text_names_.push_back("md" + std::to_string(i + 1));
      latex_names_.push_back(pfgen_support::mean_latex_name(i) + "(t-h)");
    }
    for (std::size_t i = 0; i < n; ++i) {
      text_names_.push_back("phi" + std::to_string(i + 1));
      latex_names_.push_back("\\Phi^*_{" + std::to_string(i + 1) + "}");
    }
    for (std::size_t i = 0; i < n; ++i) {
      text_names_.push_back("xs" + std::to_string(i + 1));
      latex_names_.push_back("x^*_{" + std::to_string(i + 1) + "}");
    }
  }
  for (const auto& name : text_names_) symbols_.push_back(GiNaC::symbol(name));
}

std::uint32_t FilterVariables::delayed_variable(std::size_t block, std::size_t i) const {
  if (!delayed_ || i >= n_) throw std::out_of_range("FilterVariables: no such delayed-filter variable");
  return static_cast<std::uint32_t>(count() + block * n_ + i);
}

std::uint32_t FilterVariables::higher_moment(std::vector<std::size_t> indices) const {
  std::sort(indices.begin(), indices.end());
  const auto it = std::lower_bound(moments_.begin(), moments_.end(), indices, [](const auto& a, const auto& b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
  });
  if (it == moments_.end() || *it != indices) throw std::out_of_range("FilterVariables: no such central moment");
  return static_cast<std::uint32_t>(first_higher_moment() + (it - moments_.begin()));
}

std::size_t FilterVariables::upper_index(std::size_t i, std::size_t j) const {
  if (i > j) std::swap(i, j);
  if (j >= n_) throw std::out_of_range("FilterVariables: index out of range");
  // Rows 0..i-1 hold n, n-1, ..., n-i+1 entries.
  return i * n_ - i * (i - 1) / 2 + (j - i);
}

std::uint32_t FilterVariables::P(std::size_t i, std::size_t j) const {
  return static_cast<std::uint32_t>(n_ + upper_index(i, j));
}

std::pair<std::size_t, std::size_t> FilterVariables::P_entry(std::uint32_t variable) const {
  return P_entries_.at(variable - n_);
}

}  // namespace pfgen
