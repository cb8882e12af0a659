#include "physics/trig.h"

#include <cmath>
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
// r^14/14! < 3e-13 for cos, far below float precision.
double sinPoly(double r) {
  double r2 = r * r;
  double p = 1.0 / 6227020800.0;  // 1/13!
  p = p * r2 - 1.0 / 39916800.0;  // 1/11!
  p = p * r2 + 1.0 / 362880.0;
  p = p * r2 - 1.0 / 5040.0;
  p = p * r2 + 1.0 / 120.0;
  p = p * r2 - 1.0 / 6.0;
  return r + r * r2 * p;
}

double cosPoly(double r) {
  double r2 = r * r;
  double p = 1.0 / 87178291200.0;  // 1/14!
  p = p * r2 - 1.0 / 479001600.0;  // 1/12!
  p = p * r2 + 1.0 / 3628800.0;
  p = p * r2 - 1.0 / 40320.0;
  p = p * r2 + 1.0 / 720.0;
  p = p * r2 - 1.0 / 24.0;
  p = p * r2 + 0.5;
  return 1.0 - r2 * p;
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

}  // namespace

SinCos sincos(float radians) {
  if (!std::isfinite(radians)) {
    float nan = std::numeric_limits<float>::quiet_NaN();
    return {nan, nan};
  }
  double x = static_cast<double>(radians);
  double k = std::nearbyint(x * kTwoOverPi);
  double r = ((x - k * kPio2Hi) - k * kPio2Mid) - k * kPio2Lo;
  double s = sinPoly(r);
  double c = cosPoly(r);
  switch (static_cast<long long>(k) & 3) {
    case 0:
      return {static_cast<float>(s), static_cast<float>(c)};
    case 1:
      return {static_cast<float>(c), static_cast<float>(-s)};
    case 2:
      return {static_cast<float>(-s), static_cast<float>(-c)};
    default:
      return {static_cast<float>(-c), static_cast<float>(s)};
  }
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
