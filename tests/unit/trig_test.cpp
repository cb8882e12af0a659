// Our own sin/cos/atan2 against long double std:: functions (the accuracy stated in trig.h).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "physics/random.h"
#include "physics/trig.h"

namespace {

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

// The batch form (used for every turning body each step) gives the one-by-one bits, over
// every magnitude the reduction treats differently: small (no reduction), ordinary, past
// 2^52 / (2/pi) where every multiple is an integer already, past 2^63 where the quadrant can
// no longer be taken from a 64-bit integer, and the signed zeros.
TEST(Trig, BatchMatchesOneByOne) {
  rc::Random rng(7);
  std::vector<float> angles = {0.0f, -0.0f, 0.5f, -0.785f, 1e20f, -3.4e38f, 7.1e15f};
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::ldexp(1.0f, static_cast<int>(rng.below(130)) - 20);
    angles.push_back(rng.uniform(-scale, scale));
  }
  std::vector<rc::SinCos> batch(angles.size());
  rc::sincos(angles, batch);
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const rc::SinCos one = rc::sincos(angles[i]);
    ASSERT_EQ(std::bit_cast<std::uint32_t>(batch[i].sine), std::bit_cast<std::uint32_t>(one.sine))
        << angles[i];
    ASSERT_EQ(std::bit_cast<std::uint32_t>(batch[i].cosine),
              std::bit_cast<std::uint32_t>(one.cosine))
        << angles[i];
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

}  // namespace
