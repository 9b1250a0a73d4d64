#pragma once
// Monomials as 128-bit integers, for sorting millions of terms (Polynomial::sum_of, the printers'
// display order) by integer comparisons and radix passes instead of walking factor lists.
#include <cstdint>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"

namespace pfgen {

// A monomial as a 128-bit integer whose order is one of the two monomial orders below. Up to four
// factors, the first in the highest bits; a monomial with more factors, or whose variable or
// exponent does not fit, has no key (the callers then sort by the factor lists).
struct MonomialKey {
  std::uint64_t high = 0;
  std::uint64_t low = 0;
  bool operator==(const MonomialKey& other) const { return high == other.high && low == other.low; }
  bool operator<(const MonomialKey& other) const { return high != other.high ? high < other.high : low < other.low; }
};

struct KeyedIndex {
  MonomialKey key;
  std::uint32_t index;  // position among the terms being sorted; breaks ties, so the sort is stable
  bool zero = false;    // sum_of: the term's coefficient is zero
  bool operator<(const KeyedIndex& other) const { return key < other.key || (key == other.key && index < other.index); }
};

// Monomial::operator<: the (variable, exponent) pairs compared lexicographically, a proper prefix
// first. False when m has no key.
bool map_order_key(const Monomial& m, MonomialKey& key);

// displays_before's order: total degree descending, then the factors compared in turn, a lower
// variable first, a larger exponent first. False when m has no key.
bool display_order_key(const Monomial& m, MonomialKey& key);

// Sorts by key; equal keys keep their order (so items made in index order end up sorted by
// (key, index)).
void sort_by_key(std::vector<KeyedIndex>& items);

}  // namespace pfgen
