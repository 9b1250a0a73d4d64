#pragma once
// The scalar type generated code computes in: float, double, or (C++ only) a template parameter.
#include <string>

namespace pfgen::codegen {

enum class ScalarMode { Template, Float, Double };

std::string scalar_mode_name(ScalarMode mode);  // "template", "float", "double"

}  // namespace pfgen::codegen
