#pragma once
// What bench_codegen knows of one case: the generated derivatives() with and
// without CSE (each compiled in its own translation unit, called through a
// pointer like any out-of-line function), and derivatives()'s op counts from
// `pfgen codegen --stats`; and the model's f and g typed as plain C++ for the
// quadrature baseline. The generated wrappers and the case list are written by
// benchmarks/CMakeLists.txt into the build directory.
#include <cstddef>
#include <string>

namespace pfgen_bench {

using DerivativesFunction = void (*)(const double* state, double* out);
using PolynomialFunction = void (*)(const double* x, double* out);

struct GeneratedCode {
  DerivativesFunction derivatives;
  std::size_t n;
  std::size_t state_size;
};

struct BenchCase {
  std::string label;       // "paper 000", "dense cubic n=4", ...
  std::string model_path;  // the model file the code was generated from
  GeneratedCode cse;
  GeneratedCode no_cse;
  std::size_t ops_naive;   // derivatives(): every output as its own expression tree
  std::size_t ops_cse;     // derivatives(): after common-subexpression elimination
  PolynomialFunction typed_f;  // the model's f and g typed as plain C++ (model_to_cpp), for the quadrature
  PolynomialFunction typed_g;
};

}  // namespace pfgen_bench
