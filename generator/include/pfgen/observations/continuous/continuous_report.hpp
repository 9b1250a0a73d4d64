#pragma once
// What the continuous module's report part shares with the delayed one, whose observation has the
// same matrices A0, A, B.
#include <optional>
#include <string>

#include <ginac/ginac.h>

#include "pfgen/model/observation_model.hpp"

namespace pfgen {

// A0, A and B as the standalone document's model lines: "A_0 &= [...], \quad A = [...], \quad B = [...]"
// when that fits a line, else each matrix in lines of its own; a delayed observation's h after them.
std::string rate_matrices_latex(const AffineRate& observation, const std::optional<GiNaC::numeric>& delay);

}  // namespace pfgen
