#pragma once
// How the states are observed. The model file's `observation:` section chooses the kind when it
// is read (kinds/observation_kinds.hpp lists them), and every room asks the ObservationModel for
// its kind and the alternative it handles, instead of assuming one observation equation; a new
// kind is one more alternative of the variant below. Today the one kind is continuous:
//   dy = (A0 + A x) dt + B dW2.
#include <cstddef>
#include <variant>

#include "pfgen/kinds/observation_kinds.hpp"
#include "pfgen/model/expression_matrix.hpp"

namespace pfgen {

struct ContinuousObservation {
  ExVector A0;  // p entries, independent of the states
  ExMatrix A;   // p x n
  ExMatrix B;   // p x r, with B B^T positive definite
};

class ObservationModel {
 public:
  ObservationModel() = default;  // continuous with no rows: ModelBuilder requires a real one
  ObservationModel(ContinuousObservation continuous) : form_(std::move(continuous)) {}  // NOLINT: implicit by design

  ObservationKind kind() const;
  std::size_t p() const;  // observations per time (rows of A)
  // The alternative of that kind; std::logic_error when the model's observation is of another
  // kind (a room that handles it must have checked kind() or the kind registry first).
  const ContinuousObservation& continuous() const;

 private:
  std::variant<ContinuousObservation> form_;
};

}  // namespace pfgen
