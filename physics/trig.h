// Ricochet physics: deterministic trigonometry.
//
// std::sin/cos/atan2 differ between C libraries and versions, so results that feed the simulation
// (rotations built from angles, angles read back) use these instead. They evaluate fixed
// polynomials in double precision with Cody-Waite range reduction and round once to float, so the
// same input gives the same bits everywhere IEEE-754 double arithmetic is available (no FMA: the
// build uses -ffp-contract=off).
//
// Accuracy (checked in tests/unit/trig_test.cpp against long double std:: functions):
//   sin, cos: absolute error <= 1.2e-7 (about 1 float ulp of 1) for |x| <= 1e5; the error grows
//             with |x| beyond that as the reduction constant's precision runs out. From 2^24 on
//             (floats 2 rad apart) x is first reduced by the double nearest 2 pi: the result is
//             still a rotation (sin^2 + cos^2 = 1 to float rounding), no longer sin(x).
//   atan2:    absolute error <= 2.4e-7 rad (2 float ulps of pi) over the whole plane; atan2(0, 0)
//             returns 0; signed zeros and infinities follow the C standard's quadrants.
// NaN in gives NaN out.
#pragma once

#include <span>

namespace rc {

struct SinCos {
  float sine;
  float cosine;
};

SinCos sincos(float radians);
// out[i] = sincos(radians[i]), bit for bit, for i below the shorter span's length. For many angles
// at once (every turning body each step): the calls are independent and, in one loop with the
// polynomials inlined, overlap in the processor; one by one inside a longer loop each waits out
// its polynomial chains.
void sincos(std::span<const float> radians, std::span<SinCos> out);
float sin(float radians);
float cos(float radians);
float atan2(float y, float x);

inline constexpr float kPi = 3.14159265358979323846f;

}  // namespace rc
