#pragma once
// The banner at the top of a generated C or C++ filter file: where it came from, how to
// regenerate it, whether its equations are the model's own, the scalar, CSE, and the operation
// counts.
#include <string>

#include "pfgen/codegen/filter_codegen.hpp"

namespace pfgen::codegen {

// `regenerate`: the command that writes the file ("pfgen codegen"); `extra`: lines (each ending
// in a newline) after the first.
std::string filter_banner(const Model& model, const FilterEquations& eq, const CodegenOptions& options,
                          const GeneratedFilter& result, const std::string& regenerate, const std::string& extra = "");

}  // namespace pfgen::codegen
