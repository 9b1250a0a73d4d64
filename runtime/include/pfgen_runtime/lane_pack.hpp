#pragma once
// W lanes of doubles held as one value (W a power of two, at most 16), for the batched stepping's
// per-step passes over a compile-time number of lanes: the tests and sums that run beside every
// step of W runs side by side.
//
// Written as loops over W doubles, compilers unroll these passes into scalar code with a compare
// and a branch per lane (GCC 12 does, even with AVX-512 enabled). Here a pack is an array of the
// target's own SIMD vectors (GCC's and Clang's vector extension: 2 doubles with SSE2, 4 with AVX,
// 8 with AVX-512), since a vector wider than the target's is lowered lane by lane for compares.
// Every operation is lane by lane IEEE arithmetic, so each lane's result is the scalar code's, bit
// for bit.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "pfgen_runtime/lane_flag.hpp"

#if !defined(__GNUC__)
#error "pfgen's runtime needs GCC's or Clang's vector extension (lane_pack.hpp)"
#endif

// Lane packs are values of up to 128 bytes, returned through memory by a call: every function on
// them, here and in the classes' *_pack tests, is always inlined.
#define PFGEN_LANE_PACK_INLINE inline __attribute__((always_inline))

namespace pfgen_runtime::lane_pack {

#if defined(__AVX512F__)
inline constexpr std::size_t kNativeLanes = 8;
#elif defined(__AVX__)
inline constexpr std::size_t kNativeLanes = 4;
#else
inline constexpr std::size_t kNativeLanes = 2;
#endif

template <std::size_t W>
struct Pieces {
  static_assert(W >= 2 && W <= 16 && (W & (W - 1)) == 0, "a lane pack is 2, 4, 8 or 16 doubles");
  static constexpr std::size_t width = W < kNativeLanes ? W : kNativeLanes;  // lanes per piece
  static constexpr std::size_t count = W / width;
  typedef double Values __attribute__((vector_size(width * sizeof(double))));
  typedef std::int64_t Mask __attribute__((vector_size(width * sizeof(double))));  // all ones or 0
};

// A pack's lanes; Mask: all ones (true) or 0 per lane, from a compare.
template <std::size_t W>
struct Mask {
  typename Pieces<W>::Mask piece[Pieces<W>::count];
};
template <std::size_t W>
struct Values {
  typename Pieces<W>::Values piece[Pieces<W>::count];
};

#define PFGEN_LANE_PACK_OPERATOR(Result, Operand, op)                          \
  template <std::size_t W>                                                     \
  PFGEN_LANE_PACK_INLINE Result<W> operator op(const Operand<W>& a, const Operand<W>& b) {     \
    Result<W> r;                                                               \
    for (std::size_t c = 0; c < Pieces<W>::count; ++c) r.piece[c] = a.piece[c] op b.piece[c]; \
    return r;                                                                  \
  }
PFGEN_LANE_PACK_OPERATOR(Values, Values, +)
PFGEN_LANE_PACK_OPERATOR(Values, Values, -)
PFGEN_LANE_PACK_OPERATOR(Values, Values, *)
PFGEN_LANE_PACK_OPERATOR(Values, Values, /)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, <)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, <=)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, >)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, >=)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, ==)
PFGEN_LANE_PACK_OPERATOR(Mask, Values, !=)
PFGEN_LANE_PACK_OPERATOR(Mask, Mask, &)
#undef PFGEN_LANE_PACK_OPERATOR

template <std::size_t W>
PFGEN_LANE_PACK_INLINE Mask<W>& operator&=(Mask<W>& a, const Mask<W>& b) {
  return a = a & b;
}
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Mask<W> operator~(const Mask<W>& a) {
  Mask<W> r;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c) r.piece[c] = ~a.piece[c];
  return r;
}
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> operator-(const Values<W>& a) {  // the sign flipped, as double's -x
  Values<W> r;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c) r.piece[c] = -a.piece[c];
  return r;
}

template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> load(const double* from) {  // no alignment assumed
  Values<W> v;
  std::memcpy(&v, from, sizeof v);
  return v;
}
template <std::size_t W>
PFGEN_LANE_PACK_INLINE void store(double* to, const Values<W>& v) {
  std::memcpy(to, &v, sizeof v);
}
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> splat(double x) {
  Values<W> v;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c) v.piece[c] = typename Pieces<W>::Values{} + x;
  return v;
}
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Mask<W> all_set() {
  Mask<W> m;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c) m.piece[c] = typename Pieces<W>::Mask{} - 1;
  return m;
}
// where ? a : b, lane by lane.
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> select(const Mask<W>& where, const Values<W>& a, const Values<W>& b) {
  using Bits = typename Pieces<W>::Mask;
  using Doubles = typename Pieces<W>::Values;
  Values<W> r;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c)
    r.piece[c] = reinterpret_cast<Doubles>((reinterpret_cast<Bits>(a.piece[c]) & where.piece[c]) |
                                           (reinterpret_cast<Bits>(b.piece[c]) & ~where.piece[c]));
  return r;
}
// where ? a : +0.0, lane by lane (a flag kept where `where` holds, cleared elsewhere).
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> keep_where(const Mask<W>& where, const Values<W>& a) {
  using Bits = typename Pieces<W>::Mask;
  using Doubles = typename Pieces<W>::Values;
  Values<W> r;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c)
    r.piece[c] = reinterpret_cast<Doubles>(reinterpret_cast<Bits>(a.piece[c]) & where.piece[c]);
  return r;
}
// std::abs: the sign bit cleared.
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Values<W> abs(const Values<W>& a) {
  using Bits = typename Pieces<W>::Mask;
  using Doubles = typename Pieces<W>::Values;
  Values<W> r;
  for (std::size_t c = 0; c < Pieces<W>::count; ++c)
    r.piece[c] = reinterpret_cast<Doubles>(reinterpret_cast<Bits>(a.piece[c]) & (Bits{} + INT64_MAX));
  return r;
}
// FilterStepper::finite: x - x == 0, false for inf and NaN.
template <std::size_t W>
PFGEN_LANE_PACK_INLINE Mask<W> finite(const Values<W>& x) {
  return (x - x) == splat<W>(0.0);
}
// Whether no lane of the mask is set.
template <std::size_t W>
PFGEN_LANE_PACK_INLINE bool none(const Mask<W>& m) {
  typename Pieces<W>::Mask any = m.piece[0];
  for (std::size_t c = 1; c < Pieces<W>::count; ++c) any |= m.piece[c];
  for (std::size_t k = 0; k < Pieces<W>::width; ++k)
    if (any[k] != 0) return false;
  return true;
}
// The lanes' sum, lane 0 first (exact for flags: whole numbers far below 2^53, in any order).
template <std::size_t W>
PFGEN_LANE_PACK_INLINE double sum(const Values<W>& v) {
  double lanes[W];
  std::memcpy(lanes, &v, sizeof lanes);
  double total = 0;
  for (std::size_t k = 0; k < W; ++k) total += lanes[k];
  return total;
}

}  // namespace pfgen_runtime::lane_pack
