#if defined(__clang__)
#pragma clang diagnostic ignored "-Wunknown-warning-option"
#endif
// sincos4 keeps its vectors inside itself: no AVX vector crosses a call (see contact_solver.cpp).
#pragma GCC diagnostic ignored "-Wpsabi"

#include "physics/trig.h"

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "physics/simd.h"

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

// Horner's rule from the highest term: sine's (over r: 1/13! r^12 .. -1/3! r^2) and cosine's
// (1/14! r^14 .. 1/2 r^2). Shared by the one-angle and the four-angle paths.
constexpr double kSineTerms[6] = {1.0 / 6227020800.0, -1.0 / 39916800.0, 1.0 / 362880.0,
                                  -1.0 / 5040.0,      1.0 / 120.0,       -1.0 / 6.0};
constexpr double kCosineTerms[7] = {1.0 / 87178291200.0,
                                    -1.0 / 479001600.0,
                                    1.0 / 3628800.0,
                                    -1.0 / 40320.0,
                                    1.0 / 720.0,
                                    -1.0 / 24.0,
                                    0.5};

SinCosD sinCosPoly(double r) {
  const double r2 = r * r;
  const Double2 x{r2, r2};
  Double2 p{0.0, kCosineTerms[0]};
  for (int j = 0; j < 6; ++j)
    p = p * x + Double2{kSineTerms[j], kCosineTerms[j + 1]};
  return {r + r * r2 * p[0], 1.0 - r2 * p[1]};
}

// The short series for |x| < 1/16 (see sincosInline), for a double or a vector of doubles.
// Vectors go through references: clang refuses an AVX vector passed or returned by value by a
// function without the AVX target (sincos4 is AVX2, these templates are not), inlined or not.
template <class D>
[[gnu::always_inline]] inline void smallSine(const D& x, D& sine) {
  const D x2 = x * x;
  sine = x + x * x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0)));
}
template <class D>
[[gnu::always_inline]] inline void smallCosine(const D& x, D& cosine) {
  const D x2 = x * x;
  cosine = 1.0 - x2 * (0.5 + x2 * (-1.0 / 24.0 + x2 * (1.0 / 720.0)));
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
    double sine = 0.0, cosine = 0.0;
    smallSine(x, sine);
    smallCosine(x, cosine);
    return {static_cast<float>(sine), static_cast<float>(cosine)};
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

#if RC_HAVE_AVX2_PATHS
// Four angles at a time in AVX2 doubles: both paths of sincosInline (the short series and the
// reduced one) for every lane, element by element the same operations in the same order, and
// the lane's own path chosen by mask; so each lane is bit for bit sincosInline's result. A group
// with an angle that is not finite or beyond 2^24 goes one by one. Returns how many were done.
using D4 = double __attribute__((vector_size(32), aligned(32)));
using I4 = std::int64_t __attribute__((vector_size(32), aligned(32)));
using F4 = float __attribute__((vector_size(16)));
using M4 = std::int32_t __attribute__((vector_size(16)));

[[gnu::target("avx2")]] std::size_t sincos4(const float* radians, SinCos* out, std::size_t n) {
  constexpr auto kSign = static_cast<std::int64_t>(0x8000000000000000ull);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    F4 xf;
    std::memcpy(&xf, radians + i, sizeof xf);
    const D4 x = __builtin_convertvector(xf, D4);
    const D4 ax = __builtin_bit_cast(D4, __builtin_bit_cast(I4, x) & ~kSign);
    D4 sSmall, cSmall;
    smallSine(x, sSmall);
    smallCosine(x, cSmall);
    const auto store = [&](F4 sine, F4 cosine) {
      const F4 low = __builtin_shufflevector(sine, cosine, 0, 4, 1, 5);
      const F4 high = __builtin_shufflevector(sine, cosine, 2, 6, 3, 7);
      std::memcpy(static_cast<void*>(out + i), &low, sizeof low);
      std::memcpy(static_cast<void*>(out + i + 2), &high, sizeof high);
    };
    // Every angle small (a substep's turns, nearly always): the short series alone, the
    // reduced path's work skipped (it is what each lane would take anyway).
    const I4 smallLanes = ax < 0.0625;  // false for NaN too
    if (smallLanes[0] & smallLanes[1] & smallLanes[2] & smallLanes[3]) {
      store(__builtin_convertvector(sSmall, F4), __builtin_convertvector(cSmall, F4));
      continue;
    }
    const I4 ordinary = ax <= 0x1p24;  // false for NaN and infinities too
    if (!(ordinary[0] & ordinary[1] & ordinary[2] & ordinary[3])) {
      for (std::size_t j = i; j < i + 4; ++j)
        out[j] = sincosInline(radians[j]);
      continue;
    }
    // The reduction: k = roundToInteger(x 2/pi), the magic sum's low bits are |k|.
    const D4 v = x * kTwoOverPi;
    const I4 vSign = __builtin_bit_cast(I4, v) & kSign;
    const D4 magicSum = __builtin_bit_cast(D4, __builtin_bit_cast(I4, v) & ~kSign) + 0x1p52 * 1.5;
    const D4 k = __builtin_bit_cast(D4, __builtin_bit_cast(I4, magicSum - 0x1p52 * 1.5) | vSign);
    const D4 r = ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
    // sinCosPoly's two lanes, one vector each.
    const D4 r2 = r * r;
    D4 ps{}, pc = kCosineTerms[0] + D4{};
    for (int j = 0; j < 6; ++j) {
      ps = ps * r2 + kSineTerms[j];
      pc = pc * r2 + kCosineTerms[j + 1];
    }
    const F4 s = __builtin_convertvector(r + r * r2 * ps, F4);
    const F4 c = __builtin_convertvector(1.0 - r2 * pc, F4);
    // The quadrant k mod 4 of a signed k from |k| mod 4.
    const I4 kAbs = __builtin_bit_cast(I4, magicSum) & 3;
    const I4 quadrant = vSign != 0 ? (4 - kAbs) & 3 : kAbs;
    const M4 q = __builtin_convertvector(quadrant, M4);
    const M4 odd = (q & 1) != 0;
    const M4 negateSine = q >= 2, negateCosine = (q == 1) | (q == 2);
    const M4 small = __builtin_convertvector(smallLanes, M4);
    const auto bits = [](F4 f) { return __builtin_bit_cast(M4, f); };
    constexpr std::int32_t kFloatSign = std::numeric_limits<std::int32_t>::min();
    const M4 sineFull = ((odd & bits(c)) | (~odd & bits(s))) ^ (negateSine & kFloatSign);
    const M4 cosineFull = ((odd & bits(s)) | (~odd & bits(c))) ^ (negateCosine & kFloatSign);
    const F4 sine = __builtin_bit_cast(
        F4, (small & bits(__builtin_convertvector(sSmall, F4))) | (~small & sineFull));
    const F4 cosine = __builtin_bit_cast(
        F4, (small & bits(__builtin_convertvector(cSmall, F4))) | (~small & cosineFull));
    store(sine, cosine);
  }
  return i;
}
#endif

void sincos(std::span<const float> radians, std::span<SinCos> out) {
  const std::size_t n = radians.size() < out.size() ? radians.size() : out.size();
  std::size_t i = 0;
#if RC_HAVE_AVX2_PATHS
  if (simd::avx2Enabled()) i = sincos4(radians.data(), out.data(), n);
#endif
  for (; i < n; ++i)
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
