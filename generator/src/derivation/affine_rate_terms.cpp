#include "pfgen/derivation/affine_rate_terms.hpp"

#include "pfgen/algebra/coefficient.hpp"

namespace pfgen {
namespace {

GiNaC::matrix to_matrix(const ExMatrix& m) {
  GiNaC::matrix out(static_cast<unsigned>(m.size()), static_cast<unsigned>(m.at(0).size()));
  for (unsigned i = 0; i < out.rows(); ++i)
    for (unsigned j = 0; j < out.cols(); ++j) out(i, j) = m[i][j];
  return out;
}

ExMatrix from_matrix(const GiNaC::matrix& m) {
  ExMatrix out(m.rows(), ExVector(m.cols()));
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out[i][j] = normalize_coefficient(m(i, j));
  return out;
}

}  // namespace

ObservationTerms observation_terms(const ContinuousObservation& observation) {
  GiNaC::matrix A = to_matrix(observation.A);
  GiNaC::matrix R = to_matrix(multiply_by_transpose(observation.B));
  GiNaC::matrix At_Rinv = A.transpose().mul(R.inverse());
  GiNaC::matrix At_Rinv_A = At_Rinv.mul(A);
  return ObservationTerms{from_matrix(At_Rinv), from_matrix(At_Rinv_A)};
}

}  // namespace pfgen
