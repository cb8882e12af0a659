#pragma once
// Float lanes through GCC/Clang vector extensions: no intrinsics, and element-wise IEEE
// arithmetic, so a lane gives bit for bit what the scalar expression gives (the build has
// -ffp-contract=off). Four lanes are SSE2 on x86-64 and NEON on ARM; eight lanes are one AVX
// register in a function compiled for AVX2 (see contact_solver.cpp) and two four-lane halves
// anywhere else.
#include <bit>
#include <cstddef>
#include <cstdint>

#include "physics/math.h"

namespace rc::simd {

using F = float __attribute__((vector_size(16)));
using M = std::int32_t __attribute__((vector_size(16)));
inline constexpr int kLanes = 4;

// Aligned to 32 bytes explicitly: compiled without AVX, GCC aligns a 32-byte vector to 16 only,
// and the AVX2 code that loads it assumes 32.
using F8 = float __attribute__((vector_size(32), aligned(32)));
using M8 = std::int32_t __attribute__((vector_size(32), aligned(32)));

// The float and mask vectors of N lanes.
template <int N>
struct Lanes;
template <>
struct Lanes<4> {
  using F = simd::F;
  using M = simd::M;
};
template <>
struct Lanes<8> {
  using F = F8;
  using M = M8;
};

// Code compiled for AVX2 (the solver's eight-lane batches, the batched sine and cosine) runs
// where the processor has AVX2; otherwise the baseline code runs. Both give the same bits (a
// world can still ask for the baseline width: WorldDef::maxSolverLanes).
#if defined(__x86_64__) || defined(__i386__)
#define RC_HAVE_AVX2_PATHS 1
#else
#define RC_HAVE_AVX2_PATHS 0
#endif
bool avx2Enabled();

// The helpers below are always inlined, so that a caller compiled for a wider instruction set
// (an AVX2 function) gets them in its own instructions, and they call no library function: in a
// Debug build std::bit_cast is a real call, compiled without AVX, and an eight-lane vector
// returned from it is returned by another convention than the AVX caller expects (it crashed).
template <class V = F>
[[gnu::always_inline]] inline V splat(float x) {
  V v{};
  for (int i = 0; i < static_cast<int>(sizeof(V) / sizeof(float)); ++i)
    v[i] = x;
  return v;
}
template <class Mask, class V>
[[gnu::always_inline]] inline V select(Mask m, V a, V b) {
  return __builtin_bit_cast(V,
                            (m & __builtin_bit_cast(Mask, a)) | (~m & __builtin_bit_cast(Mask, b)));
}
// Whether every lane of a mask (each lane 0 or all ones) is set. Folded in the vector (an
// eight-lane mask's halves, then two 64-bit words): lane by lane it was eight extracts and
// seven ands, a twentieth of a two-point batch's solve.
template <class Mask>
[[gnu::always_inline]] inline bool allLanes(Mask m) {
  using Words = long long __attribute__((vector_size(16)));
  M four;
  if constexpr (sizeof(Mask) == 2 * sizeof(M)) {
    four = __builtin_shufflevector(m, m, 0, 1, 2, 3) & __builtin_shufflevector(m, m, 4, 5, 6, 7);
  } else {
    static_assert(sizeof(Mask) == sizeof(M));
    four = m;
  }
  const Words words = __builtin_bit_cast(Words, four);
  return (words[0] & words[1]) == -1;
}
template <class V>
[[gnu::always_inline]] inline V vmax(V a, V b) {
  return a > b ? a : b;
}
template <class V>
[[gnu::always_inline]] inline V vmin(V a, V b) {
  return a < b ? a : b;
}

// The smallest of the four lanes.
inline float hmin(F a) {
  a = vmin(a, __builtin_shufflevector(a, a, 2, 3, 0, 1));
  a = vmin(a, __builtin_shufflevector(a, a, 1, 0, 3, 2));
  return a[0];
}

// Four consecutive points split into their x and y lanes.
inline void deinterleave(const Vec2* p, F* x, F* y) {
  *x = F{p[0].x, p[1].x, p[2].x, p[3].x};
  *y = F{p[0].y, p[1].y, p[2].y, p[3].y};
}

}  // namespace rc::simd
