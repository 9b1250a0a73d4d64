#pragma once
// What code generation refuses: a constant outside the scalar's range, a filter beyond the
// budgets, a name the output language cannot declare, a delay off the grid.
#include "pfgen_support/error.hpp"

namespace pfgen::codegen {

class CodegenError : public pfgen_support::Error {
 public:
  using pfgen_support::Error::Error;
};

}  // namespace pfgen::codegen
