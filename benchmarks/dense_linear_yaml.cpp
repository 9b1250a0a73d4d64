// Writes the dense linear benchmark model of size n (tests/support/dense_linear_system.hpp: dense
// stable A, dense constant G, 3 observations) as a pfgen model file, for bench_handwritten. Run at
// build time (benchmarks/CMakeLists.txt), so the model file and the hand-written filter read the
// same numbers from one definition:
//   dense_linear_yaml N OUTPUT
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "support/dense_linear_system.hpp"  // tests/support, shared with the agreement test

int main(int argc, char** argv) {
  if (argc != 3 || std::atoi(argv[1]) < 1) {
    std::fprintf(stderr, "usage: dense_linear_yaml N OUTPUT\n");
    return 2;
  }
  const std::string text =
      pfgen_test::dense_linear_yaml(pfgen_test::dense_linear_system(static_cast<std::size_t>(std::atoi(argv[1]))));
  std::ofstream out(argv[2], std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) {
    std::fprintf(stderr, "dense_linear_yaml: cannot write %s\n", argv[2]);
    return 1;
  }
  return 0;
}
