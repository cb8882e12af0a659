#include "physics/trig.h"

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace rc {
namespace {

// pi/2 split in three parts (Cody-Waite): k * kPio2Hi is exact for |k| < 2^20, so the
// reduction keeps ~85 bits of pi/2 instead of 53.
constexpr double kPio2Hi = 1.57079632673412561417e+00;   // first 33 bits of pi/2
constexpr double kPio2Mid = 6.07710050650619224932e-11;  // next 33 bits
constexpr double kPio2Lo = 2.02226624879595063154e-21;   // the rest
constexpr double kTwoOverPi = 6.36619772367581382433e-01;
constexpr double kPiD = 3.14159265358979323846;
constexpr double kPio2D = 1.57079632679489661923;
constexpr double kPio4D = 0.78539816339744830962;

// Taylor polynomials on |r| <= pi/4: the first omitted term is r^15/15! < 8e-14 for sin and
// r^14/14! < 3e-13 for cos, far below float precision. Both by Horner's rule in the two lanes
// of one vector (sin's lane starts a step late from 0, and 0 * r^2 + c is exactly c), so each
// lane computes, operation for operation, what its polynomial alone would.
using Double2 = double __attribute__((vector_size(16)));

struct SinCosD {
  double sine, cosine;
};

SinCosD sinCosPoly(double r) {
  const double r2 = r * r;
  const Double2 x{r2, r2};
  Double2 p{0.0, 1.0 / 87178291200.0};                          // cos: 1/14!
  p = p * x + Double2{1.0 / 6227020800.0, -1.0 / 479001600.0};  // sin: 1/13!; cos: 1/12!
  p = p * x + Double2{-1.0 / 39916800.0, 1.0 / 3628800.0};
  p = p * x + Double2{1.0 / 362880.0, -1.0 / 40320.0};
  p = p * x + Double2{-1.0 / 5040.0, 1.0 / 720.0};
  p = p * x + Double2{1.0 / 120.0, -1.0 / 24.0};
  p = p * x + Double2{-1.0 / 6.0, 0.5};
  return {r + r * r2 * p[0], 1.0 - r2 * p[1]};
}

// atan on [0, 1]: shifted by pi/4 when t > tan(pi/8) so |u| <= tan(pi/8) ~= 0.4142, then the
// alternating series sum (-1)^j u^(2j+1)/(2j+1) to j = 12, whose first omitted term is
// u^27/27 < 2e-12.
double atanUnit(double t) {
  constexpr double kTanPi8 = 0.41421356237309504880;
  double offset = 0.0;
  if (t > kTanPi8) {
    t = (t - 1.0) / (t + 1.0);
    offset = kPio4D;
  }
  double t2 = t * t;
  double p = 0.0;
  for (int j = 12; j >= 0; --j) {
    double c = 1.0 / static_cast<double>(2 * j + 1);
    p = ((j & 1) ? -c : c) + t2 * p;
  }
  return offset + t * p;
}

// nearbyint(v) in the default rounding mode, for |v| < 2^51, without the library call (a call
// through the PLT; x86-64 before SSE4.1 has no rounding instruction): adding 1.5 * 2^52 leaves
// no fraction bits, so the sum rounds |v| to an integer, ties to even, exactly as nearbyint
// does. The sign is put back, so -0.3 gives -0 as nearbyint does.
double roundToInteger(double v) {
  constexpr double kMagic = 0x1.8p52;
  return std::copysign((std::fabs(v) + kMagic) - kMagic, v);
}

// Bits of a if pick, else of b, and a negated when flip: selects and sign flips as masks, so
// that the quadrant (random for a spinning body) costs no mispredicted branch.
float pick(bool pick, float a, float b) {
  const std::uint32_t mask = 0u - static_cast<std::uint32_t>(pick);
  return std::bit_cast<float>((std::bit_cast<std::uint32_t>(a) & mask) |
                              (std::bit_cast<std::uint32_t>(b) & ~mask));
}
float negateIf(bool flip, float a) {
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(a) ^
                              (static_cast<std::uint32_t>(flip) << 31));
}

[[gnu::always_inline]] inline SinCos sincosInline(float radians) {
  if (!std::isfinite(radians)) {
    float nan = std::numeric_limits<float>::quiet_NaN();
    return {nan, nan};
  }
  double x = static_cast<double>(radians);
  // Small angles (what a body turns in a substep): no reduction, shorter series. The first
  // omitted terms, x^9/9! < 2e-16 and x^8/8! < 6e-15 at |x| = 1/16, are far below float
  // precision, so the result is the full path's except where the double falls within 6e-15 of
  // a float rounding boundary. A settling pyramid's turns cost a third of the full path.
  if (std::fabs(x) < 0.0625) {
    const double x2 = x * x;
    const double s = x + x * x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0)));
    const double c = 1.0 - x2 * (0.5 + x2 * (-1.0 / 24.0 + x2 * (1.0 / 720.0)));
    return {static_cast<float>(s), static_cast<float>(c)};
  }
  // From 2^24 on, floats are 2 rad or more apart and the three-part pi/2 runs out of digits
  // (at 1e20 the reduced angle would be thousands of radians and the polynomials overflow):
  // take the exact remainder by 2 pi (the double nearest) first, so the result stays a
  // rotation. std::fmod is exact, so this is as deterministic as the rest.
  if (std::fabs(x) > 0x1p24) [[unlikely]]
    x = std::fmod(x, 2.0 * kPiD);
  double k = roundToInteger(x * kTwoOverPi);
  double r = ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
  const SinCosD sc = sinCosPoly(r);
  const auto s = static_cast<float>(sc.sine);
  const auto c = static_cast<float>(sc.cosine);
  // x = r + k pi/2 (|k| < 2^24): the quadrant k mod 4 swaps and negates.
  const auto quadrant = static_cast<unsigned>(static_cast<long long>(k) & 3);
  const bool odd = (quadrant & 1u) != 0;
  return {negateIf(quadrant >= 2u, pick(odd, c, s)),
          negateIf(quadrant == 1u || quadrant == 2u, pick(odd, s, c))};
}
}  // namespace

SinCos sincos(float radians) {
  return sincosInline(radians);
}

void sincos(std::span<const float> radians, std::span<SinCos> out) {
  const std::size_t n = radians.size() < out.size() ? radians.size() : out.size();
  for (std::size_t i = 0; i < n; ++i)
    out[i] = sincosInline(radians[i]);
}

float sin(float radians) {
  return sincos(radians).sine;
}
float cos(float radians) {
  return sincos(radians).cosine;
}

float atan2(float y, float x) {
  if (std::isnan(x) || std::isnan(y)) return std::numeric_limits<float>::quiet_NaN();
  double ax = std::fabs(static_cast<double>(x));
  double ay = std::fabs(static_cast<double>(y));
  double a;
  if (ay == 0.0) {
    a = 0.0;
  } else if (ax == 0.0) {
    a = kPio2D;
  } else if (std::isinf(ax) && std::isinf(ay)) {
    a = kPio4D;
  } else if (ay <= ax) {
    a = atanUnit(ay / ax);
  } else {
    a = kPio2D - atanUnit(ax / ay);
  }
  if (std::signbit(x)) a = kPiD - a;
  return static_cast<float>(std::signbit(y) ? -a : a);
}

}  // namespace rc
