#include "pfgen/algebra/monomial_keys.hpp"

#include <algorithm>
#include <array>

namespace pfgen {

// Monomial::operator<: the (variable, exponent) pairs compared
// lexicographically, a proper prefix first. Factor k is (v + 1) << 8 | e, an absent one 0.
bool map_order_key(const Monomial& m, MonomialKey& key) {
  const FactorList& factors = m.factors();
  if (factors.size() > 4) return false;
  std::uint64_t fields[4] = {0, 0, 0, 0};
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const auto [variable, exponent] = factors[k];
    if (variable >= (1u << 24) - 1 || exponent >= (1u << 8)) return false;
    fields[k] = (std::uint64_t{variable} + 1) << 8 | exponent;
  }
  key.high = fields[0] << 32 | fields[1];
  key.low = fields[2] << 32 | fields[3];
  return true;
}

// displays_before's order: total degree descending, then the factors compared in turn, a lower
// variable first (its exponent is larger than the other's 0), a larger exponent first, a longer
// list first. 16 bits of 0xffff - degree, then four factors of 28 bits, (v + 1) << 8 | (255 - e),
// an absent one all ones.
bool display_order_key(const Monomial& m, MonomialKey& key) {
  const FactorList& factors = m.factors();
  if (factors.size() > 4) return false;
  constexpr std::uint64_t kAbsent = (std::uint64_t{1} << 28) - 1;
  std::uint64_t fields[4] = {kAbsent, kAbsent, kAbsent, kAbsent};
  std::uint64_t degree = 0;
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const auto [variable, exponent] = factors[k];
    if (variable >= (1u << 20) - 2 || exponent >= (1u << 8)) return false;
    degree += exponent;
    fields[k] = (std::uint64_t{variable} + 1) << 8 | (255 - exponent);
  }
  // Bits 127..112: the inverted degree; 111..84, 83..56, 55..28, 27..0: the factors.
  key.high = (0xffff - degree) << 48 | fields[0] << 20 | fields[1] >> 8;
  key.low = fields[1] << 56 | fields[2] << 28 | fields[3];
  return true;
}

namespace {

constexpr std::size_t kDigits = 16;  // bytes of a 128-bit key, the least significant first

unsigned digit(const MonomialKey& key, std::size_t d) {
  return static_cast<unsigned>(((d < 8 ? key.low : key.high) >> (8 * (d % 8))) & 0xff);
}

}  // namespace

void sort_by_key(std::vector<KeyedIndex>& items) {
  // Short lists by comparisons (the index breaks ties, so this is as stable); long ones (a dense
  // cubic's dP sums: 17,000 products) by a stable least-significant-digit radix sort, one byte per
  // pass, where a byte that is the same in every key (most of them: few factors, small exponents)
  // costs no pass at all.
  if (items.size() < 256) {
    std::sort(items.begin(), items.end());
    return;
  }
  std::vector<std::array<std::uint32_t, 256>> counts(kDigits);
  for (auto& count : counts) count.fill(0);
  for (const KeyedIndex& item : items)
    for (std::size_t d = 0; d < kDigits; ++d) ++counts[d][digit(item.key, d)];
  std::vector<KeyedIndex> buffer(items.size());
  for (std::size_t d = 0; d < kDigits; ++d) {
    std::array<std::uint32_t, 256>& count = counts[d];
    if (count[digit(items.front().key, d)] == items.size()) continue;  // one value: no order to make
    std::uint32_t start = 0;
    for (std::uint32_t& c : count) {
      const std::uint32_t n = c;
      c = start;
      start += n;
    }
    for (const KeyedIndex& item : items) buffer[count[digit(item.key, d)]++] = item;
    items.swap(buffer);
  }
}

}  // namespace pfgen
