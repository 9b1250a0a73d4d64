#pragma once
// A block of bytes in pieces (pfgen_runtime::PiecedBlock, what the Monte Carlo exchange hands over)
// cut into messages of a bounded size, for a transport whose counts are ints (MPI's). Free of MPI
// itself, so that the cutting is tested without it.
#include <cstddef>
#include <vector>

#include "pfgen_runtime/monte_carlo.hpp"

namespace pfgen::cli {

// The pieces of each message, in order: message k holds the block's bytes [k limit, (k + 1) limit)
// (the last one the rest), as a receiver that knows only the block's size posts them. A piece
// that runs over a message's end is cut in two; empty pieces are left out, so no message has more
// pieces than bytes. No messages for an empty block. `limit` must be at least 1.
std::vector<pfgen_runtime::PiecedBlock> in_messages(const pfgen_runtime::PiecedBlock& block, std::size_t limit);

}  // namespace pfgen::cli
