#pragma once
// Model text is ASCII: names are C++ identifiers and expressions use ASCII operators. A character
// beyond ASCII is named whole in an error message (GiNaC's parser reported one byte of it,
// which printed as a broken UTF-8 sequence).
#include <optional>
#include <string>

namespace pfgen {

// "the character 'α' (U+03B1)", or "the byte 0xCE, which is not UTF-8", for the first byte of
// `text` beyond ASCII; nullopt when `text` is ASCII.
std::optional<std::string> first_non_ascii(const std::string& text);

}  // namespace pfgen
