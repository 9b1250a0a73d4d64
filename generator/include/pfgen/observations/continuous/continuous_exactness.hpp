#pragma once
// When a Gaussian-closure filter of continuous observations dy = (A0 + A x) dt + B dW2 is exact
// (docs/theory.md §4): Kalman-Bucy, Basin, Perez & Skliar 2006 (A square and invertible, or the
// linear case) or Basin & Skliar (a partially measured split), or which of them failed.
#include "pfgen/derivation/exactness.hpp"

namespace pfgen {

ExactnessReport continuous_exactness(const Model& model, FilterKind kind);

}  // namespace pfgen
