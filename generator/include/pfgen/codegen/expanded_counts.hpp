#pragma once
// The expanded form of derivatives() counted without building its graph. derivatives() keeps the
// form with the fewest operations after sharing, and always reports the expanded equations'
// count without sharing; at dense cubic n = 20 the expanded graph is six million nodes, most of
// code generation's time and memory, built only to be counted and dropped. Where every
// coefficient of the expanded outputs is a nonzero number, both figures it is needed for come
// from the polynomials instead: its count without sharing exactly, and a lower bound of its count
// with sharing, which says when it cannot be the form kept.
#include <cstddef>
#include <functional>
#include <optional>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/derivation/filter_equations.hpp"

namespace pfgen::codegen {

// The outputs of derivatives()' expanded form in their order (m's drift, P's upper triangle row
// by row, a delayed filter's x* drift), one at a time, as the graph takes them.
void for_each_expanded_output(const FilterEquations& eq, const std::function<void(const Polynomial&)>& visit);

struct ExpandedCounts {
  OpCounts naive;                    // = tree_counts of the expanded graph's roots
  std::size_t shared_lower_bound = 0;  // <= shared_counts(...).total() of that graph
};

// The counts of the expanded form as GraphBuilder::polynomial builds each output (SignedSum over
// the terms in display order, each |c| * monomial). Empty where a coefficient is not a nonzero
// number (a parameter, a definition), whose operations only the graph counts.
std::optional<ExpandedCounts> expanded_counts(const FilterEquations& eq);

}  // namespace pfgen::codegen
