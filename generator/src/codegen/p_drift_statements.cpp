// PDriftLoops as statements (ir/statements.hpp), for every language. Each entry of a product is one
// expression, its inner sum written out (a_0 * b_0 + a_1 * b_1 + ..., summed left to right), inside
// loops over the rows and columns with literal bounds: the column loop walks rows of row-major
// blocks, which compilers vectorise, and every entry is stored once. (The same sum accumulated with
// `+=` over an inner loop was about twice as slow at n = 16 under g++ -O3: the row was stored and
// reloaded for every term.)
#include <optional>
#include <vector>

#include "pfgen/codegen/p_drift_loops.hpp"

namespace pfgen::codegen {
namespace {

using ir::Expr;

Expr operator+(Expr a, Expr b) { return ir::add(std::move(a), std::move(b)); }
Expr operator*(Expr a, Expr b) { return ir::mul(std::move(a), std::move(b)); }
Expr number(std::size_t value) { return ir::integer(value); }
Expr name(const std::string& text) { return ir::name(text); }

// array[base + index], spelled without a 0 base.
Expr at(const std::string& array, std::size_t base, Expr index) {
  return ir::element(array, base == 0 ? std::move(index) : number(base) + std::move(index));
}

ir::Statement counted(const std::string& index, std::size_t from, std::size_t to, ir::Block body) {
  return ir::loop(index, ir::Type::Int, number(from), number(to), std::move(body));
}

}  // namespace

ir::Block p_drift_statements(const PDriftLoops& loops, const PDriftLoopNames& names) {
  using Kind = PDriftLoops::WeightEntry::Kind;
  const std::size_t n = loops.n, p = loops.p;
  const Expr N = number(n);
  const Expr i = name(names.i), j = name(names.j), u = name(names.u);
  const std::string &w = names.work, &Pf = names.full_P, &JP = names.JP;
  // A block of p x n read by (row r, column `column`): a local array, or the work array at `base`.
  struct Block {
    std::string array;
    std::size_t base;
  };
  auto entry = [&](const Block& block, std::size_t row, Expr column) {
    return at(block.array, block.base + row * n, std::move(column));
  };
  // From kRowsWrittenOutFrom to kFullCombineBelow the loops over rows are written out, one column
  // loop per row with the row's offsets as numbers. g++ -O2 (GCC 12) vectorises the column loops but
  // keeps the row loop, reading each row's coefficients back from the work array and broadcasting
  // them; with the offsets known it takes E[J]'s and A's entries as the constants they often are.
  // Dense linear n = 4, -O2, float: the step 1.40x to 1.14x hand-written Eigen with these rows
  // alone, 0.93x with the step's loops written out too (codegen/heun_step.hpp); -O3
  // 1.07x to 1.18x, where GCC had unrolled the row loop itself. At n = 4 the rows are now a loop
  // again: with 512-bit vectors GCC packed the written-out rows badly (p_drift_loops.hpp,
  // kRowsWrittenOutFrom).
  const bool rows_written_out = loops.rows_written_out();
  ir::Block out;
  // dst (rows x n) = (the work array at `base`, rows x n, row-major) times the full P: dst_ij =
  // sum_k lhs_ik P_kj.
  auto times_P = [&](const std::string& dst, std::size_t rows, std::size_t base) {
    out.push_back(ir::declare_array(dst, ir::Type::Scalar, rows * n));
    if (rows_written_out) {
      for (std::size_t row = 0; row < rows; ++row) {
        std::vector<Expr> terms;
        for (std::size_t k = 0; k < n; ++k) terms.push_back(ir::element(w, base + row * n + k) * at(Pf, k * n, j));
        out.push_back(counted(names.j, 0, n, {ir::assign(at(dst, row * n, j), ir::sum(std::move(terms)))}));
      }
      return;
    }
    std::vector<Expr> terms;
    for (std::size_t k = 0; k < n; ++k) {
      Expr column = k == 0 ? i * N : i * N + number(k);
      terms.push_back(at(w, base, std::move(column)) * at(Pf, k * n, j));
    }
    out.push_back(counted(names.i, 0, rows,
                          {counted(names.j, 0, n, {ir::assign(ir::element(dst, i * N + j), ir::sum(std::move(terms)))})}));
  };

  out.push_back(ir::comment(std::string("P's drift from dense blocks (loops the compiler vectorises): E[J] P + P E[J]^T") +
                            (loops.factored ? " + E[g g^T] - K (A P)." : " + the rest.")));
  times_P(JP, n, loops.jacobian_offset);
  if (loops.full_combine()) {
    // E[J] P transposed into a block of its own, written out entry by entry, so that the combining
    // loop below reads rows only. Read back as JP[j n + i], a column, that loop stayed scalar under
    // g++ -O2 (its vectoriser's cheap model does not gather); a transposing loop stored scalars that
    // the combining loop's vector loads then waited on (store forwarding), where the written-out
    // copies are packed into vectors by the compiler. Dense linear n = 4, -O2, float: the step
    // 1.65x to 1.41x hand-written Eigen; -O3 unchanged.
    out.push_back(ir::declare_array(names.JP_T, ir::Type::Scalar, n * n));
    for (std::size_t row = 0; row < n; ++row)
      for (std::size_t column = 0; column < n; ++column)
        out.push_back(ir::assign(ir::element(names.JP_T, row * n + column), ir::element(JP, column * n + row)));
  }

  Block H{w, loops.H_offset}, K{w, loops.gain_offset};
  if (loops.factored && loops.H_in_loops) {
    times_P(names.H, p, loops.observation_offset);
    H = {names.H, 0};
  }
  if (loops.factored && loops.weighted) {
    // K^T = M H, row by row over M's nonzero entries (M = R^-1 is often diagonal).
    out.push_back(ir::declare_array(names.gain, ir::Type::Scalar, p * n));
    for (std::size_t r = 0; r < p; ++r) {
      std::vector<Expr> terms;
      for (std::size_t s = 0; s < p; ++s) {
        const PDriftLoops::WeightEntry& m = loops.weight[r][s];
        if (m.kind == Kind::Zero) continue;
        terms.push_back(m.kind == Kind::One ? entry(H, s, j) : ir::element(w, m.offset) * entry(H, s, j));
      }
      Expr sum = terms.empty() ? ir::number(GiNaC::numeric(0)) : ir::sum(std::move(terms));
      out.push_back(counted(names.j, 0, n, {ir::assign(at(names.gain, r * n, j), std::move(sum))}));
    }
    K = {names.gain, 0};
  }

  // E[J] P + P E[J]^T (- K (A P)) at (row, j): the full block's row a number (rows written out), the
  // triangle's the index i.
  auto combined = [&](std::optional<std::size_t> row) {
    Expr sum = row ? at(JP, *row * n, j) + at(names.JP_T, *row * n, j)
                   : ir::element(JP, i * N + j) + ir::element(JP, j * N + i);
    if (loops.factored) {
      // sum_r K_ir H_rj = sum_r K^T[r n + i] H[r n + j]
      std::vector<Expr> terms;
      for (std::size_t r = 0; r < p; ++r)
        terms.push_back((row ? ir::element(K.array, K.base + r * n + *row) : entry(K, r, i)) * entry(H, r, j));
      sum = ir::sub(std::move(sum), ir::grouped(ir::sum(std::move(terms))));
    }
    return sum;
  };
  if (loops.full_combine()) {
    out.push_back(ir::declare_array(names.sum, ir::Type::Scalar, n * n));
    for (std::size_t row = 0; row < n; ++row)
      out.push_back(counted(names.j, 0, n, {ir::assign(at(names.sum, row * n, j), combined(row))}));
    // The upper triangle taken out entry by entry, not in loops: GCC packs the loops' rows of
    // unequal length through stack copies whose wider reloads wait for store forwarding (n = 4:
    // 15 % of rates() on one permute after such a reload with -march=native; written out, the
    // step went from 1.21x to 0.97x hand-written there, 1.20x to 1.15x with -O3 in float).
    for (std::size_t row = 0, e = 0; row < n; ++row)
      for (std::size_t column = row; column < n; ++column, ++e) {
        Expr value = ir::element(names.sum, row * n + column);
        if (loops.rest) value = std::move(value) + ir::element(w, loops.rest_offset + e);
        out.push_back(ir::assign(ir::element(names.out, n + e), std::move(value)));
      }
  } else {
    Expr value = combined(std::nullopt);
    if (loops.rest) value = std::move(value) + at(w, loops.rest_offset, u);
    ir::Statement columns = ir::loop(names.j, ir::Type::Int, i, N, {ir::assign(at(names.out, n, u), std::move(value))},
                                     std::nullopt, names.u);
    out.push_back(ir::loop(names.i, ir::Type::Int, number(0), N, {std::move(columns)},
                           ir::Loop::Follower{names.u, number(0)}));
  }
  out.push_back(counted(names.i, 0, n, {ir::assign(ir::element(names.out, i), ir::element(w, i))}));
  if (loops.gain_out && loops.full_combine()) {
    // Written out: g++ -O2 neither unrolls nor vectorises a transposing loop nest this short, and its
    // loop overhead was a tenth of rates() at n = 4.
    for (std::size_t row = 0; row < n; ++row)
      for (std::size_t r = 0; r < p; ++r)
        out.push_back(ir::assign(ir::element(names.out, loops.gain_target() + row * p + r),
                                 ir::element(K.array, K.base + r * n + row)));
  } else if (loops.gain_out) {
    out.push_back(counted(
        names.i, 0, n,
        {counted(names.j, 0, p,
                 {ir::assign(at(names.out, loops.gain_target(), i * number(p) + j), entry(K, 0, j * N + i))})}));
  }
  if (loops.tail != 0)
    out.push_back(counted(names.i, 0, loops.tail,
                          {ir::assign(at(names.out, loops.tail_target(), i), at(w, loops.tail_offset, i))}));
  return out;
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
ir::Block full_P_statements(const PDriftLoops& loops, const PDriftLoopNames& names) {
  const std::size_t n = loops.n;
  const Expr N = number(n);
  const Expr i = name(names.i), j = name(names.j), u = name(names.u);
  const std::string& Pf = names.full_P;
  ir::Block out = {ir::declare_array(Pf, ir::Type::Scalar, n * n)};
  if (loops.full_combine()) {
    // Each entry's place in the state's triangle, counted as the loops below count u.
    std::vector<std::size_t> packed(n * n);
    for (std::size_t row = 0, e = 0; row < n; ++row)
      for (std::size_t column = row; column < n; ++column, ++e) packed[row * n + column] = packed[column * n + row] = e;
    for (std::size_t e = 0; e < n * n; ++e)
      out.push_back(ir::assign(ir::element(Pf, e), ir::element(names.state, n + packed[e])));
    return out;
  }
  ir::Statement columns =
      ir::loop(names.j, ir::Type::Int, i, N,
               {ir::assign_all({ir::element(Pf, i * N + j), ir::element(Pf, j * N + i)}, ir::element(names.state, number(n) + u))},
               std::nullopt, names.u);
  out.push_back(ir::loop(names.i, ir::Type::Int, number(0), N, {std::move(columns)}, ir::Loop::Follower{names.u, number(0)}));
  return out;
}

}  // namespace pfgen::codegen
