#pragma once
// A 64-bit FNV-1a hash over a sequence of fields, each preceded by its length so that
// ("ab", "c") and ("a", "bc") differ. Not cryptographic: it names cache entries (the plugin
// cache compares the stored source before trusting an entry) and tells apart the shortened C names
// of split functions' parts.
#include <cstdint>
#include <string>

namespace pfgen_support {

class ContentHash {
 public:
  ContentHash& add(const std::string& field);
  std::uint64_t value() const { return state_; }
  std::string hex() const;  // 16 lower-case hex digits

 private:
  void bytes(const void* data, std::size_t size);
  std::uint64_t state_ = 14695981039346656037ull;  // the FNV-1a 64 offset basis
};

}  // namespace pfgen_support
