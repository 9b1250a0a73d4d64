#pragma once
// How large a YAML document is with its aliases expanded, counted by yaml-cpp's event parser before
// any node is built. yaml-cpp shares an aliased node instead of copying it, but everything that
// walks the tree (the duplicate-key check, the loader) visits it once per reference, so nine levels
// of ten aliases each (a 687-byte "billion laughs") took 14 s to refuse and ten levels ran past 30 s.
// The count saturates, so it never overflows however deep the nesting.
#include <cstddef>
#include <cstdint>
#include <string>

namespace pfgen {

struct YamlAliasExpansion {
  bool exceeded = false;     // the expanded first document has more than the limit's nodes
  int line = 0, column = 0;  // 0-based: the alias that took the count past the limit
};

// At most this many nodes (scalars, collections, aliases counted as what they stand for) in a
// model file's document: a dense 20-state cubic model has a few thousand.
inline constexpr std::uint64_t kMaxYamlNodes = 1000000;

// The first document of `text` only (a second one is refused elsewhere); a text yaml-cpp cannot
// parse is left to the loader's own parse, which reports it.
YamlAliasExpansion expand_yaml_aliases(const std::string& text, std::uint64_t limit = kMaxYamlNodes);

}  // namespace pfgen
