// What the firmware's start-up code (startup.cpp) tells main about the board.
#pragma once

#include <cstdint>

namespace pfgen_embedded::board {

// Bytes reserved for the stack by link.ld.
std::uint32_t stack_reserved_bytes();
// Bytes of that stack written since reset (it is painted with a pattern at reset).
std::uint32_t stack_peak_bytes();

}  // namespace pfgen_embedded::board
