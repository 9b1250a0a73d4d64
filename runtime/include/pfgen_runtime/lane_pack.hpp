#pragma once
// The per-step passes over W lanes of the batched stepping (the tests and sums that run beside
// every step of W runs side by side), two lanes at a time: a lane pack is two consecutive lanes in
// one SSE2 register (x86-64's baseline; elsewhere GCC's and Clang's vector extension), and a pass
// over W lanes (W even) is a loop over W / 2 packs.
//
// Why not loops over W doubles: compilers unroll those into scalar code with a compare and a
// branch per lane (GCC 12 does, even with AVX-512 enabled). Why not one vector of W doubles, or
// the vector extension's compares: GCC lowers compares of vectors wider than the target lane by
// lane, keeps arrays of vectors in memory, and turned a select on a compare into code it could
// not expand (an internal compiler error in GCC 12). The SSE2 compares give masks as doubles,
// combined by and/andnot and tested by movemask. Every operation is lane by lane IEEE arithmetic,
// so each lane's result is the scalar code's, bit for bit.
//
// Layout: entry-major, entry e of lane k at e * W + k; pack c holds lanes 2c and 2c + 1. A pass's
// functions take its W / 2 packs as an array, and loop over the entries outside, the packs inside.
#include <cstddef>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif !defined(__GNUC__)
#error "pfgen's runtime needs SSE2 or GCC's or Clang's vector extension (lane_pack.hpp)"
#endif

// Functions on packs, here and in the classes' *_packs tests, are always inlined.
#define PFGEN_LANE_PACK_INLINE inline __attribute__((always_inline))

namespace pfgen_runtime::lane_pack {

inline constexpr std::size_t kLanes = 2;  // lanes per pack

#if defined(__SSE2__)
using Pack = __m128d;  // two doubles; also a mask: all ones (true) or 0 per lane
PFGEN_LANE_PACK_INLINE Pack load(const double* from) { return _mm_loadu_pd(from); }
PFGEN_LANE_PACK_INLINE void store(double* to, Pack v) { _mm_storeu_pd(to, v); }
PFGEN_LANE_PACK_INLINE Pack splat(double x) { return _mm_set1_pd(x); }
PFGEN_LANE_PACK_INLINE Pack add(Pack a, Pack b) { return _mm_add_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack subtract(Pack a, Pack b) { return _mm_sub_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack multiply(Pack a, Pack b) { return _mm_mul_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack divide(Pack a, Pack b) { return _mm_div_pd(a, b); }
// Compares as C++'s on doubles: false where either side is NaN, except not_equal.
PFGEN_LANE_PACK_INLINE Pack less(Pack a, Pack b) { return _mm_cmplt_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack less_equal(Pack a, Pack b) { return _mm_cmple_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack greater(Pack a, Pack b) { return _mm_cmpgt_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack greater_equal(Pack a, Pack b) { return _mm_cmpge_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack equal(Pack a, Pack b) { return _mm_cmpeq_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack not_equal(Pack a, Pack b) { return _mm_cmpneq_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack all_set() { return _mm_castsi128_pd(_mm_set1_epi32(-1)); }
PFGEN_LANE_PACK_INLINE Pack both(Pack a, Pack b) { return _mm_and_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack either(Pack a, Pack b) { return _mm_or_pd(a, b); }
PFGEN_LANE_PACK_INLINE Pack except(Pack a, Pack b) { return _mm_andnot_pd(b, a); }  // a and not b
// where ? a : b, lane by lane.
PFGEN_LANE_PACK_INLINE Pack select(Pack where, Pack a, Pack b) {
  return _mm_or_pd(_mm_and_pd(where, a), _mm_andnot_pd(where, b));
}
// Whether no lane of the mask is set.
PFGEN_LANE_PACK_INLINE bool none(Pack mask) { return _mm_movemask_pd(mask) == 0; }
// -a: the sign bit flipped, as double's -x.
PFGEN_LANE_PACK_INLINE Pack negate(Pack a) { return _mm_xor_pd(a, _mm_set1_pd(-0.0)); }
#else
typedef double Pack __attribute__((vector_size(2 * sizeof(double))));
typedef long long PackBits __attribute__((vector_size(2 * sizeof(double))));
PFGEN_LANE_PACK_INLINE Pack load(const double* from) {
  Pack v;
  std::memcpy(&v, from, sizeof v);
  return v;
}
PFGEN_LANE_PACK_INLINE void store(double* to, Pack v) { std::memcpy(to, &v, sizeof v); }
PFGEN_LANE_PACK_INLINE Pack splat(double x) { return Pack{x, x}; }
PFGEN_LANE_PACK_INLINE Pack add(Pack a, Pack b) { return a + b; }
PFGEN_LANE_PACK_INLINE Pack subtract(Pack a, Pack b) { return a - b; }
PFGEN_LANE_PACK_INLINE Pack multiply(Pack a, Pack b) { return a * b; }
PFGEN_LANE_PACK_INLINE Pack divide(Pack a, Pack b) { return a / b; }
PFGEN_LANE_PACK_INLINE Pack as_pack(PackBits bits) { return reinterpret_cast<Pack>(bits); }
PFGEN_LANE_PACK_INLINE PackBits bits_of(Pack v) { return reinterpret_cast<PackBits>(v); }
PFGEN_LANE_PACK_INLINE Pack less(Pack a, Pack b) { return as_pack(a < b); }
PFGEN_LANE_PACK_INLINE Pack less_equal(Pack a, Pack b) { return as_pack(a <= b); }
PFGEN_LANE_PACK_INLINE Pack greater(Pack a, Pack b) { return as_pack(a > b); }
PFGEN_LANE_PACK_INLINE Pack greater_equal(Pack a, Pack b) { return as_pack(a >= b); }
PFGEN_LANE_PACK_INLINE Pack equal(Pack a, Pack b) { return as_pack(a == b); }
PFGEN_LANE_PACK_INLINE Pack not_equal(Pack a, Pack b) { return as_pack(a != b); }
PFGEN_LANE_PACK_INLINE Pack all_set() { return as_pack(PackBits{-1, -1}); }
PFGEN_LANE_PACK_INLINE Pack both(Pack a, Pack b) { return as_pack(bits_of(a) & bits_of(b)); }
PFGEN_LANE_PACK_INLINE Pack either(Pack a, Pack b) { return as_pack(bits_of(a) | bits_of(b)); }
PFGEN_LANE_PACK_INLINE Pack except(Pack a, Pack b) { return as_pack(bits_of(a) & ~bits_of(b)); }
PFGEN_LANE_PACK_INLINE Pack select(Pack where, Pack a, Pack b) {
  return as_pack((bits_of(where) & bits_of(a)) | (~bits_of(where) & bits_of(b)));
}
PFGEN_LANE_PACK_INLINE bool none(Pack mask) { return (bits_of(mask)[0] | bits_of(mask)[1]) == 0; }
PFGEN_LANE_PACK_INLINE Pack negate(Pack a) { return as_pack(bits_of(a) ^ bits_of(Pack{-0.0, -0.0})); }
#endif

// where ? a : +0.0, lane by lane (a flag kept where `where` holds, cleared elsewhere).
PFGEN_LANE_PACK_INLINE Pack keep_where(Pack where, Pack a) { return both(where, a); }
// std::abs: the sign bit cleared.
PFGEN_LANE_PACK_INLINE Pack abs(Pack a) { return except(a, splat(-0.0)); }
// FilterStepper::finite: x - x == 0, false for inf and NaN.
PFGEN_LANE_PACK_INLINE Pack finite(Pack x) { return equal(subtract(x, x), splat(0.0)); }

// Passes over a run-time number of lanes (a batch of any size): for_lanes(count, op) calls
// op(k, lanes) for the packs of two lanes from k, then for the last lane alone when count is odd,
// with `lanes` TwoLanes or OneLane. The same generic op then works on a Pack or a double: load,
// store, splat, sqrt, greater, flag and choose below take either, and +, -, * and / are the
// operators of both (GCC's and Clang's vector extension on a Pack).
struct TwoLanes {};
struct OneLane {};
template <class Op>
PFGEN_LANE_PACK_INLINE void for_lanes(std::size_t count, Op op) {
  std::size_t k = 0;
  for (; k + kLanes <= count; k += kLanes) op(k, TwoLanes{});
  if (k < count) op(k, OneLane{});
}
PFGEN_LANE_PACK_INLINE Pack load(const double* from, TwoLanes) { return load(from); }
PFGEN_LANE_PACK_INLINE double load(const double* from, OneLane) { return *from; }
PFGEN_LANE_PACK_INLINE void store(double* to, Pack v, TwoLanes) { store(to, v); }
PFGEN_LANE_PACK_INLINE void store(double* to, double v, OneLane) { *to = v; }
PFGEN_LANE_PACK_INLINE Pack splat(double x, TwoLanes) { return splat(x); }
PFGEN_LANE_PACK_INLINE double splat(double x, OneLane) { return x; }
#if defined(__SSE2__)
PFGEN_LANE_PACK_INLINE Pack sqrt(Pack x) { return _mm_sqrt_pd(x); }  // IEEE's correctly rounded root
#else
PFGEN_LANE_PACK_INLINE Pack sqrt(Pack x) { return Pack{__builtin_sqrt(x[0]), __builtin_sqrt(x[1])}; }
#endif
PFGEN_LANE_PACK_INLINE double sqrt(double x) { return __builtin_sqrt(x); }
PFGEN_LANE_PACK_INLINE double abs(double x) { return __builtin_fabs(x); }
PFGEN_LANE_PACK_INLINE bool greater(double a, double b) { return a > b; }
PFGEN_LANE_PACK_INLINE bool not_equal(double a, double b) { return a != b; }
PFGEN_LANE_PACK_INLINE bool equal(double a, double b) { return a == b; }
PFGEN_LANE_PACK_INLINE bool both(bool a, bool b) { return a && b; }
// A mask as flags: 1.0 where set, 0.0 elsewhere.
PFGEN_LANE_PACK_INLINE Pack flag(Pack mask) { return keep_where(mask, splat(1.0)); }
PFGEN_LANE_PACK_INLINE double flag(bool set) { return set ? 1.0 : 0.0; }
// where ? a : b.
PFGEN_LANE_PACK_INLINE Pack choose(Pack where, Pack a, Pack b) { return select(where, a, b); }
PFGEN_LANE_PACK_INLINE double choose(bool where, double a, double b) { return where ? a : b; }

// `count` doubles from `from` to `to` in packs: the few a step copies, where a call of memmove
// costs more than the copy (and its wider loads would straddle the narrower stores just made).
PFGEN_LANE_PACK_INLINE void copy(const double* from, std::size_t count, double* to) {
  for_lanes(count, [&](std::size_t k, auto lanes) { store(to + k, load(from + k, lanes), lanes); });
}

}  // namespace pfgen_runtime::lane_pack
