#pragma once
// Numbers and vectors of numbers as their bytes, for what processes of one job send each other
// (run_codec, series_codec). A vector travels as its length and then its elements. The reader
// refuses bytes that end early or lengths that exceed what is left, before allocating them.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace pfgen_runtime::monte_carlo_detail {

class ByteWriter {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* bytes = reinterpret_cast<const char*>(&value);
    out.insert(out.end(), bytes, bytes + sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& values) {
    put_range(values.data(), values.size());
  }
  // values[0 .. count) as a vector of `count` elements.
  template <class T>
  void put_range(const T* values, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(static_cast<std::uint64_t>(count));
    const char* bytes = reinterpret_cast<const char*>(values);
    out.insert(out.end(), bytes, bytes + count * sizeof(T));
  }
  // A block's 8-byte tag, which names its layout and version.
  void put_magic(const char (&magic)[8]) {
    for (char c : magic) put(c);
  }
  std::vector<char> out;
};

class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <class T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
  }
  // A flag is one byte, 0 or 1: any other byte is a corrupt share, not a bool to load (which would
  // be undefined behaviour).
  void get(bool& value) {
    unsigned char byte = 0;
    get(byte);
    if (byte > 1) fail();
    value = byte == 1;
  }
  template <class T>
  void get(std::vector<T>& values) {
    std::size_t size = 0;
    const char* first = get_in_place<T>(size);  // its length checked before allocating it
    values.resize(size);
    if (size > 0) std::memcpy(values.data(), first, size * sizeof(T));
  }
  // A vector left where it is in the bytes: its elements' first byte (nullptr when it has none),
  // its length in `size`.
  template <class T>
  const char* get_in_place(std::size_t& size) {
    static_assert(std::is_trivially_copyable_v<T>);
    std::uint64_t length = 0;
    get(length);
    if (length > (bytes_.size() - at_) / sizeof(T)) fail();  // before anyone allocates a corrupt length
    size = static_cast<std::size_t>(length);
    const char* first = size > 0 ? bytes_.data() + at_ : nullptr;
    at_ += size * sizeof(T);
    return first;
  }
  // Reads the block's tag; fail() unless it is `magic`.
  void check_magic(const char (&magic)[8]) {
    for (char expected : magic) {
      char c = 0;
      get(c);
      if (c != expected) fail();
    }
  }
  bool done() const { return at_ == bytes_.size(); }
  [[noreturn]] static void fail() { throw std::runtime_error("monte carlo: a process's share of the runs is malformed"); }

 private:
  void need(std::size_t size) const {
    if (bytes_.size() - at_ < size) fail();
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace pfgen_runtime::monte_carlo_detail
