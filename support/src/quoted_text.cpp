#include "pfgen_support/quoted_text.hpp"

namespace pfgen_support {

std::string quoted(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return "'" + text + "'";
  std::size_t cut = limit;
  // Back to the start of a UTF-8 sequence: continuation bytes are 10xxxxxx.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return "'" + text.substr(0, cut) + "...' (" + std::to_string(text.size()) + " characters)";
}

}  // namespace pfgen_support
