#pragma once
// std::cerr sent elsewhere while one of these lives, and given back after: to nowhere (nullptr:
// another MPI process's notes, which one process says for the job) or to a buffer (the API keeps a
// simulation's notes for its caller). Giving it back clears the bad bit a write to nowhere set.
#include <iostream>

namespace pfgen::cli {

class RedirectedStderr {
 public:
  explicit RedirectedStderr(std::streambuf* target) : saved_(std::cerr.rdbuf(target)) {}
  ~RedirectedStderr() { std::cerr.rdbuf(saved_); }
  RedirectedStderr(const RedirectedStderr&) = delete;
  RedirectedStderr& operator=(const RedirectedStderr&) = delete;

 private:
  std::streambuf* saved_;
};

}  // namespace pfgen::cli
