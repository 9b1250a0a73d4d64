#pragma once
// Paths the tests need, fixed by CMake at configure time.
#include <string>

namespace pfgen_test {
inline std::string pfgen_executable() { return PFGEN_EXECUTABLE; }
inline std::string source_dir() { return PFGEN_SOURCE_DIR; }
inline std::string test_data_dir() { return PFGEN_TEST_DATA_DIR; }
inline std::string example(const std::string& file) { return source_dir() + "/examples/" + file; }
}  // namespace pfgen_test
