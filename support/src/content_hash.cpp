#include "pfgen_support/content_hash.hpp"

#include <cstdio>

namespace pfgen_support {

void ContentHash::bytes(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t k = 0; k < size; ++k) {
    state_ ^= p[k];
    state_ *= 1099511628211ull;  // the FNV-1a 64 prime
  }
}

ContentHash& ContentHash::add(const std::string& field) {
  // The length as 8 little-endian bytes, whatever the host's byte order.
  unsigned char length[8];
  std::uint64_t size = field.size();
  for (unsigned char& b : length) {
    b = static_cast<unsigned char>(size & 0xff);
    size >>= 8;
  }
  bytes(length, sizeof length);
  bytes(field.data(), field.size());
  return *this;
}

std::string ContentHash::hex() const {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(state_));
  return buffer;
}

}  // namespace pfgen_support
