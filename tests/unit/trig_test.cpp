// Our own sin/cos/atan2 against long double std:: functions (the accuracy stated in trig.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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
