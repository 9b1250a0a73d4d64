#include "pfgen/toolchain/process.hpp"

namespace pfgen::toolchain {

ProcessResult run_program(const std::vector<std::string>& argv) {
  try {
    return pfgen_support::run_program(argv);
  } catch (const pfgen_support::ProcessError& e) {
    throw ToolchainError(e.what());
  } catch (const std::invalid_argument& e) {  // an empty argv
    throw ToolchainError(e.what());
  }
}

}  // namespace pfgen::toolchain
