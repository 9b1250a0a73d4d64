#pragma once
// The filter's own variables: m_1..m_n, then the upper triangle of P row by
// row, P_11, P_12, ..., P_1n, P_22, ... The numbering is shared by the
// derivation (Polynomial variable indices), every printer and the generated
// code's state layout. m_i has index i, the same index as state x_i, so an
// x-polynomial read as an m-polynomial needs no renumbering (f(m) in the EKF).
// Text names come from the model room's filter_variable_names(), which user
// filters (Model::user_filters) are written in.
#include <cstdint>
#include <string>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen {

class FilterVariables {
 public:
  explicit FilterVariables(std::size_t n = 0);

  std::size_t n() const { return n_; }
  std::size_t count() const { return n_ + n_ * (n_ + 1) / 2; }
  std::uint32_t m(std::size_t i) const { return static_cast<std::uint32_t>(i); }
  // P(i,j) and P(j,i) are the same variable.
  std::uint32_t P(std::size_t i, std::size_t j) const;
  std::size_t upper_index(std::size_t i, std::size_t j) const;  // position in the upper triangle

  bool is_mean(std::uint32_t variable) const { return variable < n_; }
  // (row, column) of a P variable, 0-based, row <= column.
  std::pair<std::size_t, std::size_t> P_entry(std::uint32_t variable) const;

  const std::string& text_name(std::uint32_t variable) const { return text_names_.at(variable); }
  const std::string& latex_name(std::uint32_t variable) const { return latex_names_.at(variable); }
  // Symbols named as in text output, for conversions to GiNaC expressions.
  const std::vector<GiNaC::ex>& symbols() const { return symbols_; }

 private:
  std::size_t n_;
  std::vector<std::string> text_names_;
  std::vector<std::string> latex_names_;
  std::vector<GiNaC::ex> symbols_;
  std::vector<std::pair<std::size_t, std::size_t>> P_entries_;
};

}  // namespace pfgen
