#pragma once
// The dense cubic system of size n (dense_cubic_system.hpp) as a pfgen Model named
// "dense_cubic_<n>", with exact rational coefficients: what bench_derive derives and
// test_codegen_ops generates code for.
#include <cstddef>

#include "pfgen/model/model.hpp"

namespace pfgen_test {

pfgen::Model dense_cubic_model(std::size_t n);

}  // namespace pfgen_test
