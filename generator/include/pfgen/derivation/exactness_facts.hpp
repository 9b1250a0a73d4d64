#pragma once
// Facts about the model a filter kind is derived for (with the kind's diffusion: the model's, or its
// additive one), which the exactness conditions of every kind and observation model read
// (exactness.cpp, observations/<kind>/<kind>_exactness.cpp). Each is empty when it does not hold
// against exactness, or one phrase of rich text saying why.
#include <string>
#include <vector>

#include "pfgen/algebra/polynomial.hpp"
#include "pfgen/kinds/filter_kinds.hpp"
#include "pfgen/model/model.hpp"

namespace pfgen {

struct ExactnessFacts {
  const Model& model;
  const Diffusion& diffusion;
  std::vector<Polynomial> f;

  ExactnessFacts(const Model& m, FilterKind kind);

  std::string nonaffine_drift() const;        // "drift of y has degree 3"
  std::string state_dependent_noise() const;  // the diffusion depends on the state
  std::string nonaffine_noise() const;        // g not affine in the state
};

}  // namespace pfgen
