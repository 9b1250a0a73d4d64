#include "pfgen_runtime/filter_stepping.hpp"

#include <stdexcept>

#include "pfgen_runtime/guards.hpp"

namespace pfgen_runtime {

FilterStepper::FilterStepper(std::size_t n, std::size_t p, const FilterStepControl& control, std::size_t extra_capacity)
    : n_(n), p_(p), size_(filter_state_size(n)), capacity_(filter_state_size(n) + extra_capacity), control_(control) {
  if (control.max_depth < 0 || !(control.tolerance > 0) || !(control.floor >= 0))
    throw std::invalid_argument("filter step control: need max_depth >= 0, tolerance > 0, floor >= 0");
  const auto levels = static_cast<std::size_t>(control.max_depth) + 1;
  saved_.assign(levels * capacity_, 0.0);
  half_dy_.assign(levels * p_, 0.0);
  probe_.assign(capacity_, 0.0);
  zero_dy_.assign(p_, 0.0);
}

}  // namespace pfgen_runtime
