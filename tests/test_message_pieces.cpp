// A block in pieces cut into messages of bounded size (generator/cli/message_pieces), as the MPI
// exchange sends what the Monte Carlo runtime hands it: each message must hold exactly the
// block's bytes [k limit, (k + 1) limit), which the receiving rank posts, and nothing else.
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "message_pieces.hpp"

using pfgen::cli::in_messages;
using pfgen_runtime::BytePiece;
using pfgen_runtime::PiecedBlock;

namespace {

// The block's pieces over `text`, of the given sizes in order (a size 0 is an empty piece).
PiecedBlock pieces_of(const std::string& text, const std::vector<std::size_t>& sizes) {
  PiecedBlock block;
  std::size_t at = 0;
  for (std::size_t size : sizes) {
    block.push_back({text.data() + at, size});
    at += size;
  }
  REQUIRE(at == text.size());
  return block;
}

std::string bytes_of(const PiecedBlock& block) {
  std::string bytes;
  for (const BytePiece& piece : block) bytes.append(piece.data, piece.size);
  return bytes;
}

}  // namespace

TEST_CASE("a block in pieces is cut into messages of the receiver's sizes", "[unit][mpi_messages]") {
  const std::string text = "abcdefghijklmnopqrstuvwxyz0123456789";  // 36 bytes
  const std::vector<std::vector<std::size_t>> layouts = {
      {36}, {1, 35}, {0, 10, 0, 0, 26, 0}, {7, 7, 7, 7, 8}, {5, 3, 9, 1, 1, 17}, {1, 1, 1, 1, 1, 1, 1, 1, 28}};
  for (const std::vector<std::size_t>& sizes : layouts)
    for (std::size_t limit : {1, 2, 3, 5, 7, 8, 12, 35, 36, 37, 1000}) {
      CAPTURE(sizes, limit);
      const std::vector<PiecedBlock> messages = in_messages(pieces_of(text, sizes), limit);
      REQUIRE(messages.size() == (text.size() + limit - 1) / limit);
      for (std::size_t k = 0; k < messages.size(); ++k) {
        CHECK(bytes_of(messages[k]) == text.substr(k * limit, limit));
        for (const BytePiece& piece : messages[k]) CHECK(piece.size > 0);
        CHECK(messages[k].size() <= limit);
      }
    }
}

TEST_CASE("an empty block is no message, and a message holds at least a byte", "[unit][mpi_messages]") {
  const std::string text;
  CHECK(in_messages({}, 8).empty());
  CHECK(in_messages(pieces_of(text, {0, 0}), 8).empty());
  CHECK_THROWS_AS(in_messages(pieces_of("ab", {2}), 0), std::logic_error);
}
