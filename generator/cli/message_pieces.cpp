#include "message_pieces.hpp"

#include <algorithm>
#include <stdexcept>

namespace pfgen::cli {

std::vector<pfgen_runtime::PiecedBlock> in_messages(const pfgen_runtime::PiecedBlock& block, std::size_t limit) {
  if (limit == 0) throw std::logic_error("in_messages: a message must hold at least one byte");
  std::vector<pfgen_runtime::PiecedBlock> messages;
  std::size_t room = 0;  // bytes the last message can still take
  for (const pfgen_runtime::BytePiece& piece : block) {
    for (std::size_t at = 0; at < piece.size;) {
      if (room == 0) {
        messages.emplace_back();
        room = limit;
      }
      const std::size_t size = std::min(room, piece.size - at);
      messages.back().push_back({piece.data + at, size});
      at += size;
      room -= size;
    }
  }
  return messages;
}

}  // namespace pfgen::cli
