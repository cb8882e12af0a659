// Our own sin/cos/atan2 against long double std:: functions (the accuracy stated in trig.h).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "physics/random.h"
#include "physics/trig.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace trig_test {

TEST(Trig, SinCosAccuracyOverWideRange) {
  rc::Random rng(1);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    float scale = (i % 4 == 0) ? 1e5f : (i % 4 == 1 ? 100.0f : 4.0f);
    float x = rng.uniform(-scale, scale);
    rc::SinCos sc = rc::sincos(x);
    long double lx = x;
    worst = std::max(worst, static_cast<double>(std::fabs(sc.sine - std::sin(lx))));
    worst = std::max(worst, static_cast<double>(std::fabs(sc.cosine - std::cos(lx))));
  }
  EXPECT_LE(worst, 1.2e-7);
}

// Below 1/16 rad sincos takes a shorter series without reduction (what bodies turn in a
// substep). There it rounds correctly: every result is the float nearest the long double
// value. (Dropping sine's last term, an error of 1e-11 relative at 1/16, breaks that for 2 of
// these angles.) Half the angles uniform, half spread over magnitudes down to 1e-30, and the
// boundary itself.
TEST(Trig, SmallAnglesRoundCorrectly) {
  rc::Random rng(3);
  std::vector<float> angles = {0.0625f, std::nextafter(0.0625f, 0.0f), -0.0625f, 1e-30f,
                               std::numeric_limits<float>::denorm_min()};
  for (int i = 0; i < 200000; ++i) {
    const float x = i % 2 == 0 ? rng.uniform(-0.0625f, 0.0625f)
                               : std::exp2(rng.uniform(-100.0f, -4.0f)) * (i % 4 == 1 ? 1 : -1);
    angles.push_back(x);
  }
  int wrong = 0;
  for (float x : angles) {
    const rc::SinCos sc = rc::sincos(x);
    const long double lx = x;
    wrong += sc.sine != static_cast<float>(std::sin(lx));
    wrong += sc.cosine != static_cast<float>(std::cos(lx));
  }
  EXPECT_EQ(wrong, 0);
}

// The batch (four at a time in AVX2 where the processor has it) gives, bit for bit, what the
// one-angle sincos gives: angles of every size, both sides of the short series' boundary and of
// the quadrant boundaries, the special values, in spans of every length mod 4 (the groups and
// the tail), a group holding one angle beyond 2^24 or not finite (which goes one by one), and
// runs of small angles (a substep's turns), whose groups take the short series alone when every
// angle in them is below 1/16.
TEST(Trig, BatchMatchesOneAtATime) {
  rc::Random rng(7);
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> angles = {0.0f,
                               -0.0f,
                               0.0625f,
                               -0.0625f,
                               std::nextafter(0.0625f, 0.0f),
                               0x1p24f,
                               -0x1p24f,
                               std::nextafter(0x1p24f, inf),
                               3e30f,
                               inf,
                               -inf,
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::denorm_min()};
  for (int q = -40; q <= 40; ++q) {
    const float edge = static_cast<float>(q) * (rc::kPi / 4.0f);
    angles.push_back(edge);
    angles.push_back(std::nextafter(edge, inf));
    angles.push_back(std::nextafter(edge, -inf));
  }
  for (int i = 0; i < 400000; ++i) {
    switch (i % 4) {
      case 0:
        angles.push_back(rng.uniform(-0.1f, 0.1f));
        break;
      case 1:
        angles.push_back(rng.uniform(-10.0f, 10.0f));
        break;
      case 2:
        angles.push_back(rng.uniform(-2e5f, 2e5f));
        break;
      default:
        angles.push_back(std::exp2(rng.uniform(-60.0f, 30.0f)) * (i % 8 < 4 ? 1 : -1));
    }
  }
  for (int i = 0; i < 100000; ++i)
    angles.push_back(i % 1000 < 500 ? rng.uniform(-0.0625f, 0.0625f) : rng.uniform(-0.07f, 0.07f));
  int different = 0;
  for (std::size_t length :
       {angles.size(), angles.size() - 1, angles.size() - 2, angles.size() - 3}) {
    std::vector<rc::SinCos> out(length);
    rc::sincos(std::span<const float>(angles.data(), length), out);
    for (std::size_t i = 0; i < length; ++i) {
      const rc::SinCos one = rc::sincos(angles[i]);
      different +=
          std::bit_cast<std::uint32_t>(out[i].sine) != std::bit_cast<std::uint32_t>(one.sine);
      different +=
          std::bit_cast<std::uint32_t>(out[i].cosine) != std::bit_cast<std::uint32_t>(one.cosine);
    }
  }
  EXPECT_EQ(different, 0);
}

TEST(Trig, ExactValuesAndSymmetry) {
  EXPECT_EQ(rc::sin(0.0f), 0.0f);
  EXPECT_EQ(rc::cos(0.0f), 1.0f);
  EXPECT_NEAR(rc::sin(rc::kPi / 2), 1.0f, 1e-7f);
  EXPECT_NEAR(rc::cos(rc::kPi), -1.0f, 1e-7f);
  for (float x : {0.1f, 1.0f, 2.5f, 10.0f, 1000.0f}) {
    EXPECT_EQ(rc::sin(-x), -rc::sin(x));
    EXPECT_EQ(rc::cos(-x), rc::cos(x));
  }
}

// A reference for the reduction as it was first written: std::nearbyint for the multiple of
// pi/2, each polynomial on its own, a switch on the quadrant. The fast rounding, the two-lane
// polynomials and the quadrant masks must give its bits exactly below 2^24 rad.
rc::SinCos referenceSinCos(float radians) {
  const double pio2Hi = 1.57079632673412561417e+00, pio2Mid = 6.07710050650619224932e-11,
               pio2Lo = 2.02226624879595063154e-21, twoOverPi = 6.36619772367581382433e-01;
  const double x = radians;
  const double k = std::nearbyint(x * twoOverPi);
  const double r = ((x - k * pio2Hi) - k * pio2Mid) - k * pio2Lo;
  const double r2 = r * r;
  double p = 1.0 / 6227020800.0;
  for (double c : {-1.0 / 39916800.0, 1.0 / 362880.0, -1.0 / 5040.0, 1.0 / 120.0, -1.0 / 6.0})
    p = p * r2 + c;
  const double sine = r + r * r2 * p;
  p = 1.0 / 87178291200.0;
  for (double c :
       {-1.0 / 479001600.0, 1.0 / 3628800.0, -1.0 / 40320.0, 1.0 / 720.0, -1.0 / 24.0, 0.5})
    p = p * r2 + c;
  const double cosine = 1.0 - r2 * p;
  switch (static_cast<long long>(k) & 3) {
    case 0:
      return {static_cast<float>(sine), static_cast<float>(cosine)};
    case 1:
      return {static_cast<float>(cosine), static_cast<float>(-sine)};
    case 2:
      return {static_cast<float>(-sine), static_cast<float>(-cosine)};
    default:
      return {static_cast<float>(-cosine), static_cast<float>(sine)};
  }
}

std::uint64_t bits(rc::SinCos sc) {
  return std::uint64_t{std::bit_cast<std::uint32_t>(sc.sine)} << 32 |
         std::bit_cast<std::uint32_t>(sc.cosine);
}

// Below 2^24 rad: the reference's bits, one by one and in the batch form (used for every
// turning body each step), over every magnitude, the multiples of pi/4 where the rounding
// ties, and the signed zeros. Above: the batch form still gives the one-by-one bits.
TEST(Trig, BitsOfTheReferenceReduction) {
  rc::Random rng(7);
  std::vector<float> angles = {0.0f, -0.0f, 0.5f, -0.785f, 0x1p24f, -0x1p24f};
  for (int m = -64; m <= 64; ++m) {
    const float q = static_cast<float>(m) * (rc::kPi / 4);
    angles.insert(angles.end(), {q, std::nextafter(q, 1e9f), std::nextafter(q, -1e9f)});
  }
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::ldexp(1.0f, static_cast<int>(rng.below(45)) - 20);  // to 2^24
    angles.push_back(rng.uniform(-scale, scale));
  }
  const std::size_t belowLimit = angles.size();
  for (float huge : {0x1.000002p24f, 1e20f, -3.4e38f, 7.1e15f})
    angles.push_back(huge);
  std::vector<rc::SinCos> batch(angles.size());
  rc::sincos(angles, batch);
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const rc::SinCos one = rc::sincos(angles[i]);
    ASSERT_EQ(bits(batch[i]), bits(one)) << angles[i];
    if (i < belowLimit) {
      ASSERT_EQ(bits(one), bits(referenceSinCos(angles[i]))) << angles[i];
    }
  }
}

// Beyond 1e5 the reduction's digits run out (trig.h), but the result stays a rotation.
TEST(Trig, HugeAnglesStayOnTheUnitCircle) {
  for (float x : {1e10f, 1e20f, 9.3e18f, -1e25f, 3.4e38f, -std::numeric_limits<float>::max()}) {
    const rc::SinCos sc = rc::sincos(x);
    EXPECT_NEAR(sc.sine * sc.sine + sc.cosine * sc.cosine, 1.0f, 1e-6f) << x;
  }
}

TEST(Trig, NonFiniteGivesNaN) {
  EXPECT_TRUE(std::isnan(rc::sin(std::numeric_limits<float>::infinity())));
  EXPECT_TRUE(std::isnan(rc::cos(std::numeric_limits<float>::quiet_NaN())));
  EXPECT_TRUE(std::isnan(rc::atan2(std::numeric_limits<float>::quiet_NaN(), 1.0f)));
}

TEST(Trig, Atan2AccuracyAllQuadrants) {
  rc::Random rng(2);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    float y = rng.uniform(-10.0f, 10.0f), x = rng.uniform(-10.0f, 10.0f);
    if (i % 3 == 0) y *= 1e-4f;
    if (i % 5 == 0) x *= 1e-4f;
    long double ref = std::atan2(static_cast<long double>(y), static_cast<long double>(x));
    worst = std::max(worst, static_cast<double>(std::fabs(rc::atan2(y, x) - ref)));
  }
  EXPECT_LE(worst, 2.4e-7);
}

TEST(Trig, Atan2SpecialCasesFollowC) {
  const float inf = std::numeric_limits<float>::infinity();
  for (float y : {0.0f, -0.0f, 1.0f, -1.0f, inf, -inf}) {
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f, inf, -inf}) {
      float ours = rc::atan2(y, x);
      float ref = std::atan2(y, x);
      EXPECT_NEAR(ours, ref, 2.4e-7f) << "atan2(" << y << ", " << x << ")";
      EXPECT_EQ(std::signbit(ours), std::signbit(ref)) << "atan2(" << y << ", " << x << ")";
    }
  }
}

TEST(Trig, RoundTripAngle) {
  for (float a = -3.1f; a < 3.1f; a += 0.01f) {
    rc::SinCos sc = rc::sincos(a);
    EXPECT_NEAR(rc::atan2(sc.sine, sc.cosine), a, 4e-7f);
  }
}

}  // namespace trig_test
