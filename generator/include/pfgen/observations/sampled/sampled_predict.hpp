#pragma once
// The body of a generated sampled filter's predict(state, t, dt, params), one sub-step over
// [t, t + dt], as statements for every language. The module chooses the scheme with its
// functions: cd-euler's exact moments of one Euler step (m' = m + m_drift dt, P' = P + P_drift dt
// + Cov(f) dt^2, when the filter has euler_square()), else Heun's predictor-corrector on the
// prediction ODEs (second order in dt, as the continuous filters' step()).
#include <string>

#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// What the step reads besides its arguments and its local arrays, as the file names and spells
// them: the sizes (C++: `n`; C: `<prefix>_n`; Rust: `STATES`), the scalar 2 (C++: `Scalar(2)`),
// and the file's functions derivatives() and euler_square() (C: `<prefix>_derivatives`).
struct PredictNames {
  ir::Expr n, state_size, two;
  std::string derivatives, euler_square;
};

ir::Block predict_statements(bool euler, const PredictNames& names);

}  // namespace pfgen::codegen
