#pragma once
// The body of a generated sampled filter's predict(state, t, dt, params), one sub-step over
// [t, t + dt], as statements for every language. The module chooses the scheme with its
// functions: cd-euler's exact moments of one Euler step (m' = m + m_drift dt, P' = P + P_drift dt
// + Cov(f) dt^2, when the filter has euler_square()), else Heun's predictor-corrector on the
// prediction ODEs (second order in dt, as the continuous filters' step()). The sizes are the
// file's dimensions (n, state_size) and the functions the file's (derivatives, euler_square), each
// spelt by the backend's emitter.
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

ir::Block predict_statements(bool euler);

// The body of advance(state, t, y, params), from one sample time t to the next: `substeps`
// predictions of period() / substeps each, then update() with the sample y taken at t + period().
ir::Block advance_statements();

}  // namespace pfgen::codegen
