// CFamilyEmitter::p_drift_loops: PDriftLoops in C and C++, one text for both (int indices, plain
// arrays of the scalar type). Each entry of a product is one expression, its inner sum written out
// (a_0 * b_0 + a_1 * b_1 + ..., summed left to right), inside loops over the rows and columns with
// literal bounds: the column loop walks rows of row-major blocks, which compilers vectorise, and
// every entry is stored once. (The same sum accumulated with `+=` over an inner loop was about
// twice as slow at n = 16 under g++ -O3: the row was stored and reloaded for every term.)
#include <optional>
#include <vector>

#include "pfgen/codegen/backends/c_family/c_family_emitter.hpp"

namespace pfgen::codegen {

std::string CFamilyEmitter::p_drift_loops(const PDriftLoops& loops, const PDriftLoopNames& names) const {
  using Kind = PDriftLoops::WeightEntry::Kind;
  const std::size_t n = loops.n, p = loops.p;
  const std::string N = std::to_string(n);
  const std::string& T = scalar_type_;
  const std::string &i = names.i, &j = names.j, &u = names.u;
  const std::string &w = names.work, &Pf = names.full_P, &JP = names.JP;
  // base + index, spelled without a 0 base.
  auto at = [](const std::string& array, std::size_t base, const std::string& index) {
    return array + "[" + (base == 0 ? index : std::to_string(base) + " + " + index) + "]";
  };
  // A block of p x n read by (row r, column `column`): a local array, or the work array at `base`.
  struct Block {
    std::string array;
    std::size_t base;
  };
  auto entry = [&](const Block& block, std::size_t row, const std::string& column) {
    return at(block.array, block.base + row * n, column);
  };
  auto loop = [&](const std::string& index, std::size_t from, std::size_t to) {
    return "for (int " + index + " = " + std::to_string(from) + "; " + index + " < " + std::to_string(to) + "; ++" +
           index + ")";
  };
  // From kRowsWrittenOutFrom to kFullCombineBelow the loops over rows are written out, one column
  // loop per row with the row's offsets as numbers. g++ -O2 (GCC 12) vectorises the column loops but
  // keeps the row loop, reading each row's coefficients back from the work array and broadcasting
  // them; with the offsets known it takes E[J]'s and A's entries as the constants they often are.
  // Dense linear n = 4, -O2, float: the step 1.40x to 1.14x hand-written Eigen with these rows
  // alone, 0.93x with the step's loops written out too (heun_step_text.hpp); -O3 1.07x to 1.18x,
  // where GCC had unrolled the row loop itself. At n = 4 the rows are now a loop again: with 512-bit
  // vectors GCC packed the written-out rows badly (p_drift_loops.hpp, kRowsWrittenOutFrom).
  const bool rows_written_out = loops.rows_written_out();
  // dst (rows x n) = (the work array at `base`, rows x n, row-major) times the full P: dst_ij =
  // sum_k lhs_ik P_kj.
  auto times_P = [&](const std::string& dst, std::size_t rows, std::size_t base) {
    std::string text = "  " + T + " " + dst + "[" + std::to_string(rows * n) + "];\n";
    if (rows_written_out) {
      for (std::size_t row = 0; row < rows; ++row) {
        std::string sum;
        for (std::size_t k = 0; k < n; ++k)
          sum += (k ? " + " : "") + w + "[" + std::to_string(base + row * n + k) + "] * " + at(Pf, k * n, j);
        text += "  " + loop(j, 0, n) + " " + at(dst, row * n, j) + " = " + sum + ";\n";
      }
      return text;
    }
    std::string sum;
    for (std::size_t k = 0; k < n; ++k) {
      const std::string column = k == 0 ? i + " * " + N : i + " * " + N + " + " + std::to_string(k);
      sum += (k ? " + " : "") + at(w, base, column) + " * " + at(Pf, k * n, j);
    }
    return text + "  " + loop(i, 0, rows) + "\n    " + loop(j, 0, n) + " " + dst + "[" + i + " * " + N + " + " + j +
           "] = " + sum + ";\n";
  };

  std::string text;
  text += "  // P's drift from dense blocks (loops the compiler vectorises): E[J] P + P E[J]^T";
  text += loops.factored ? " + E[g g^T] - K (A P).\n" : " + the rest.\n";
  text += times_P(JP, n, loops.jacobian_offset);
  if (loops.full_combine()) {
    // E[J] P transposed into a block of its own, written out entry by entry, so that the combining
    // loop below reads rows only. Read back as JP[j n + i], a column, that loop stayed scalar under
    // g++ -O2 (its vectoriser's cheap model does not gather); a transposing loop stored scalars that
    // the combining loop's vector loads then waited on (store forwarding), where the written-out
    // copies are packed into vectors by the compiler. Dense linear n = 4, -O2, float: the step
    // 1.65x to 1.41x hand-written Eigen; -O3 unchanged.
    text += "  " + T + " " + names.JP_T + "[" + std::to_string(n * n) + "];\n";
    for (std::size_t row = 0; row < n; ++row)
      for (std::size_t column = 0; column < n; ++column)
        text += "  " + names.JP_T + "[" + std::to_string(row * n + column) + "] = " + JP + "[" +
                std::to_string(column * n + row) + "];\n";
  }

  Block H{w, loops.H_offset}, K{w, loops.gain_offset};
  if (loops.factored && loops.H_in_loops) {
    text += times_P(names.H, p, loops.observation_offset);
    H = {names.H, 0};
  }
  if (loops.factored && loops.weighted) {
    // K^T = M H, row by row over M's nonzero entries (M = R^-1 is often diagonal).
    text += "  " + T + " " + names.gain + "[" + std::to_string(p * n) + "];\n";
    for (std::size_t r = 0; r < p; ++r) {
      std::string sum;
      for (std::size_t s = 0; s < p; ++s) {
        const PDriftLoops::WeightEntry& m = loops.weight[r][s];
        if (m.kind == Kind::Zero) continue;
        sum += (sum.empty() ? "" : " + ") +
               (m.kind == Kind::One ? entry(H, s, j) : w + "[" + std::to_string(m.offset) + "] * " + entry(H, s, j));
      }
      if (sum.empty()) sum = literal(GiNaC::numeric(0));
      text += "  " + loop(j, 0, n) + " " + at(names.gain, r * n, j) + " = " + sum + ";\n";
    }
    K = {names.gain, 0};
  }

  // E[J] P + P E[J]^T (- K (A P)) at (row, j): the full block's row a number (rows written out), the
  // triangle's the index i.
  auto combined = [&](std::optional<std::size_t> row) {
    std::string sum = row ? at(JP, *row * n, j) + " + " + at(names.JP_T, *row * n, j)
                          : JP + "[" + i + " * " + N + " + " + j + "] + " + JP + "[" + j + " * " + N + " + " + i + "]";
    if (loops.factored) {
      // sum_r K_ir H_rj = sum_r K^T[r n + i] H[r n + j]
      std::string correction;
      for (std::size_t r = 0; r < p; ++r)
        correction += (r ? " + " : "") +
                      (row ? K.array + "[" + std::to_string(K.base + r * n + *row) + "]" : entry(K, r, i)) + " * " +
                      entry(H, r, j);
      sum += " - (" + correction + ")";
    }
    return sum;
  };
  if (loops.full_combine()) {
    text += "  " + T + " " + names.sum + "[" + std::to_string(n * n) + "];\n";
    for (std::size_t row = 0; row < n; ++row)
      text += "  " + loop(j, 0, n) + " " + at(names.sum, row * n, j) + " = " + combined(row) + ";\n";
    // The upper triangle taken out entry by entry, not in loops: GCC packs the loops' rows of
    // unequal length through stack copies whose wider reloads wait for store forwarding (n = 4:
    // 15 % of rates() on one permute after such a reload with -march=native; written out, the
    // step went from 1.21x to 0.97x hand-written there, 1.20x to 1.15x with -O3 in float).
    for (std::size_t row = 0, entry = 0; row < n; ++row)
      for (std::size_t column = row; column < n; ++column, ++entry) {
        const std::string index = std::to_string(row * n + column);
        text += "  " + names.out + "[" + std::to_string(n + entry) + "] = " + names.sum + "[" + index + "]" +
                (loops.rest ? " + " + w + "[" + std::to_string(loops.rest_offset + entry) + "]" : "") + ";\n";
      }
  } else {
    const std::string rest = loops.rest ? " + " + at(w, loops.rest_offset, u) : "";
    text += "  for (int " + i + " = 0, " + u + " = 0; " + i + " < " + N + "; ++" + i + ")\n" + "    for (int " + j +
            " = " + i + "; " + j + " < " + N + "; ++" + j + ", ++" + u + ") " + at(names.out, n, u) + " = " +
            combined(std::nullopt) + rest + ";\n";
  }
  text += "  " + loop(i, 0, n) + " " + names.out + "[" + i + "] = " + w + "[" + i + "];\n";
  if (loops.gain_out && loops.full_combine()) {
    // Written out: g++ -O2 neither unrolls nor vectorises a transposing loop nest this short, and its
    // loop overhead was a tenth of rates() at n = 4.
    for (std::size_t row = 0; row < n; ++row)
      for (std::size_t r = 0; r < p; ++r)
        text += "  " + names.out + "[" + std::to_string(loops.gain_target() + row * p + r) + "] = " +
                K.array + "[" + std::to_string(K.base + r * n + row) + "];\n";
  } else if (loops.gain_out) {
    text += "  " + loop(i, 0, n) + "\n";
    text += "    " + loop(j, 0, p) + " " + at(names.out, loops.gain_target(), i + " * " + std::to_string(p) + " + " + j) +
            " = " + entry(K, 0, j + " * " + N + " + " + i) + ";\n";
  }
  if (loops.tail != 0)
    text += "  " + loop(i, 0, loops.tail) + " " + at(names.out, loops.tail_target(), i) + " = " +
            at(w, loops.tail_offset, i) + ";\n";
  return text;
}

// Unpacked entry by entry, each store a scalar. The loops read P's rows as vectors, and a vector
// load of several scalar stores still in the store buffer cannot be forwarded from them: it waits
// until they reach the cache. Written before the graph's statements, the stores are there by then.
// On the dense linear n = 4 benchmark this took the Heun step from 1.30x to 1.20x hand-written
// Eigen with -O3 -march=native in double, and from 2.12x to 1.96x with -O2 in float. Below
// kFullCombineBelow the unpacking is written out statement by statement rather than in loops, so
// the compiler sees whole rows (P_00..P_03 are the state's consecutive entries) and stores them
// as vectors: at n = 4, -O2, 1.20x to 1.10x in double and 1.85x to 1.65x in float, and 0.97x to
// 0.87x (double) and 0.90x to 0.73x (float) with -march=native; -O3 in double 0.85x to 0.88x.
std::string CFamilyEmitter::full_P(const PDriftLoops& loops, const PDriftLoopNames& names) const {
  const std::size_t n = loops.n;
  const std::string N = std::to_string(n);
  const std::string &i = names.i, &j = names.j, &u = names.u, &Pf = names.full_P;
  std::string text = "  " + scalar_type_ + " " + Pf + "[" + std::to_string(n * n) + "];\n";
  if (loops.full_combine()) {
    // Each entry's place in the state's triangle, counted as the loops below count u.
    std::vector<std::size_t> packed(n * n);
    for (std::size_t row = 0, entry = 0; row < n; ++row)
      for (std::size_t column = row; column < n; ++column, ++entry)
        packed[row * n + column] = packed[column * n + row] = entry;
    for (std::size_t e = 0; e < n * n; ++e)
      text += "  " + Pf + "[" + std::to_string(e) + "] = " + names.state + "[" + std::to_string(n + packed[e]) + "];\n";
    return text;
  }
  text += "  for (int " + i + " = 0, " + u + " = 0; " + i + " < " + N + "; ++" + i + ")\n";
  text += "    for (int " + j + " = " + i + "; " + j + " < " + N + "; ++" + j + ", ++" + u + ") " + Pf + "[" + i + " * " +
          N + " + " + j + "] = " + Pf + "[" + j + " * " + N + " + " + i + "] = " + names.state + "[" +
          std::to_string(n) + " + " + u + "];\n";
  return text;
}

}  // namespace pfgen::codegen
