#include "pfgen/model/text_characters.hpp"

#include <cstdio>

namespace pfgen {

std::optional<std::string> first_non_ascii(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto lead = static_cast<unsigned char>(text[i]);
    if (lead < 0x80) continue;
    // The sequence's length from its lead byte, then its continuation bytes 10xxxxxx.
    const std::size_t length = lead >= 0xF0 && lead < 0xF5 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC2 && lead < 0xE0 ? 2 : 0;
    unsigned long code = length == 4 ? lead & 0x07u : length == 3 ? lead & 0x0Fu : lead & 0x1Fu;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0u) == 0x80u;
      code = (code << 6) | (next & 0x3Fu);
    }
    char buffer[64];
    if (!valid || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
      std::snprintf(buffer, sizeof buffer, "the byte 0x%02X, which is not UTF-8", lead);
      return std::string(buffer);
    }
    std::snprintf(buffer, sizeof buffer, " (U+%04lX)", code);
    return "the character '" + text.substr(i, length) + "'" + buffer;
  }
  return std::nullopt;
}

}  // namespace pfgen
