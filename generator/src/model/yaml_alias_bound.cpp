#include "pfgen/model/yaml_alias_bound.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <sstream>
#include <unordered_map>
#include <vector>

namespace pfgen {
namespace {

// Thrown out of the parser at the first alias that passes the limit: nothing after it is read.
struct LimitPassed {
  YAML::Mark mark;
};

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
  return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

// Each collection's expanded size is 1 + its children's; an anchor remembers its node's size and
// an alias adds it again.
class ExpandedSize : public YAML::EventHandler {
 public:
  explicit ExpandedSize(std::uint64_t limit) : limit_(limit) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor, 1); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, const std::string&) override {
    leaf(mark, anchor, 1);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto found = sizes_.find(anchor);
    leaf(mark, 0, found == sizes_.end() ? 1 : found->second);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    open(mark, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Collection {
    YAML::anchor_t anchor;
    std::uint64_t size;
  };

  // The total counts every node once, an alias as the whole node it stands for: a collection
  // when it opens, a leaf or an alias when it is read.
  void open(const YAML::Mark& mark, YAML::anchor_t anchor) {
    open_.push_back({anchor, 1});
    count(mark, 1);
  }
  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor, std::uint64_t size) {
    if (anchor) sizes_[anchor] = size;
    if (!open_.empty()) open_.back().size = saturating_add(open_.back().size, size);
    count(mark, size);
  }
  void close() {
    const Collection done = open_.back();
    open_.pop_back();
    if (done.anchor) sizes_[done.anchor] = done.size;
    if (!open_.empty()) open_.back().size = saturating_add(open_.back().size, done.size);
  }
  void count(const YAML::Mark& mark, std::uint64_t size) {
    total_ = saturating_add(total_, size);
    if (total_ > limit_) throw LimitPassed{mark};
  }

  std::uint64_t limit_;
  std::uint64_t total_ = 0;
  std::vector<Collection> open_;
  std::unordered_map<YAML::anchor_t, std::uint64_t> sizes_;
};

}  // namespace

YamlAliasExpansion expand_yaml_aliases(const std::string& text, std::uint64_t limit) {
  YamlAliasExpansion out;
  std::istringstream input(text);
  ExpandedSize counter(limit);
  try {
    YAML::Parser parser(input);
    parser.HandleNextDocument(counter);
  } catch (const LimitPassed& passed) {
    out.exceeded = true;
    out.line = passed.mark.line;
    out.column = passed.mark.column;
  } catch (const YAML::Exception&) {
  }
  return out;
}

}  // namespace pfgen
