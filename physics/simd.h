#pragma once
// Four-wide float lanes through GCC/Clang vector extensions (SSE2 on x86-64, NEON on ARM): no
// intrinsics, and element-wise IEEE arithmetic, so a lane gives bit for bit what the scalar
// expression gives (the build has -ffp-contract=off).
#include <bit>
#include <cstdint>

#include "physics/math.h"

namespace rc::simd {

using F = float __attribute__((vector_size(16)));
using M = std::int32_t __attribute__((vector_size(16)));
inline constexpr int kLanes = 4;

inline F splat(float x) {
  return F{x, x, x, x};
}
inline F select(M m, F a, F b) {
  return std::bit_cast<F>((m & std::bit_cast<M>(a)) | (~m & std::bit_cast<M>(b)));
}
inline F vmax(F a, F b) {
  return a > b ? a : b;
}
inline F vmin(F a, F b) {
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
