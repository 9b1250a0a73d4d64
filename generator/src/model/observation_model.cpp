#include "pfgen/model/observation_model.hpp"

#include <algorithm>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/model/polynomial_shape.hpp"

namespace pfgen {

namespace {

// Rows written A0 + A x when every one is a polynomial of degree <= 1 in the states.
std::optional<AffineRate> affine_rows(const ExVector& rows, const ExMatrix& noise, const std::vector<GiNaC::symbol>& states) {
  std::vector<Polynomial> polynomials;
  for (const GiNaC::ex& row : rows) {
    // Polynomial::from_ex reads polynomials only: a row that is none (refused by the validator)
    // or has a degree above 1 in some state is not affine.
    const PolynomialShape shape = polynomial_shape(row, states, 1);
    if (!shape.polynomial || std::any_of(shape.degrees.begin(), shape.degrees.end(), [](std::int64_t d) { return d > 1; }))
      return std::nullopt;
    polynomials.push_back(Polynomial::from_ex(row, states));
    if (polynomials.back().degree() > 1) return std::nullopt;
  }
  AffineRate out{ExVector(rows.size(), GiNaC::ex(0)), ExMatrix(rows.size(), ExVector(states.size(), GiNaC::ex(0))), noise};
  for (std::size_t r = 0; r < polynomials.size(); ++r)
    for (const auto& [monomial, coefficient] : polynomials[r].terms()) {
      if (monomial.is_one())
        out.A0[r] = coefficient;
      else
        out.A[r][monomial.factors().front().first] = coefficient;
    }
  return out;
}

}  // namespace

ObservationRate ObservationRate::of_affine(ExVector constant, ExMatrix linear, ExMatrix noise) {
  ObservationRate out;
  out.written_affine_ = true;
  out.n_ = linear.empty() ? 0 : linear.front().size();
  out.noise_ = noise;
  out.affine_ = AffineRate{std::move(constant), std::move(linear), std::move(noise)};
  return out;
}

ObservationRate ObservationRate::of_rows(ExVector rows, ExMatrix noise, const std::vector<GiNaC::symbol>& states) {
  ObservationRate out;
  out.written_affine_ = false;
  out.n_ = states.size();
  out.affine_ = affine_rows(rows, noise, states);
  out.rows_ = std::move(rows);
  out.noise_ = std::move(noise);
  return out;
}

std::size_t ObservationRate::p() const {
  if (!written_affine_) return rows_.size();
  return affine_ ? affine_->A.size() : 0;  // a default rate has no rows yet
}

std::vector<Polynomial> ObservationRate::polynomials(const std::vector<GiNaC::symbol>& states) const {
  std::vector<Polynomial> out;
  if (!written_affine_) {
    for (const GiNaC::ex& row : rows_) out.push_back(Polynomial::from_ex(row, states));
    return out;
  }
  if (!affine_) return out;
  for (std::size_t r = 0; r < affine_->A.size(); ++r) {
    Polynomial row = Polynomial::constant(affine_->A0[r]);
    for (std::size_t k = 0; k < affine_->A[r].size(); ++k)
      row.add_term(Monomial::variable(static_cast<std::uint32_t>(k)), affine_->A[r][k]);
    out.push_back(std::move(row));
  }
  return out;
}

unsigned ObservationRate::degree(const std::vector<GiNaC::symbol>& states) const {
  unsigned out = 0;
  for (const Polynomial& row : polynomials(states)) out = std::max(out, row.degree());
  return out;
}

ObservationModel::ObservationModel(ObservationRate rate, std::optional<SampleTimes> samples,
                                   std::optional<GiNaC::numeric> delay)
    : rate_(std::move(rate)), samples_(std::move(samples)), delay_(std::move(delay)) {}

ObservationKind ObservationModel::kind() const {
  if (samples_) return ObservationKind::Sampled;
  if (delay_) return ObservationKind::Delayed;
  return rate_.written_affine() ? ObservationKind::Continuous : ObservationKind::Polynomial;
}

}  // namespace pfgen
