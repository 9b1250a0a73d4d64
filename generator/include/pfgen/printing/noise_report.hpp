#pragma once
// What a report says of a model with Stratonovich noise (Model::noise): the drift as written, the
// Ito correction c and the Ito drift f + c that the equations below it are derived from. An Ito
// model gets nothing, so its reports do not change by a byte.
#include <string>

#include "pfgen/model/model.hpp"
#include "pfgen/printing/json_writer.hpp"

namespace pfgen {

// Text: "noise: stratonovich ...\n" and one line per state; empty for Ito noise.
std::string noise_text(const Model& model);
// LaTeX: a paragraph and an align* with f (as written), c and f + c; empty for Ito noise.
std::string noise_latex(const Model& model);
// JSON: adds "noise": {"calculus", "drift_as_written", "correction", "ito_drift"} for Stratonovich.
void add_noise_json(const Model& model, Json& out);

}  // namespace pfgen
