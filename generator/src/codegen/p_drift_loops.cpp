#include "pfgen/codegen/p_drift_loops.hpp"

namespace pfgen::codegen {

OpCounts PDriftLoops::counts() const {
  OpCounts c;
  const std::size_t upper = n * (n + 1) / 2;
  // E[J] P: n^3 products, each entry's first product starts its sum.
  c.muls += n * n * n;
  c.adds += n * n * (n - 1);
  // The entries E[J] P + P E[J]^T - K (A P) is summed for: the upper triangle, or all of them.
  const std::size_t combined = full_combine() ? n * n : upper;
  c.adds += combined;  // (E[J] P)_ij + (E[J] P)_ji
  if (factored) {
    if (H_in_loops) {  // H = A P, p x n
      c.muls += p * n * n;
      c.adds += p * n * (n - 1);
    }
    if (weighted)  // K^T = M H over M's nonzero entries, a product for each that is not 1
      for (const auto& row : weight) {
        std::size_t terms = 0;
        for (const WeightEntry& entry : row) {
          if (entry.kind == WeightEntry::Kind::Zero) continue;
          ++terms;
          if (entry.kind == WeightEntry::Kind::Value) c.muls += n;
        }
        if (terms > 1) c.adds += (terms - 1) * n;
      }
    // sum_r K_ir H_rj, subtracted
    c.muls += combined * p;
    c.adds += combined * p;
  }
  if (rest) c.adds += upper;  // + the rest
  return c;
}

}  // namespace pfgen::codegen
