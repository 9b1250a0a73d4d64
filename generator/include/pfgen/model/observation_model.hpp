#pragma once
// How the states are observed. The model file's `observation:` section chooses the kind when it
// is read (kinds/observation_kinds.hpp lists them); the rooms above reach what the kind means to
// them through its module (observations/<kind>/, found by kind()), which reads the alternative it
// is for, instead of assuming one observation equation. A new kind is one more alternative of the
// variant below: continuous, dy = (A0 + A x) dt + B dW2, or sampled, y_k = C0 + C x(t_k) + Uv v_k
// at t_k = k T, or delayed, dy = (A0 + A x(t - h)) dt + B dW2, or polynomial, dy = h(x, t) dt + B dW2.
#include <cstddef>
#include <optional>
#include <variant>
#include <vector>

#include "pfgen/kinds/observation_kinds.hpp"
#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

// Rows polynomial in the states (a polynomial observation's h, a sampled c) written C0 + C x:
// the constant of each row and its coefficient of each state, or nothing when a row has degree > 1.
struct AffineRows {
  ExVector constant;  // one per row
  ExMatrix linear;    // rows x states
};
std::optional<AffineRows> affine_rows(const ExVector& rows, const std::vector<GiNaC::symbol>& states);

struct ContinuousObservation {
  ExVector A0;  // p entries, independent of the states
  ExMatrix A;   // p x n
  ExMatrix B;   // p x r, with B B^T positive definite
};

// Samples every `period` time units. The sampled filter kinds predict between samples in
// `substeps` equal sub-steps of period / substeps (for cd-euler the sub-step is part of the
// filter's definition: 1 sub-step is the discrete-discrete filter). Without them each filter takes
// as many as its prediction's rate at the prior needs (observations/sampled/substep_choice.hpp).
struct SampledObservation {
  GiNaC::numeric period;      // T > 0, exact
  ExVector C0;                // r entries, independent of the states (zeros when not given)
  ExMatrix C;                 // r x n
  ExMatrix Uv;                // r x q, with Uv Uv^T positive definite
  std::optional<std::size_t> substeps;  // prediction sub-steps per period, >= 1; absent: chosen
  // Samples y_k = c(x(t_k)) + Uv v_k through r polynomials in the states of degree >= 2 (the model
  // file's `c:`); C0 and C are then zero, r x n. Empty for y_k = C0 + C x(t_k) + Uv v_k, which a
  // `c:` of degree <= 1 is written as when the model is built.
  ExVector c;
  bool is_polynomial() const { return !c.empty(); }
};

// Continuous observations of the state h time units ago (paper 004): the sensor reports late.
// Before t = h the observation sees the pre-history x(s) = x(0), s < 0 (docs/theory.md §2.6).
// The model file's `delay: 0` is an ordinary ContinuousObservation; h = 0 here (C++ API) keeps the
// delayed kinds' equations, which then reduce to the undelayed ones.
struct DelayedObservation {
  GiNaC::numeric delay;  // h >= 0, exact
  ContinuousObservation rate;  // A0, A, B of dy = (A0 + A x(t - h)) dt + B dW2
};

// A polynomial observation: each h_r a polynomial in the states (of any degree), with parameters
// and functions of t in its coefficients; linear h is the continuous observation's model written
// otherwise (its filters are the same, docs/theory.md).
struct PolynomialObservation {
  ExVector h;  // p entries
  ExMatrix B;  // p x r, with B B^T positive definite
};

class ObservationModel {
 public:
  ObservationModel() = default;  // continuous with no rows: ModelBuilder requires a real one
  ObservationModel(ContinuousObservation continuous) : form_(std::move(continuous)) {}  // NOLINT: implicit by design
  ObservationModel(SampledObservation sampled) : form_(std::move(sampled)) {}  // NOLINT: implicit by design
  ObservationModel(DelayedObservation delayed) : form_(std::move(delayed)) {}  // NOLINT: implicit by design
  ObservationModel(PolynomialObservation polynomial) : form_(std::move(polynomial)) {}  // NOLINT: implicit by design

  ObservationKind kind() const;
  std::size_t p() const;  // observations per time or per sample (rows of A or of C)
  // The alternative of that kind; std::logic_error when the model's observation is of another
  // kind (its module is the one that reads it; the model room checks kind() first).
  const ContinuousObservation& continuous() const;
  const SampledObservation& sampled() const;
  const DelayedObservation& delayed() const;
  const PolynomialObservation& polynomial() const;
  // For the model room, below the modules, where its own rules differ by kind (DESIGN.md).
  bool is_sampled() const { return kind() == ObservationKind::Sampled; }
  bool is_delayed() const { return kind() == ObservationKind::Delayed; }
  bool is_polynomial() const { return kind() == ObservationKind::Polynomial; }
  // A0, A and B of a continuous or delayed observation (the rate terms of dy); std::logic_error
  // for sampled ones. For rooms that handle the delay themselves (or need only the coefficients).
  const ContinuousObservation& rate() const;
  // h of a delayed observation, 0 for the others.
  GiNaC::numeric delay() const;

 private:
  std::variant<ContinuousObservation, SampledObservation, DelayedObservation, PolynomialObservation> form_;
};

}  // namespace pfgen
