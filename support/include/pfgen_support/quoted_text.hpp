#pragma once
// A user's text quoted in a one-line message, cut to a length a terminal line can hold: an unknown
// symbol in a 99 kB expression echoed the whole expression, and an option's 10,000-digit value its
// every digit. The cut text ends in "..." and says how long the whole was.
#include <cstddef>
#include <string>

namespace pfgen_support {

inline constexpr std::size_t kQuotedTextLimit = 200;

// 'text', or 'the first 200 characters...' (N characters) when it is longer. The cut never splits a
// UTF-8 sequence.
std::string quoted(const std::string& text, std::size_t limit = kQuotedTextLimit);

}  // namespace pfgen_support
