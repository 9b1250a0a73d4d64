#include "pfgen/model/yaml_documents.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <sstream>

namespace pfgen {
namespace {

// Records where each document starts, and where its root node starts (what YAML::LoadAll's
// node's Mark() gives, so messages point where they did); every other event is ignored.
class DocumentStarts : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override {
    previous_ = last_;
    last_ = root_ = mark;
    awaiting_root_ = true;
    ++count_;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    node(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

  std::size_t count() const { return count_; }
  const YAML::Mark& last() const { return last_; }
  const YAML::Mark& root() const { return root_; }  // of the last document
  // Two documents in a row at one position: the parser made no progress.
  bool stuck() const { return count_ >= 2 && previous_.pos == last_.pos; }

 private:
  void node(const YAML::Mark& mark) {
    if (awaiting_root_) root_ = mark;
    awaiting_root_ = false;
  }
  std::size_t count_ = 0;
  bool awaiting_root_ = false;
  YAML::Mark previous_ = YAML::Mark::null_mark(), last_ = YAML::Mark::null_mark(), root_ = YAML::Mark::null_mark();
};

}  // namespace

YamlDocuments count_yaml_documents(const std::string& text, std::size_t cap) {
  YamlDocuments out;
  std::istringstream input(text);
  DocumentStarts starts;
  YAML::Mark second = YAML::Mark::null_mark();
  try {
    YAML::Parser parser(input);
    while (starts.count() < cap && parser.HandleNextDocument(starts)) {
      if (starts.stuck()) {
        out.stuck = true;
        second = starts.last();
        break;
      }
      if (starts.count() == 2) second = starts.root();
    }
  } catch (const YAML::Exception&) {
    out.parse_error = true;
  }
  out.count = starts.count();
  out.line = second.line;
  out.column = second.column;
  return out;
}

}  // namespace pfgen
