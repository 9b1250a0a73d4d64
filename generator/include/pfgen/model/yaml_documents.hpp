#pragma once
// How many YAML documents a text holds, counted by yaml-cpp's event parser without building any
// node. yaml-cpp 0.7's YAML::LoadAll never returns on some malformed text: its parser reports
// document after document at the same place, and LoadAll keeps each one, until memory runs out
// (a fuzz finding, tests/data/bad/fuzz_endless_documents.yaml). Counting events instead, and
// stopping where the parser no longer advances or at a cap, always ends.
#include <cstddef>
#include <string>

namespace pfgen {

struct YamlDocuments {
  std::size_t count = 0;     // documents seen, at most the cap
  bool stuck = false;        // a document started where the previous one did: the text is not valid YAML there
  bool parse_error = false;  // yaml-cpp threw (the caller's own parse reports it)
  int line = 0, column = 0;  // 0-based: the second document's root node, or where the parser stuck
};

YamlDocuments count_yaml_documents(const std::string& text, std::size_t cap = 1000);

}  // namespace pfgen
