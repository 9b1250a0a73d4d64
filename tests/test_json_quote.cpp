// JSON strings are UTF-8 (RFC 8259): json_quote keeps well-formed UTF-8 as it is, escapes what JSON
// requires, and writes U+FFFD for a byte that is not UTF-8, which a file's path can hold and which
// made `fit -o FILE.json` write a file no JSON reader takes.
#include <catch2/catch.hpp>

#include <string>

#include "pfgen/printing/json_writer.hpp"

using pfgen::json_quote;

TEST_CASE("json_quote: UTF-8 kept, control characters escaped, bytes that are not UTF-8 replaced", "[unit]") {
  CHECK(json_quote("plain") == "\"plain\"");
  CHECK(json_quote("a\"b\\c\n\t\x01") == "\"a\\\"b\\\\c\\n\\t\\u0001\"");
  // Two-, three- and four-byte sequences: alpha, the euro sign, an emoji.
  CHECK(json_quote("\xCE\xB1 \xE2\x82\xAC \xF0\x9F\x98\x80") == "\"\xCE\xB1 \xE2\x82\xAC \xF0\x9F\x98\x80\"");
  // A lone byte, a stray continuation, a truncated sequence, an overlong form, a surrogate, above U+10FFFF.
  CHECK(json_quote("x\xFFy") == "\"x\\ufffdy\"");
  CHECK(json_quote("\x80") == "\"\\ufffd\"");
  CHECK(json_quote("\xE2\x82") == "\"\\ufffd\\ufffd\"");
  CHECK(json_quote("\xC0\xAF") == "\"\\ufffd\\ufffd\"");
  CHECK(json_quote("\xED\xA0\x80") == "\"\\ufffd\\ufffd\\ufffd\"");
  CHECK(json_quote("\xF4\x90\x80\x80") == "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");
}
