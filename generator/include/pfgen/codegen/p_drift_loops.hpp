#pragma once
// P's drift in loops over dense blocks: the derivation's matrix-shaped terms, language-neutral.
//
// The Gaussian-closure kinds' P drift is E[J] P + P E[J]^T + E[g g^T] - K (A P), K the gain. Written
// out per entry, as the straight-line forms do, each product is its own scalar expression: the code
// is as long as its operation count, and compilers keep it scalar. Written as products of full
// blocks (E[J] P once, read back transposed for P E[J]^T, below kFullCombineBelow from a copy
// transposed entry by entry; H = A P; K^T = M H where the gain is
// P A^T M, M = R^-1 for the mean-square kinds), the same operations are a few loops whose inner
// trip counts are n, which compilers vectorise. For a dense E[J] the loops do the straight-line
// structured form's products (n^3 for E[J] P, where the straight-line form does n^2 (n + 1) / 2 twice
// over the upper triangle less the diagonal's), so code generation writes them where E[J] is dense
// (derivatives_code). A block whose left factor is not dense is not multiplied out: H is then the
// graph's (its entries' nonzero terms only), and M's zero entries are left out of K^T's sums.
//
// The graph computes the blocks' entries into a local work array (`work` below): m's drift first,
// then the blocks at the offsets recorded here, then the rest of P's drift per upper entry (E[g g^T],
// or E[g g^T] minus the correction where it is not factored), then the tail (rates(): what the loops
// do not give). The loops are statements (p_drift_statements), which every backend writes.
#include <cstddef>
#include <string>
#include <vector>

#include "pfgen/codegen/expression_graph.hpp"
#include "pfgen/codegen/ir/statements.hpp"

namespace pfgen::codegen {

// The smallest n the loops are written for in rates() (which shares K with them): below it a block
// is a handful of scalars, which straight-line code holds in registers and loops gain nothing on.
inline constexpr std::size_t kMinLoopDimension = 4;
// The smallest n derivatives() alone is written in loops for: without the gain to share, the loops
// made it slower at n = 4 and 5 (1.16-1.38x on the dense linear and cubic models, g++ -O2) and
// faster from n = 6 on (docs/benchmarks.md, "Generated code against hand-written code").
inline constexpr std::size_t kMinLoopDimensionAlone = 6;
// Below this n, E[J] P + P E[J]^T - K (A P) is summed over the full n x n block before its upper
// triangle is taken: rows of fewer than 8 entries are a vector or two, and the triangle's shorter
// rows kept a compiler from vectorising them (g++ -O3, n = 4: the whole step 1.6x faster in full;
// no difference at n = 8 or 16, where the triangle saves (n^2 - n) / 2 entries' operations).
inline constexpr std::size_t kFullCombineBelow = 8;
// From this n up to kFullCombineBelow the dense products' rows are written out, one column loop
// per row (p_drift_statements.cpp says why); below it, at n = 4, they are a loop over the
// rows. Written out at n = 4, GCC 12 -O3 -march=native with 512-bit vectors preferred (its tuning
// for Zen 4 and other AVX-512 machines) packed the four row loops into shuffled 512-bit vectors:
// the step 1.27x hand-written Eigen in double, 1.11x with the row loop; 256-bit vectors 0.84x to
// 0.82x (double) and 0.83x to 0.71x (float), -O3 float 1.18x to 1.12x, -O2 0.71x to 0.77x
// (double) and 0.93x to 1.00x (float). At n = 6 the row loop was no better (-O3 double 0.89x to
// 1.09x), so from 5 on the rows stay written out (docs/benchmarks.md, "Generated code against
// hand-written code").
inline constexpr std::size_t kRowsWrittenOutFrom = 5;

struct PDriftLoops {
  std::size_t n = 0;
  std::size_t p = 0;  // observations (factored only)
  // The correction as K (A P), summed in the loops from K^T and H (p x n each).
  bool factored = false;
  // Where H = A P comes from: a product in the loops of A (work array, p x n, at `observation_offset`)
  // with P, or the graph (the work array at `H_offset`).
  bool H_in_loops = false;
  std::size_t observation_offset = 0, H_offset = 0;
  // Where K^T comes from: M H in the loops (`weighted`; M's entries below), or the graph (the work
  // array at `gain_offset`).
  bool weighted = false;
  std::size_t gain_offset = 0;
  struct WeightEntry {
    enum class Kind { Zero, One, Value } kind = Kind::Zero;
    std::size_t offset = 0;  // Value: its place in the work array
  };
  std::vector<std::vector<WeightEntry>> weight;  // p x p
  std::size_t jacobian_offset = 0;               // E[J], n x n row-major
  std::size_t rest_offset = 0;                   // the rest, one entry per upper (i, j)
  bool rest = false;                             // whether any entry of the rest is nonzero
  // rates() (filter_functions.hpp): the loops also write K = (K^T)^T after P's drift (`gain_out`,
  // factored only), and copy `tail` entries the graph computed (the gain where the loops do not give
  // it, the predicted observation) from the work array at `tail_offset` after that.
  bool gain_out = false;
  std::size_t tail = 0, tail_offset = 0;
  std::size_t work_size = 0;

  bool full_combine() const { return n < kFullCombineBelow; }
  bool rows_written_out() const { return full_combine() && n >= kRowsWrittenOutFrom; }
  // Where the outputs go: m's drift at 0, P's drift at n, then K, then the tail.
  std::size_t gain_target() const { return n + n * (n + 1) / 2; }
  std::size_t tail_target() const { return gain_target() + (gain_out ? n * p : 0); }

  // The operations the loops do (the graph's own are counted apart).
  OpCounts counts() const;
};

// The names the loops declare and the arrays they read and write: chosen clear of the model's
// names (FunctionNames).
struct PDriftLoopNames {
  std::string work, state, out;
  std::string full_P, JP, gain, H;  // local arrays: P in full, E[J] P, K^T, A P
  std::string sum;                  // local array: the full block summed (full_combine)
  std::string i, j, u;              // loop indices: row, column, upper entry
  std::string JP_T;                 // local array: E[J] P transposed (full_combine)
};

// The loops of `loops`: P's drift into names.out from the work array the graph filled and the full
// P (full_P_statements'), and m's drift copied from the work array.
ir::Block p_drift_statements(const PDriftLoops& loops, const PDriftLoopNames& names);
// names.full_P, the n x n P, unpacked from the state's triangle; it opens the function, before
// the graph's statements, so that its stores are done when the loops read its rows.
ir::Block full_P_statements(const PDriftLoops& loops, const PDriftLoopNames& names);

}  // namespace pfgen::codegen
