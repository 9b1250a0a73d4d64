#pragma once
// The filter's own variables: m_1..m_n, then the upper triangle of P row by
// row, P_11, P_12, ..., P_1n, P_22, ... The numbering is shared by the
// derivation (Polynomial variable indices), every printer and the generated
// code's state layout. m_i has index i, the same index as state x_i, so an
// x-polynomial read as an m-polynomial needs no renumbering (f(m) in the EKF).
// Text names come from the model room's filter_variable_names(), which user
// filters (Model::user_filters) are written in.
// A filter for delayed observations (docs/theory.md §2.6) has three more blocks after P, which
// are not part of count(): md_i = m_i(t - h), phi_i = Phi*_ii(t - h, t) (inputs the filter reads
// from its history) and xs_i = x*_i, the noise-free solution the Phi* kinds integrate beside m, P.
// A moment filter of order k >= 3 (the closure kinds, docs/theory.md §2.10) carries after P the central
// moments of orders 3..k, E[(x-m)_i (x-m)_j (x-m)_l] for i <= j <= l (M3_ijl), then those of order 4
// (M4_ijlq), each order in lexicographic order of its ascending indices; they are part of count().
#include <cstdint>
#include <string>
#include <vector>

#include <ginac/ginac.h>

namespace pfgen {

// Every ascending list of `order` indices below n (i <= j <= ...), in lexicographic order: the higher moments'
// indices at each order, and a sampled moment filter's joint moments'.
std::vector<std::vector<std::size_t>> ascending_indices(std::size_t n, std::size_t order);

class FilterVariables {
 public:
  explicit FilterVariables(std::size_t n = 0, bool delayed = false, std::size_t order = 2);

  std::size_t n() const { return n_; }
  // The highest order of central moment carried: 2 (m and P) but for a moment filter.
  std::size_t order() const { return order_; }
  std::size_t count() const { return n_ + n_ * (n_ + 1) / 2 + moments_.size(); }
  std::uint32_t m(std::size_t i) const { return static_cast<std::uint32_t>(i); }
  // P(i,j) and P(j,i) are the same variable.
  std::uint32_t P(std::size_t i, std::size_t j) const;
  std::size_t upper_index(std::size_t i, std::size_t j) const;  // position in the upper triangle

  bool is_mean(std::uint32_t variable) const { return variable < n_; }

  // The central moments of order >= 3, in the state's order after P, each as its ascending indices.
  const std::vector<std::vector<std::size_t>>& higher_moments() const { return moments_; }
  std::uint32_t first_higher_moment() const { return static_cast<std::uint32_t>(n_ + n_ * (n_ + 1) / 2); }
  // The variable of the central moment with these indices (any order; 3..order() of them).
  std::uint32_t higher_moment(std::vector<std::size_t> indices) const;

  bool delayed() const { return delayed_; }
  std::uint32_t m_delayed(std::size_t i) const { return delayed_variable(0, i); }  // m_i(t - h)
  std::uint32_t phi(std::size_t i) const { return delayed_variable(1, i); }        // Phi*_ii(t - h, t)
  std::uint32_t x_star(std::size_t i) const { return delayed_variable(2, i); }     // x*_i(t)
  // Every variable a polynomial of this filter may hold: count(), or 4n more when delayed.
  std::size_t all_count() const { return count() + (delayed_ ? 3 * n_ : 0); }
  // (row, column) of a P variable, 0-based, row <= column.
  std::pair<std::size_t, std::size_t> P_entry(std::uint32_t variable) const;

  const std::string& text_name(std::uint32_t variable) const { return text_names_.at(variable); }
  const std::string& latex_name(std::uint32_t variable) const { return latex_names_.at(variable); }
  // Symbols named as in text output, for conversions to GiNaC expressions.
  const std::vector<GiNaC::ex>& symbols() const { return symbols_; }

 private:
  std::uint32_t delayed_variable(std::size_t block, std::size_t i) const;
  std::size_t n_;
  bool delayed_ = false;
  std::size_t order_ = 2;
  std::vector<std::vector<std::size_t>> moments_;
  std::vector<std::string> text_names_;
  std::vector<std::string> latex_names_;
  std::vector<GiNaC::ex> symbols_;
  std::vector<std::pair<std::size_t, std::size_t>> P_entries_;
};

}  // namespace pfgen
