#pragma once
// How the states are observed, as three independent axes (docs/theory.md §2, DESIGN.md):
//   timing: continuously, dy = rate dt + noise dW2, or at samples t_k = k T, y_k = rate + noise v_k;
//   delay:  none, or h, the rate read at x(t - h);
//   rate:   rows h_r(x, t) polynomial in the states with their noise matrix (B, or a sample's Uv),
//           with A0 + A x, the affine case, found once when the rate is made.
// The kind printed in messages and listed by the filter kinds' registry (kinds/observation_kinds)
// is a name derived from the axes, kind(). The rooms above choose their part (observations/<kind>/)
// from the axes, each in one function (observation_derivation, observation_report, ...).
#include <cstddef>
#include <optional>
#include <vector>

#include "pfgen/kinds/observation_kinds.hpp"
#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

class Polynomial;

// The affine case of a rate: A0 + A x with its noise B (a sample's C0 + C x and Uv).
struct AffineRate {
  ExVector A0;  // p entries, independent of the states
  ExMatrix A;   // p x n
  ExMatrix B;   // p x r, with B B^T positive definite
};

// The rate axis: what each observation row measures, and its noise.
class ObservationRate {
 public:
  ObservationRate() = default;
  // Written A0 + A x: the model file's A0 and A (a sample's C0 and C), noise B (or Uv).
  static ObservationRate of_affine(ExVector constant, ExMatrix linear, ExMatrix noise);
  // Written as rows h_r(x, t) (the model file's h, a sample's c): affine() is found here, once,
  // present when every row is a polynomial of degree <= 1 in `states` (a row that is no
  // polynomial is left for the validator to refuse).
  static ObservationRate of_rows(ExVector rows, ExMatrix noise, const std::vector<GiNaC::symbol>& states);

  std::size_t p() const;                   // observations per time or per sample
  const ExMatrix& noise() const { return noise_; }  // p x r: B of dW2, or Uv of the samples' v_k
  // How the model wrote it, which the reports and the messages repeat: A0 + A x, or rows.
  bool written_affine() const { return written_affine_; }
  const ExVector& rows() const { return rows_; }  // as written; empty when written_affine()
  // The affine case, A0 + A x: the observation's own when written so, else found from rows() when
  // every row has degree <= 1 in the states; a property the derivation and the code may use.
  const std::optional<AffineRate>& affine() const { return affine_; }
  // h_r as polynomials in the states, however written (A0 + A x gives its rows term by term).
  std::vector<Polynomial> polynomials(const std::vector<GiNaC::symbol>& states) const;
  unsigned degree(const std::vector<GiNaC::symbol>& states) const;  // of the highest row
  std::size_t n() const { return n_; }  // the states the rate is written in (the columns of A)

 private:
  bool written_affine_ = true;
  std::size_t n_ = 0;
  ExVector rows_;
  ExMatrix noise_;
  std::optional<AffineRate> affine_;
};

// The timing axis' sampled value: samples every `period` time units. The sampled filter kinds
// predict between samples in `substeps` equal sub-steps of period / substeps (for cd-euler the
// sub-step is part of the filter's definition: 1 sub-step is the discrete-discrete filter).
// Without them each filter takes as many as its prediction's rate at the prior needs
// (observations/sampled/substep_choice.hpp).
struct SampleTimes {
  GiNaC::numeric period;                // T > 0, exact
  std::optional<std::size_t> substeps;  // prediction sub-steps per period, >= 1; absent: chosen
};

class ObservationModel {
 public:
  ObservationModel() = default;  // continuous with no rows: ModelBuilder requires a real one
  ObservationModel(ObservationRate rate, std::optional<SampleTimes> samples, std::optional<GiNaC::numeric> delay);

  // The axes.
  const ObservationRate& rate() const { return rate_; }
  const std::optional<SampleTimes>& samples() const { return samples_; }  // nothing: continuous
  // h >= 0, the rate read at x(t - h); nothing: undelayed. Before t = h the observation sees the
  // pre-history x(s) = x(0), s < 0 (docs/theory.md §2.6). The model file's `delay: 0` is an
  // undelayed observation; h = 0 here (C++ API) keeps the delayed kinds' equations, which then
  // reduce to the undelayed ones.
  const std::optional<GiNaC::numeric>& delay_h() const { return delay_; }

  // The name derived from the axes (kinds/observation_kinds.hpp): sampled, delayed, continuous
  // when written A0 + A x, polynomial when written as rows.
  ObservationKind kind() const;
  std::size_t p() const { return rate_.p(); }
  // h of a delayed observation, 0 for the others.
  GiNaC::numeric delay() const { return delay_ ? *delay_ : GiNaC::numeric(0); }
  bool is_sampled() const { return samples_.has_value(); }
  bool is_delayed() const { return delay_.has_value(); }

 private:
  ObservationRate rate_;
  std::optional<SampleTimes> samples_;
  std::optional<GiNaC::numeric> delay_;
};

}  // namespace pfgen
