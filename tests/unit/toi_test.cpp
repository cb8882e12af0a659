// Swept circles, shape casts and time of impact (physics/toi.h): hand-worked cases, the
// far-apart robustness case of the issue (with the textbook quadratic shown to fail it), references
// found from the GJK distance alone (bisection along a linear cast, fine sampling along a rotating
// sweep), the states, and the same answers 1e4 m from the origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>

#include "physics/distance.h"
#include "physics/random.h"
#include "physics/toi.h"
#include "support/random_shapes.h"
#include "support/sweeps.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace toi_test {

using rc::Vec2;
using rc::testing::Kind;
using rc::testing::kSolidKinds;
using rc::testing::randomSweep;
using rc::testing::solidShape;
using rc::testing::SweepCase;

// The TOI tolerance of toi.h (Box2D's): surfaces stop within 0.25 * slop = 1.25 mm of the target.
constexpr float kTol = 0.25f * rc::kLinearSlop;

void expectVecNear(Vec2 got, Vec2 want, float tol, const std::string& what) {
  EXPECT_NEAR(got.x, want.x, tol) << what;
  EXPECT_NEAR(got.y, want.y, tol) << what;
}

float ulpOf(float x) {
  x = std::fabs(x);
  return std::nextafter(x, std::numeric_limits<float>::infinity()) - x;
}

// =============================================================================================
// Swept circles

TEST(SweptCircles, HeadOn) {
  // A (r 0.5) at rest at the origin; B (r 1) from (5, 0) moving (-4, 0). Touching when the centres
  // are 1.5 apart: 5 - 4 t = 1.5, t = 0.875. Normal A -> B is +x; the point is on A's surface.
  rc::CastOutput o = rc::sweptCircles({0, 0}, 0.5f, {0, 0}, {5, 0}, 1.0f, {-4, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.875f, 1e-6f);
  expectVecNear(o.normal, {1, 0}, 1e-6f, "normal");
  expectVecNear(o.point, {0.5f, 0}, 1e-6f, "point");

  // Both moving, radii 1 and 1: the gap 5 - 2 closes at 2 + 2 per unit t, t = 0.75. A is then at
  // (1.5, 0), B at (3.5, 0), the contact at (2.5, 0).
  o = rc::sweptCircles({0, 0}, 1.0f, {2, 0}, {5, 0}, 1.0f, {-2, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.75f, 1e-6f);
  expectVecNear(o.normal, {1, 0}, 1e-6f, "normal");
  expectVecNear(o.point, {2.5f, 0}, 1e-6f, "point");
}

TEST(SweptCircles, Oblique) {
  // A (r 1) at rest at the origin; B (r 1) from (4, 1) moving (-4, 0). B's centre runs along y = 1
  // and touches when x^2 + 1 = 2^2, x = sqrt(3): t = (4 - sqrt 3) / 4. Normal (sqrt 3, 1) / 2,
  // contact at A's centre + normal.
  const float s3 = std::sqrt(3.0f);
  rc::CastOutput o = rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {4, 1}, 1.0f, {-4, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, (4.0f - s3) / 4.0f, 1e-6f);
  expectVecNear(o.normal, {0.5f * s3, 0.5f}, 1e-6f, "normal");
  expectVecNear(o.point, {0.5f * s3, 0.5f}, 1e-6f, "point");

  // The same relative motion with both moving: A from (1, 1) by (1, 0), B from (5, 2) by (-3, 0).
  // Same fraction and normal; A is then at (1 + t, 1) and the point is on its surface.
  o = rc::sweptCircles({1, 1}, 1.0f, {1, 0}, {5, 2}, 1.0f, {-3, 0});
  ASSERT_TRUE(o.hit);
  float t = (4.0f - s3) / 4.0f;
  EXPECT_NEAR(o.fraction, t, 1e-6f);
  expectVecNear(o.normal, {0.5f * s3, 0.5f}, 1e-6f, "normal");
  expectVecNear(o.point, {1.0f + t + 0.5f * s3, 1.5f}, 1e-6f, "point");
}

TEST(SweptCircles, TouchingOrOverlappingAtStartHitsAtZero) {
  // Exactly touching: centres 1.5 apart, radii 1 and 0.5.
  rc::CastOutput o = rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {1.5f, 0}, 0.5f, {-1, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_EQ(o.fraction, 0.0f);
  expectVecNear(o.normal, {1, 0}, 1e-6f, "normal");
  expectVecNear(o.point, {1, 0}, 1e-6f, "point");
  // Touching and moving apart still reports the contact at 0.
  o = rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {1.5f, 0}, 0.5f, {1, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_EQ(o.fraction, 0.0f);
  // Overlapping: normal along the centres.
  o = rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {0.5f, 0.5f}, 0.5f, {3, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_EQ(o.fraction, 0.0f);
  expectVecNear(o.normal, {std::sqrt(0.5f), std::sqrt(0.5f)}, 1e-6f, "normal");
  // Concentric: some unit normal, never NaN.
  o = rc::sweptCircles({2, 3}, 1.0f, {1, 0}, {2, 3}, 0.5f, {0, 1});
  ASSERT_TRUE(o.hit);
  EXPECT_EQ(o.fraction, 0.0f);
  EXPECT_NEAR(rc::length(o.normal), 1.0f, 1e-6f);
  EXPECT_TRUE(rc::isFinite(o.point));
}

TEST(SweptCircles, MovingApartOrNotMovingNoHit) {
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {3, 0}, 1.0f, {1, 0}).hit);
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {-1, 0}, {3, 0}, 1.0f, {0, 0}).hit);
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 2}, {3, 0}, 1.0f, {0, 2}).hit);  // same motion
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {3, 0}, 1.0f, {0, 0}).hit);
  // Sideways: the centres only get farther apart.
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {3, 0}, 1.0f, {0, 5}).hit);
}

TEST(SweptCircles, PassingByNoHit) {
  // B runs along y = 2.5 past A; radii sum 2, closest approach 2.5.
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {4, 2.5f}, 1.0f, {-8, 0}).hit);
  // Just outside and just inside the grazing line y = 2.
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {4, 2.001f}, 1.0f, {-8, 0}).hit);
  rc::CastOutput o = rc::sweptCircles({0, 0}, 1.0f, {0, 0}, {4, 1.999f}, 1.0f, {-8, 0});
  ASSERT_TRUE(o.hit);
  // x^2 + 1.999^2 = 4: x = sqrt(0.003999) = 0.0632377; t = (4 - x) / 8.
  EXPECT_NEAR(o.fraction, (4.0f - 0.0632377f) / 8.0f, 2e-5f);
}

TEST(SweptCircles, HitJustAfterTheStepIsNoHit) {
  // Gap 5.01 - 2 closing at 3 per unit t: contact at t = 1.00333, after the step.
  EXPECT_FALSE(rc::sweptCircles({0, 0}, 1.0f, {2, 0}, {5.01f, 0}, 1.0f, {-1, 0}).hit);
  // Gap 4.99 - 2: t = 0.99667, inside the step.
  rc::CastOutput o = rc::sweptCircles({0, 0}, 1.0f, {2, 0}, {4.99f, 0}, 1.0f, {-1, 0});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 2.99f / 3.0f, 1e-6f);
}

// ---------------------------------------------------------------------------------------------
// Far apart: the robustness case. Circles of radius 0.05 m start 1e2 to 1e6 radii apart (5 m to
// 50 km) and close in on each other so that they touch inside the step.

// The textbook solution, all in float: a t^2 + 2 b t + c = 0, a = v.v, b = d.v, c = d.d - R^2,
// smaller root t = (-b - sqrt(b^2 - a c)) / a. d.d and b^2 are ~(|d| / R)^2 times larger than the
// R^2 and a R^2 they must resolve, so far apart those digits are gone before the subtraction.
rc::CastOutput naiveSweptCircles(Vec2 centerA, float radiusA, Vec2 moveA, Vec2 centerB,
                                 float radiusB, Vec2 moveB) {
  rc::CastOutput out;
  Vec2 d = centerB - centerA, v = moveB - moveA;
  float radius = radiusA + radiusB;
  float a = rc::dot(v, v), b = rc::dot(d, v), c = rc::dot(d, d) - radius * radius;
  if (c <= 0.0f) {
    out.hit = true;
    out.fraction = 0.0f;
    out.normal = rc::normalize(d);
    out.point = rc::mulAdd(centerA, radiusA, out.normal);
    return out;
  }
  if (a == 0.0f || b >= 0.0f) return out;
  float disc = b * b - a * c;
  if (disc < 0.0f) return out;
  float t = (-b - std::sqrt(disc)) / a;
  if (t < 0.0f || t > 1.0f) return out;
  out.hit = true;
  out.fraction = t;
  out.normal = rc::normalize(rc::mulAdd(centerB, t, moveB) - rc::mulAdd(centerA, t, moveA));
  out.point = rc::mulAdd(rc::mulAdd(centerA, t, moveA), radiusA, out.normal);
  return out;
}

struct FarCase {
  Vec2 centerA, moveA, centerB, moveB;
  float radius = 0.05f;  // of each circle
  float separation = 0;  // |cB - cA| in float
  double radii = 0;      // the separation in radii
};

std::vector<FarCase> farCases(int n) {
  rc::Random rng(2024);
  std::vector<FarCase> cases;
  for (int i = 0; i < n; ++i) {
    FarCase c;
    c.radii = std::pow(10.0, 2.0 + 4.0 * rng.uniformDouble());  // log-uniform in [1e2, 1e6]
    rc::Rot dir = rc::Rot::fromAngle(rng.uniform(-rc::kPi, rc::kPi));
    Vec2 u{dir.c, dir.s};
    c.centerA = rng.inBox({-1, -1}, {1, 1});
    c.centerB = c.centerA + static_cast<float>(c.radii * c.radius) * u;
    c.moveA = rng.inBox({-2, -2}, {2, 2});
    // B (relative to A) heads for a point beside A's centre, at most 0.9 of the radii sum off the
    // line of centres (not grazing), and would pass it at t = 1 / s: the contact is inside [0, 1].
    float sumRadii = 2.0f * c.radius;
    Vec2 aim = c.centerA + (rng.uniform(-0.9f, 0.9f) * sumRadii) * rc::leftPerp(u);
    c.moveB = c.moveA + rng.uniform(1.1f, 3.0f) * (aim - c.centerB);
    c.separation = rc::length(c.centerB - c.centerA);
    cases.push_back(c);
  }
  return cases;
}

// Exact solution for the float inputs, in long double (64-bit significand): the differences of
// the float coordinates and their products are exact there, so this is the contact time of the
// circles as given, not as some float computation sees them.
long double exactFraction(const FarCase& c) {
  using LD = long double;
  LD dx = static_cast<LD>(c.centerB.x) - c.centerA.x,
     dy = static_cast<LD>(c.centerB.y) - c.centerA.y;
  LD vx = static_cast<LD>(c.moveB.x) - c.moveA.x, vy = static_cast<LD>(c.moveB.y) - c.moveA.y;
  LD r = 2.0L * c.radius;
  LD dist = std::sqrt(dx * dx + dy * dy);
  LD cc = (dist - r) * (dist + r);
  LD a = vx * vx + vy * vy, b = dx * vx + dy * vy, cr = dx * vy - dy * vx;
  LD disc = a * r * r - cr * cr;
  if (disc < 0 || b >= 0) return -1;
  return cc / (-b + std::sqrt(disc));
}

// Residual of the contact condition at fraction t: |(cB + t mB) - (cA + t mA)| - (rA + rB), in
// long double from the float inputs and the float t (products of two floats are exact there).
long double contactResidual(const FarCase& c, float t) {
  using LD = long double;
  LD x = (static_cast<LD>(c.centerB.x) + static_cast<LD>(t) * c.moveB.x) -
         (static_cast<LD>(c.centerA.x) + static_cast<LD>(t) * c.moveA.x);
  LD y = (static_cast<LD>(c.centerB.y) + static_cast<LD>(t) * c.moveB.y) -
         (static_cast<LD>(c.centerA.y) + static_cast<LD>(t) * c.moveA.y);
  return std::sqrt(x * x + y * y) - 2.0L * c.radius;
}

// Tolerance on the contact residual. The input positions are floats |d| apart, so each carries a
// rounding of up to half an ulp(|d|) per coordinate (cB = cA + d was rounded when it was made):
// a geometry specified to the user's intent is only known to ~ulp(|d|), and no float algorithm
// can do better than that against the exact solution of the float inputs either, because the
// returned float t is itself rounded (|v| * ulp(t) / 2 ~ ulp(|d|) / 2) and every float operation
// on d, v adds a relative 2^-24 of |d| or |v| t ~ ulp(|d|) / 2. Budget, in ulp(|d|): rounding
// of d = cB - cA (<= 0.7), of v = mB - mA times t (<= ~1: |v| t ~ |d|, but |v| may sit in a
// higher binade), the cross product d x v, whose two ~|d||v| products cancel down to ~|v| R
// (<= ~2 after division by |v|), and length, c, sqrt and the division (~1): about 5. We allow
// 8 ulp(|d|), plus 1e-3 R where ulp(|d|) is tiny (near 1e2 radii). Measured worst for
// rc::sweptCircles on these cases: 3.6 ulp(|d|) (printed by FarApartKeepsItsDigits).
double farTolerance(const FarCase& c) {
  return 1e-3 * (2.0 * c.radius) + 8.0 * ulpOf(c.separation);
}

constexpr int kFarCases = 4000;

TEST(SweptCircles, FarApartKeepsItsDigits) {
  std::vector<FarCase> cases = farCases(kFarCases);
  double worstUlps = 0, worstOverTol = 0;
  for (int i = 0; i < kFarCases; ++i) {
    const FarCase& c = cases[static_cast<size_t>(i)];
    rc::CastOutput o = rc::sweptCircles(c.centerA, c.radius, c.moveA, c.centerB, c.radius, c.moveB);
    long double exact = exactFraction(c);
    ASSERT_GT(exact, 0.0L) << i;
    ASSERT_LT(exact, 1.0L) << i;
    ASSERT_TRUE(o.hit) << "case " << i << " at " << c.radii << " radii";
    ASSERT_TRUE(rc::isFinite(o.point) && rc::isFinite(o.normal)) << i;
    double residual = std::fabs(static_cast<double>(contactResidual(c, o.fraction)));
    double tol = farTolerance(c);
    EXPECT_LE(residual, tol) << "case " << i << " at " << c.radii << " radii: t " << o.fraction
                             << " exact " << static_cast<double>(exact) << " residual " << residual;
    worstUlps = std::max(worstUlps, residual / ulpOf(c.separation));
    worstOverTol = std::max(worstOverTol, residual / tol);
    EXPECT_NEAR(rc::length(o.normal), 1.0f, 1e-5f) << i;
  }
  RecordProperty("worst_residual_ulps", std::to_string(worstUlps));
  std::printf("[ SweptCircles ] rc::sweptCircles worst residual %.3f ulp(|d|), %.3f of tolerance\n",
              worstUlps, worstOverTol);
}

TEST(SweptCircles, NaiveFormulaFailsTheSameCases) {
  // The same cases and tolerance: the test above has teeth only if the textbook formula fails it.
  std::vector<FarCase> cases = farCases(kFarCases);
  int failed = 0, noHit = 0;
  int perDecade[4] = {}, perDecadeFailed[4] = {};
  for (int i = 0; i < kFarCases; ++i) {
    const FarCase& c = cases[static_cast<size_t>(i)];
    rc::CastOutput o =
        naiveSweptCircles(c.centerA, c.radius, c.moveA, c.centerB, c.radius, c.moveB);
    int decade = std::clamp(static_cast<int>(std::log10(c.radii)) - 2, 0, 3);
    ++perDecade[decade];
    bool bad = !o.hit;
    if (o.hit) {
      double residual = std::fabs(static_cast<double>(contactResidual(c, o.fraction)));
      bad = !(residual <= farTolerance(c));
    } else {
      ++noHit;
    }
    if (bad) {
      ++failed;
      ++perDecadeFailed[decade];
    }
  }
  std::printf(
      "[ SweptCircles ] naive formula fails %d of %d (%d report no hit); per decade "
      "1e2/1e3/1e4/1e5: %d/%d %d/%d %d/%d %d/%d\n",
      failed, kFarCases, noHit, perDecadeFailed[0], perDecade[0], perDecadeFailed[1], perDecade[1],
      perDecadeFailed[2], perDecade[2], perDecadeFailed[3], perDecade[3]);
  // Clear majority: everything from ~1e3 radii on (three of the four decades).
  EXPECT_GT(failed, kFarCases * 2 / 3);
  // And it is not a strawman: near 1e2 radii it still passes.
  EXPECT_LT(perDecadeFailed[0], perDecade[0] / 2);
}

// =============================================================================================
// Shape casts: hand-worked

rc::ShapeProxy proxyOf(const rc::Shape& s) {
  return rc::makeProxy(s);
}

TEST(ShapeCast, CircleAgainstSegment) {
  // Circle r 0.5 from the origin by (4, 0) against the segment x = 3, |y| <= 1: the centre stops
  // at x = 2.5, t = 0.625. B's normal towards A is -x, the contact (3, 0).
  rc::CastOutput o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.5f)), {}, {4, 0},
                                   proxyOf(rc::makeSegment({3, -1}, {3, 1})), {});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.625f, kTol / 4.0f);
  expectVecNear(o.normal, {-1, 0}, 1e-5f, "normal");
  expectVecNear(o.point, {3, 0}, 1e-5f, "point");
}

TEST(ShapeCast, NegativeTargetAsksForOverlap) {
  // Circles r 0.5, A from (-3, 0) by (4, 0) against B at the origin, asked to overlap 5 mm: the
  // centres stop 0.995 apart, t = (3 - 0.995) / 4 = 0.50125, no later, at most the tolerance
  // (0.25 slop of motion) earlier. The point is on B's surface, the normal B's towards A.
  // (The surfaces' distance is 0 once they overlap: a cast measured on it never hit.)
  const rc::ShapeProxy circle = proxyOf(rc::makeCircle({}, 0.5f));
  for (float target : {-0.005f, -0.5f, -0.99f}) {
    rc::CastOutput o = rc::shapeCast(circle, {{-3, 0}, {}}, {4, 0}, circle, {}, target);
    ASSERT_TRUE(o.hit) << target;
    const float exact = (3.0f - (1.0f + target)) / 4.0f;
    EXPECT_LE(o.fraction, exact + 1e-6f) << target;
    EXPECT_GE(o.fraction, exact - kTol / 4.0f) << target;
    expectVecNear(o.normal, {-1, 0}, 1e-5f, "normal");
    expectVecNear(o.point, {-0.5f, 0}, 1e-5f, "point");
  }
}

TEST(ShapeCast, CircleAgainstBox) {
  // Circle r 0.5 from (-3, 0.2) by (4, 0) against the box |x|, |y| <= 1: the centre stops at
  // x = -1.5, t = 1.5 / 4 = 0.375. Normal -x, contact (-1, 0.2).
  rc::CastOutput o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.5f)), {{-3, 0.2f}, {}}, {4, 0},
                                   proxyOf(rc::makeBox(1, 1)), {});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.375f, kTol / 4.0f);
  expectVecNear(o.normal, {-1, 0}, 1e-5f, "normal");
  expectVecNear(o.point, {-1, 0.2f}, 1e-5f, "point");
  // The same box placed by a transform: moved to (10, 0), turned a quarter turn (a square is
  // symmetric under it), and the circle shifted with it.
  o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.5f)), {{7, 0.2f}, {}}, {4, 0},
                    proxyOf(rc::makeBox(1, 1)), {{10, 0}, rc::Rot::fromAngle(0.5f * rc::kPi)});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.375f, kTol / 4.0f);
  expectVecNear(o.point, {9, 0.2f}, 1e-5f, "point");
  // Missing the box: passes 0.1 above its top edge plus the radius.
  EXPECT_FALSE(rc::shapeCast(proxyOf(rc::makeCircle({}, 0.5f)), {{-3, 1.6f}, {}}, {6, 0},
                             proxyOf(rc::makeBox(1, 1)), {})
                   .hit);
}

TEST(ShapeCast, CircleAgainstPolygon) {
  // A square of half-width 1 turned 45 degrees: a diamond with vertices (+-sqrt 2, 0),
  // (0, +-sqrt 2) and its upper-left edge on the line (-x + y) / sqrt 2 = 1. Circle r 0.5 from
  // (-3, 3) by (3, -3), straight at the centre: it starts 3 sqrt 2 away and stops 1.5 away,
  // t = 1 - 1.5 / (3 sqrt 2). Normal (-1, 1) / sqrt 2, contact at that normal (the edge midpoint).
  rc::Polygon diamond = rc::makeOrientedBox(1, 1, {}, 0.25f * rc::kPi);
  rc::CastOutput o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.5f)), {{-3, 3}, {}}, {3, -3},
                                   proxyOf(diamond), {});
  ASSERT_TRUE(o.hit);
  const float h = std::sqrt(0.5f);
  const float distance = 3.0f * std::sqrt(2.0f);  // length of the translation
  EXPECT_NEAR(o.fraction, 1.0f - 1.5f / distance, kTol / distance);
  expectVecNear(o.normal, {-h, h}, 1e-4f, "normal");
  expectVecNear(o.point, {-h, h}, 1e-4f, "point");
  // A triangle hit on its apex: circle r 0.25 from (1, 5) straight down by 6 onto (1, 2). The
  // centre stops at y = 2.25, t = 2.75 / 6; normal +y.
  o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.25f)), {{1, 5}, {}}, {0, -6},
                    proxyOf(rc::makeTriangle({0, 0}, {2, 0}, {1, 2})), {});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 2.75f / 6.0f, kTol / 6.0f);
  expectVecNear(o.normal, {0, 1}, 1e-3f, "normal");
  expectVecNear(o.point, {1, 2}, 1e-4f, "point");
}

TEST(ShapeCast, CircleAgainstCapsule) {
  // Capsule (0, -1)-(0, 1) radius 0.5; circle r 0.25 from (3, 1.5) by (-4, 0) meets the upper cap:
  // |(x, 1.5) - (0, 1)| = 0.75 gives x = sqrt(0.3125) = 0.559017, t = (3 - 0.559017) / 4.
  // Normal from the cap centre to the circle centre: (0.559017, 0.5) / 0.75; contact on the cap.
  rc::CastOutput o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.25f)), {{3, 1.5f}, {}}, {-4, 0},
                                   proxyOf(rc::makeCapsule({0, -1}, {0, 1}, 0.5f)), {});
  ASSERT_TRUE(o.hit);
  const float x = std::sqrt(0.3125f);
  EXPECT_NEAR(o.fraction, (3.0f - x) / 4.0f, kTol / 4.0f);
  Vec2 n{x / 0.75f, 0.5f / 0.75f};
  expectVecNear(o.normal, n, 2e-3f, "normal");
  expectVecNear(o.point, Vec2{0, 1} + 0.5f * n, 2e-3f, "point");
  // Flat against the side: from (3, 0) the circle stops at x = 0.75, t = 2.25 / 4.
  o = rc::shapeCast(proxyOf(rc::makeCircle({}, 0.25f)), {{3, 0}, {}}, {-4, 0},
                    proxyOf(rc::makeCapsule({0, -1}, {0, 1}, 0.5f)), {});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 2.25f / 4.0f, kTol / 4.0f);
  expectVecNear(o.normal, {1, 0}, 1e-5f, "normal");
  expectVecNear(o.point, {0.5f, 0}, 1e-5f, "point");
}

TEST(ShapeCast, BoxAgainstBoxGivesTheFaceNormal) {
  // Two sharp boxes, face to face: A (half-width 0.5) from (-3, 0.25) by (4, 0) against B (half-
  // width 1) at the origin. A's right face x = -2.5 meets B's left face x = -1 after 1.5 m,
  // t = 0.375. B's normal towards A is -x; the contact lies on x = -1 where the faces overlap,
  // -0.25 <= y <= 0.75. Conservative advancement lands exactly on the contact here (one step,
  // gap / approach), so the cores touch and the normal must not come from the degenerate GJK
  // result there.
  rc::ShapeProxy a = proxyOf(rc::makeBox(0.5f, 0.5f)), b = proxyOf(rc::makeBox(1, 1));
  rc::CastOutput o = rc::shapeCast(a, {{-3, 0.25f}, {}}, {4, 0}, b, {});
  ASSERT_TRUE(o.hit);
  EXPECT_NEAR(o.fraction, 0.375f, kTol / 4.0f);
  expectVecNear(o.normal, {-1, 0}, 1e-5f, "normal");
  EXPECT_NEAR(o.point.x, -1.0f, 1e-5f);
  EXPECT_GE(o.point.y, -0.25f - 1e-5f);
  EXPECT_LE(o.point.y, 0.75f + 1e-5f);
}

TEST(ShapeCast, StartingInContactAndMovingAway) {
  rc::ShapeProxy circle = proxyOf(rc::makeCircle({}, 0.5f)), box = proxyOf(rc::makeBox(1, 1));
  // Overlapping at the start: hit at 0, whatever the direction.
  rc::CastOutput o = rc::shapeCast(circle, {{1.2f, 0}, {}}, {3, 0}, box, {});
  ASSERT_TRUE(o.hit);
  EXPECT_EQ(o.fraction, 0.0f);
  EXPECT_NEAR(rc::length(o.normal), 1.0f, 1e-5f);
  // Apart and moving away, or sliding past.
  EXPECT_FALSE(rc::shapeCast(circle, {{2, 0}, {}}, {3, 0}, box, {}).hit);
  EXPECT_FALSE(rc::shapeCast(circle, {{-2, 2}, {}}, {4, 0}, box, {}).hit);
  // Short of the box: stops 0.5 m before it.
  EXPECT_FALSE(rc::shapeCast(circle, {{-4, 0}, {}}, {2, 0}, box, {}).hit);
}

// ---------------------------------------------------------------------------------------------
// Shape casts against a reference found by bisection on rc::shapeDistance.

struct CastCase {
  rc::ShapeProxy a, b;
  rc::Transform xfA, xfB;
  Vec2 translation;
};

// A starts 1.5 to 5 m from B and heads for a point near B, overshooting or falling short of it.
CastCase randomCast(rc::Random& rng, Kind ka, Kind kb) {
  CastCase c;
  c.a = proxyOf(solidShape(rng, ka));
  c.b = proxyOf(solidShape(rng, kb));
  c.xfB = rc::testing::randomTransform(rng, {0, 0}, 0.5f);
  rc::Rot dir = rc::Rot::fromAngle(rng.uniform(-rc::kPi, rc::kPi));
  c.xfA = {c.xfB.p + rng.uniform(1.5f, 5.0f) * Vec2{dir.c, dir.s},
           rc::Rot::fromAngle(rng.uniform(-rc::kPi, rc::kPi))};
  Vec2 aim = c.xfB.p + rng.inBox({-1.5f, -1.5f}, {1.5f, 1.5f});
  c.translation = rng.uniform(0.3f, 1.5f) * (aim - c.xfA.p);
  return c;
}

// Float slack on positions along the cast: coordinates up to ~10 m (ulps ~1e-6 m) and GJK
// distances good to ~1e-5 m; 1e-4 m covers both with room.
constexpr float kCastSlack = 1e-4f;

float castDistance(const CastCase& c, float t) {
  return rc::shapeDistance(c.a, {rc::mulAdd(c.xfA.p, t, c.translation), c.xfA.q}, c.b, c.xfB)
      .distance;
}

struct CastReference {
  float minDistance = 0;  // over t in [0, 1]
  float tMin = 0;         // where it is reached
  float tFirst = 2;       // first t with distance <= kTol (2: never)
  float tTouch = 2;       // first t with distance == 0 (touching or overlapping; 2: never)
};

// The distance from a convex set moving on a line to a fixed convex set is a convex function of t
// (it is the distance from a point on a line to their Minkowski difference). So each set
// {t : d(t) <= level} is an interval: golden-section search finds the minimum and bisection on
// [0, tMin] finds where d first drops to a level.
CastReference castReference(const CastCase& c) {
  CastReference r;
  auto d = [&](double t) { return castDistance(c, static_cast<float>(t)); };
  auto firstAtOrBelow = [&](float level, double hi) {
    double lo = 0;
    if (d(0) <= level) return 0.0f;
    for (int i = 0; i < 26; ++i) {  // 2^-26: below a float step of t near 1
      double mid = 0.5 * (lo + hi);
      (d(mid) <= level ? hi : lo) = mid;
    }
    return static_cast<float>(hi);
  };
  float d0 = d(0), d1 = d(1);
  if (d1 <= 0.0f) {
    r.minDistance = 0;
    r.tMin = 1;
  } else if (d0 <= 0.0f) {
    r.minDistance = 0;
    r.tMin = 0;
  } else {
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = 0, hi = 1, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    float f1 = d(x1), f2 = d(x2);
    // Stop early once a hit is found (a probe at distance 0) or once the distance is certainly
    // above kTol + kCastSlack on the whole bracket: it changes by at most |translation| per unit
    // t, and the probes are less than the bracket's width from any point of it.
    const float len = rc::length(c.translation);
    for (int i = 0; i < 36 && f1 > 0.0f && f2 > 0.0f; ++i) {
      if (std::min(f1, f2) - len * static_cast<float>(hi - lo) > kTol + kCastSlack) break;
      if (f1 <= f2) {
        hi = x2;
        x2 = x1;
        f2 = f1;
        x1 = hi - g * (hi - lo);
        f1 = d(x1);
      } else {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + g * (hi - lo);
        f2 = d(x2);
      }
    }
    r.minDistance = std::min({f1, f2, d0, d1});
    r.tMin = static_cast<float>(r.minDistance == d0   ? 0.0
                                : r.minDistance == d1 ? 1.0
                                : f1 <= f2            ? x1
                                                      : x2);
  }
  if (r.minDistance <= kTol) r.tFirst = firstAtOrBelow(kTol, r.tMin);
  if (r.minDistance <= 0.0f) r.tTouch = firstAtOrBelow(0.0f, r.tMin);
  return r;
}

// Separation of the two placed shapes along n (pointing from B towards A): how far A's rounded
// surface lies beyond B's along n. Negative when n does not separate them.
float separationAlong(const rc::ShapeProxy& a, const rc::Transform& xfA, const rc::ShapeProxy& b,
                      const rc::Transform& xfB, Vec2 n) {
  float minA = std::numeric_limits<float>::max(), maxB = -std::numeric_limits<float>::max();
  for (int i = 0; i < a.count; ++i)
    minA = std::min(minA, rc::dot(n, rc::apply(xfA, a.points[i])));
  for (int i = 0; i < b.count; ++i)
    maxB = std::max(maxB, rc::dot(n, rc::apply(xfB, b.points[i])));
  return (minA - a.radius) - (maxB + b.radius);
}

// 20,000 casts for each of the 16 ordered pairs of solid types (mover, fixed).
constexpr int kCastsPerPair = 20000;
constexpr int kOrderedPairs = 16;

CastCase randomCastNamed(rc::Random& rng, Kind mover, Kind fixed, std::string* what, int i) {
  *what = std::string(rc::testing::kindName(mover)) + " cast at " + rc::testing::kindName(fixed) +
          " case " + std::to_string(i);
  return randomCast(rng, mover, fixed);
}

TEST(ShapeCast, MatchesBisectionOnDistanceForEveryPair) {
  // 20,000 casts per ordered pair of the four solid types (polygons half sharp, half rounded).
  // shapeCast stops at the first t where the surfaces are within kTol. Against the reference:
  //  - hit whenever the shapes touch within the step, no hit when they never come within kTol
  //    (closest approach in (0, kTol]: either answer is right);
  //  - on a hit, the distance there is at most kTol, the fraction is not before the first t at
  //    distance kTol and not after the first contact (t at distance 0): it never tunnels;
  //  - the measure |t - tRef| * |translation| <= kTol + 1e-4 m, with tRef the first contact
  //    (distance 0, located by bisection to far below the tolerance), wherever the motion meets
  //    the surface head-on (see below; the oblique rest is counted and printed).
  rc::Random rng(77);
  int hits = 0, misses = 0, undecided = 0, measured = 0, overMeasure = 0;
  double worstHeadOn = 0, worstOblique = 0;
  for (int ia = 0; ia < 4; ++ia) {
    for (int ib = 0; ib < 4; ++ib) {
      for (int i = 0; i < kCastsPerPair; ++i) {
        std::string what;
        CastCase c = randomCastNamed(rng, kSolidKinds[ia], kSolidKinds[ib], &what, i);
        rc::CastOutput o = rc::shapeCast(c.a, c.xfA, c.translation, c.b, c.xfB);
        ASSERT_TRUE(rc::isFinite(o.point) && rc::isFinite(o.normal) && std::isfinite(o.fraction))
            << what;
        CastReference ref = castReference(c);
        float len = rc::length(c.translation);
        float slackT = kCastSlack / len;
        if (ref.minDistance <= 0.0f) {
          ASSERT_TRUE(o.hit) << what << ": touches at t " << ref.tTouch;
        } else if (ref.minDistance > kTol + kCastSlack) {
          ASSERT_FALSE(o.hit) << what << ": closest " << ref.minDistance << " at t " << ref.tMin
                              << " but hit at " << o.fraction;
        } else {
          ++undecided;
        }
        if (!o.hit) {
          ++misses;
          continue;
        }
        ++hits;
        ASSERT_GE(o.fraction, 0.0f) << what;
        ASSERT_LE(o.fraction, 1.0f) << what;
        float atHit = castDistance(c, o.fraction);
        EXPECT_LE(atHit, kTol + kCastSlack) << what << " t " << o.fraction;
        EXPECT_GE(o.fraction, ref.tFirst - slackT) << what << " first at kTol " << ref.tFirst;
        if (ref.minDistance > 0.0f) continue;
        EXPECT_LE(o.fraction, ref.tTouch + slackT) << what << " contact at " << ref.tTouch;
        double measure = std::fabs(static_cast<double>(o.fraction) - ref.tTouch) * len;
        ++measured;
        // The measure holds along the motion only where the motion meets the surface
        // head-on: the band between distance kTol and contact is kTol / cos(angle) long along an
        // oblique motion, and a correct cast may stop anywhere in it. The angle is that of the
        // closest features, which may change between the hit and the contact (a corner sliding
        // onto a face), so it is taken at both ends. Asserted for cos >= 0.95 at both
        // (kTol / 0.95 < kTol + 1e-4), counted for the rest.
        auto cosineAt = [&](float t) {
          Vec2 n =
              rc::shapeDistance(c.a, {rc::mulAdd(c.xfA.p, t, c.translation), c.xfA.q}, c.b, c.xfB)
                  .normal;
          return n == Vec2{} ? 1.0f : rc::dot(c.translation, n) / len;
        };
        float nearTouch = std::max(o.fraction, ref.tTouch - 2.0f * slackT);
        float cosine = std::min(cosineAt(o.fraction), cosineAt(nearTouch));
        if (measure > kTol + kCastSlack) ++overMeasure;
        if (cosine >= 0.95f) {
          EXPECT_LE(measure, kTol + kCastSlack)
              << what << " t " << o.fraction << " contact " << ref.tTouch << " |translation| "
              << len << " distance at t " << atHit;
          worstHeadOn = std::max(worstHeadOn, measure);
        } else {
          worstOblique = std::max(worstOblique, measure);
        }
      }
    }
  }
  std::printf(
      "[ ShapeCast ] %d hits, %d misses, %d undecided (closest approach in (0, kTol]); "
      "|t - contact| * |translation|: worst %.3g m head-on, %.3g m oblique; %d of %d "
      "touching hits over kTol + 1e-4, all oblique\n",
      hits, misses, undecided, worstHeadOn, worstOblique, overMeasure, measured);
  EXPECT_GT(hits, kOrderedPairs * kCastsPerPair / 4);
  EXPECT_GT(misses, kOrderedPairs * kCastsPerPair / 10);
}

TEST(ShapeCast, NormalSeparatesTheShapesAtTheHit) {
  // The same casts. At the hit the normal (B's surface normal, towards A) must be a unit vector
  // that separates the shapes to within the float slack: for the normal of the closest features
  // the separation along it is the distance itself, in [0, kTol]; a wrong direction shows up as a
  // deep negative separation. (Near-tangent hits reported just past the closest approach may have
  // A already moving away along the normal; that is within the contract, so not checked.)
  rc::Random rng(77);
  int bad = 0, hits = 0;
  std::string first;
  for (int ia = 0; ia < 4; ++ia) {
    for (int ib = 0; ib < 4; ++ib) {
      int badHere = 0;
      for (int i = 0; i < kCastsPerPair; ++i) {
        std::string what;
        CastCase c = randomCastNamed(rng, kSolidKinds[ia], kSolidKinds[ib], &what, i);
        rc::CastOutput o = rc::shapeCast(c.a, c.xfA, c.translation, c.b, c.xfB);
        if (!o.hit || o.fraction == 0.0f) continue;  // at 0 any direction out will do
        ++hits;
        rc::Transform at{rc::mulAdd(c.xfA.p, o.fraction, c.translation), c.xfA.q};
        float sep = separationAlong(c.a, at, c.b, c.xfB, o.normal);
        bool ok = std::fabs(rc::length(o.normal) - 1.0f) <= 1e-4f && sep >= -kCastSlack;
        if (!ok) {
          ++bad;
          ++badHere;
          if (first.empty())
            first = what + ": normal (" + std::to_string(o.normal.x) + ", " +
                    std::to_string(o.normal.y) + "), separation along it " + std::to_string(sep);
        }
      }
      if (badHere > 0)
        std::printf("[ ShapeCast ] %s cast at %s: %d bad normals\n",
                    rc::testing::kindName(kSolidKinds[ia]), rc::testing::kindName(kSolidKinds[ib]),
                    badHere);
    }
  }
  EXPECT_EQ(bad, 0) << "of " << hits << " hits; first: " << first;
}

// =============================================================================================
// Time of impact with rotation

// First of n + 1 uniform samples t = i / n at which the distance is below `level` (2: none).
float firstSampleBelow(const SweepCase& c, float level, int n) {
  for (int i = 0; i <= n; ++i) {
    float t = static_cast<float>(i) / static_cast<float>(n);
    if (c.distanceAt(t) < level) return t;
  }
  return 2.0f;
}

// The first crossing of `level` by the surface distance, to within kTol / 4 of motion after it.
float firstBelowLipschitz(const SweepCase& c, float level) {
  return rc::testing::firstBelowLipschitz(
      c, [&](float t) { return c.distanceAt(t); }, level, 0.25f * kTol);
}

// Checks a hand-worked sweep with the default target (kLinearSlop) against its closed-form time
// of impact: the closed form agrees with uniform sampling of the GJK distance (kTol / 4 of motion
// per sample), and timeOfImpact hits no later than either by more than kTol of motion, with the
// surfaces within kTol of the target.
rc::ToiOutput checkedHandSweep(const SweepCase& c, float closedForm) {
  const float m = c.motion();
  const int n = static_cast<int>(std::ceil(4.0f * m / kTol));
  const float sampled = firstSampleBelow(c, rc::kLinearSlop, n);
  EXPECT_NEAR(sampled, closedForm, 1.0f / static_cast<float>(n) + 1e-5f);
  rc::ToiOutput o = rc::timeOfImpact(c.a, c.sa, c.b, c.sb);
  EXPECT_EQ(o.state, rc::ToiState::hit);
  EXPECT_LE((o.fraction - sampled) * m, kTol) << o.fraction << " vs first sample " << sampled;
  EXPECT_LE((o.fraction - closedForm) * m, kTol) << o.fraction << " vs " << closedForm;
  float d = c.distanceAt(o.fraction);
  EXPECT_GE(d, rc::kLinearSlop - kTol);
  EXPECT_LE(d, rc::kLinearSlop + kTol);
  return o;
}

TEST(TimeOfImpact, SpinningBoxHitsWall) {
  // A bar of half-extents (1, 0.1) moves its centre from the origin to (2, 0) while turning from
  // 0 to 1 rad; a wall (half-extents (0.25, 5)) stands at x = 2.5, its face at x = 2.25. The bar's
  // rightmost point is at 2 t + cos t + 0.1 sin t, so with the default target (kLinearSlop) the
  // contact is the root of 2 t + cos t + 0.1 sin t = 2.25 - 0.005, t = 0.71097 (found below by
  // bisection on the closed form, and by sampling the GJK distance).
  SweepCase c{proxyOf(rc::makeBox(1.0f, 0.1f)), proxyOf(rc::makeBox(0.25f, 5.0f)),
              rc::Sweep{{}, {0, 0}, {2, 0}, 0.0f, 1.0f}, rc::Sweep{{}, {2.5f, 0}, {2.5f, 0}, 0, 0}};
  auto reach = [](double t) { return 2.0 * t + std::cos(t) + 0.1 * std::sin(t); };
  double lo = 0, hi = 1;
  for (int i = 0; i < 60; ++i)
    (reach(0.5 * (lo + hi)) < 2.25 - rc::kLinearSlop ? lo : hi) = 0.5 * (lo + hi);
  const float closedForm = static_cast<float>(lo);
  EXPECT_NEAR(closedForm, 0.71097f, 1e-4f);

  rc::ToiOutput o = checkedHandSweep(c, closedForm);
  if (o.state != rc::ToiState::hit) return;
  // The normal points from the bar to the wall, the point lies between them on the wall's face.
  expectVecNear(o.normal, {1, 0}, 1e-3f, "normal");
  EXPECT_NEAR(o.point.x, 2.25f - 0.5f * rc::kLinearSlop, kTol);
}

TEST(TimeOfImpact, RotatingCapsuleHitsCircle) {
  // A capsule (-1, 0)-(1, 0), radius 0.2, spins about its centre from 0 to 2 rad; a circle of
  // radius 0.3 rests at (0.6, 0.8), at polar angle phi = atan2(0.8, 0.6), 1 m from the centre.
  // The circle's centre is |sin(phi - a)| from the capsule's axis (its projection, cos(phi - a),
  // stays inside the segment), so the surfaces are kLinearSlop apart when
  // sin(phi - a) = 0.5 + kLinearSlop: a = phi - asin(0.505) = 0.92730 - 0.52938, t = a / 2 =
  // 0.19896.
  SweepCase c{proxyOf(rc::makeCapsule({-1, 0}, {1, 0}, 0.2f)),
              proxyOf(rc::makeCircle({0.6f, 0.8f}, 0.3f)), rc::Sweep{{}, {}, {}, 0.0f, 2.0f},
              rc::Sweep{}};
  const double phi = std::atan2(0.8, 0.6);
  const float closedForm = static_cast<float>(0.5 * (phi - std::asin(0.5 + rc::kLinearSlop)));
  EXPECT_NEAR(closedForm, 0.19896f, 1e-5f);
  rc::ToiOutput o = checkedHandSweep(c, closedForm);
  if (o.state != rc::ToiState::hit) return;
  // Normal from the capsule's axis towards the circle: perpendicular to the axis at angle 2 t.
  float a = 2.0f * o.fraction;
  expectVecNear(o.normal, {-std::sin(a), std::cos(a)}, 2e-3f, "normal");
}

TEST(TimeOfImpact, States) {
  rc::ShapeProxy box = proxyOf(rc::makeBox(0.5f, 0.5f));
  rc::ShapeProxy circle = proxyOf(rc::makeCircle({}, 0.5f));
  // Overlapped at t = 0: fraction 0, whatever the motion.
  rc::ToiOutput o = rc::timeOfImpact(box, rc::Sweep{{}, {0, 0}, {1, 0}, 0, 1}, box,
                                     rc::Sweep{{}, {0.8f, 0}, {0.8f, 0}, 0, 0});
  EXPECT_EQ(o.state, rc::ToiState::overlapped);
  EXPECT_EQ(o.fraction, 0.0f);
  // Exactly kLinearSlop apart at t = 0 and approaching: a hit at 0 (within the tolerance).
  o = rc::timeOfImpact(box, rc::Sweep{{}, {0, 0}, {1, 0}, 0, 0}, box,
                       rc::Sweep{{}, {1.005f, 0}, {1.005f, 0}, 0, 0});
  EXPECT_EQ(o.state, rc::ToiState::hit);
  EXPECT_EQ(o.fraction, 0.0f);
  // Moving apart, turning: separated, fraction tMax.
  o = rc::timeOfImpact(box, rc::Sweep{{}, {0, 0}, {-2, 0}, 0, 1}, circle,
                       rc::Sweep{{}, {2, 0}, {3, 1}, 0, 0});
  EXPECT_EQ(o.state, rc::ToiState::separated);
  EXPECT_EQ(o.fraction, 1.0f);
  // Passing by: the box slides 1 m above the circle, turning a little.
  o = rc::timeOfImpact(box, rc::Sweep{{}, {-3, 2}, {3, 2}, 0, 0.3f}, circle, rc::Sweep{});
  EXPECT_EQ(o.state, rc::ToiState::separated);
  // Not moving at all and apart.
  o = rc::timeOfImpact(box, rc::Sweep{{}, {0, 0}, {0, 0}, 0, 0}, circle,
                       rc::Sweep{{}, {3, 0}, {3, 0}, 0, 0});
  EXPECT_EQ(o.state, rc::ToiState::separated);
  // A hit after tMax: the box reaches the circle (gap 2 m at 4 m per unit t) at t ~0.5;
  // with tMax = 0.4 that is no hit, fraction tMax; with tMax = 0.6 it is.
  rc::Sweep moving{{}, {-3, 0}, {1, 0}, 0, 0};
  rc::Sweep still{{}, {0, 0}, {0, 0}, 0, 0};
  o = rc::timeOfImpact(box, moving, circle, still, 0.4f);
  EXPECT_EQ(o.state, rc::ToiState::separated);
  EXPECT_EQ(o.fraction, 0.4f);
  o = rc::timeOfImpact(box, moving, circle, still, 0.6f);
  EXPECT_EQ(o.state, rc::ToiState::hit);
  EXPECT_NEAR(o.fraction, (2.0f - rc::kLinearSlop) / 4.0f, kTol / 4.0f);
  // Degenerate inputs never give NaN: concentric circles, coincident boxes, zero motion.
  for (const rc::ShapeProxy& p : {box, circle}) {
    o = rc::timeOfImpact(p, still, p, still);
    EXPECT_EQ(o.state, rc::ToiState::overlapped);
    EXPECT_TRUE(rc::isFinite(o.point) && rc::isFinite(o.normal) && std::isfinite(o.fraction));
  }
}

constexpr int kSweepsPerPair = 1000;

TEST(TimeOfImpact, RandomSweepsMatchSampledDistance) {
  // 1,000 sweeps per ordered pair of the four solid types, against the first time the sampled GJK
  // distance drops below the target (firstBelowLipschitz). A hit must not come later than that by
  // more than kTol of motion and must be within kTol of the target; separated must mean the
  // distance never drops below target - kTol; overlapped must mean it starts there.
  rc::Random rng(91);
  int hits = 0, separated = 0, overlapped = 0, failed = 0, total = 0;
  double worstLate = -1;
  for (Kind ka : kSolidKinds) {
    for (Kind kb : kSolidKinds) {
      for (int i = 0; i < kSweepsPerPair; ++i) {
        SweepCase c = randomSweep(rng, ka, kb);
        std::string what = std::string(rc::testing::kindName(ka)) + " vs " +
                           rc::testing::kindName(kb) + " case " + std::to_string(i);
        ++total;
        const float target = rc::kLinearSlop, m = c.motion();
        rc::ToiOutput o = rc::timeOfImpact(c.a, c.sa, c.b, c.sb);
        ASSERT_TRUE(rc::isFinite(o.point) && rc::isFinite(o.normal) && std::isfinite(o.fraction))
            << what;
        ASSERT_GE(o.fraction, 0.0f) << what;
        ASSERT_LE(o.fraction, 1.0f) << what;
        float first = firstBelowLipschitz(c, target);
        float d0 = c.distanceAt(0);
        switch (o.state) {
          case rc::ToiState::overlapped:
            ++overlapped;
            EXPECT_LT(d0, target) << what;
            break;
          case rc::ToiState::hit: {
            ++hits;
            float d = c.distanceAt(o.fraction);
            EXPECT_GE(d, target - kTol) << what << " t " << o.fraction;
            EXPECT_LE(d, target + kTol) << what << " t " << o.fraction;
            double late = (static_cast<double>(o.fraction) - first) * m;
            EXPECT_LE(late, kTol) << what << " t " << o.fraction << " first sample " << first;
            worstLate = std::max(worstLate, late);
            EXPECT_NEAR(rc::length(o.normal), 1.0f, 1e-3f) << what;
            break;
          }
          case rc::ToiState::separated:
            ++separated;
            EXPECT_EQ(o.fraction, 1.0f) << what;
            EXPECT_EQ(firstBelowLipschitz(c, target - kTol), 2.0f)
                << what << ": below target - kTol at " << firstBelowLipschitz(c, target - kTol);
            break;
          case rc::ToiState::failed:
            ++failed;
            // A safe time: not past the first contact.
            EXPECT_LE((static_cast<double>(o.fraction) - first) * m, kTol) << what;
            break;
        }
      }
    }
  }
  std::printf(
      "[ TimeOfImpact ] %d sweeps: %d hits, %d separated, %d overlapped, %d failed; "
      "latest hit %.3g m of motion after the first sample below target\n",
      total, hits, separated, overlapped, failed, worstLate);
  EXPECT_GT(hits, total / 4);
  EXPECT_GT(separated, total / 10);
  EXPECT_LE(failed, total / 100);
}

// =============================================================================================
// Far from the origin

// Rounds to the 2^-10 grid, so that adding 10000 (where a float has exactly 2^-10 m resolution)
// is exact.
Vec2 onGrid(Vec2 p) {
  return {std::round(p.x * 1024.0f) / 1024.0f, std::round(p.y * 1024.0f) / 1024.0f};
}
const Vec2 kFar{10000.0f, -10000.0f};
// One ulp of a coordinate near 1e4 (2^-10 m). A position computed there (A's position along the
// cast; a sweep's centre, then minus the rotated local centre) is rounded to half an ulp per
// coordinate at each step; the relative position of the two shapes, on which the distance
// depends, is then off by at most 2 ulp per coordinate, 2 sqrt(2) ulp = 2.8 mm in length.
const float kFarUlp = 1.0f / 1024.0f;
const float kFarError = 2.0f * std::sqrt(2.0f) * kFarUlp;

TEST(ShapeCast, SameAnswerFarFromOrigin) {
  // The random casts with both shapes moved by the same exact offset, 1e4 m away. The far answer
  // must be a correct answer to the problem at the origin, to within kFarError: the distance
  // there at most kTol + kFarError, and where the motion meets the surface head-on (as in
  // MatchesBisectionOnDistanceForEveryPair) the fractions within (kTol + kFarError) /
  // |translation|. Hit or no hit may differ only where one of the two is near tangent (closest
  // approach in (0, kTol + kFarError]).
  rc::Random rng(55);
  int both = 0, mismatched = 0;
  double worstHeadOn = 0, worst = 0;
  for (Kind ka : kSolidKinds) {
    for (Kind kb : kSolidKinds) {
      for (int i = 0; i < 500; ++i) {
        CastCase c = randomCast(rng, ka, kb);
        c.xfA.p = onGrid(c.xfA.p);
        c.xfB.p = onGrid(c.xfB.p);
        CastCase f = c;
        f.xfA.p = c.xfA.p + kFar;
        f.xfB.p = c.xfB.p + kFar;
        ASSERT_EQ(f.xfA.p - kFar, c.xfA.p);  // the offset is exact
        ASSERT_EQ(f.xfB.p - kFar, c.xfB.p);
        std::string what = std::string(rc::testing::kindName(ka)) + " cast at " +
                           rc::testing::kindName(kb) + " case " + std::to_string(i);
        rc::CastOutput o = rc::shapeCast(c.a, c.xfA, c.translation, c.b, c.xfB);
        rc::CastOutput g = rc::shapeCast(f.a, f.xfA, f.translation, f.b, f.xfB);
        ASSERT_TRUE(rc::isFinite(g.point) && rc::isFinite(g.normal) && std::isfinite(g.fraction))
            << what;
        if (o.hit != g.hit) {
          ++mismatched;
          float nearOrigin = castReference(c).minDistance, nearFar = castReference(f).minDistance;
          auto tangent = [](float m) { return m > 0.0f && m <= kTol + kFarError; };
          EXPECT_TRUE(tangent(nearOrigin) || tangent(nearFar))
              << what << ": hit " << o.hit << " at the origin, " << g.hit << " far; closest "
              << nearOrigin << " and " << nearFar;
          continue;
        }
        if (!o.hit) continue;
        ++both;
        float len = rc::length(c.translation);
        double measure = std::fabs(static_cast<double>(o.fraction) - g.fraction) * len;
        EXPECT_LE(castDistance(c, g.fraction), kTol + kFarError) << what;
        Vec2 n = rc::shapeDistance(c.a, {rc::mulAdd(c.xfA.p, o.fraction, c.translation), c.xfA.q},
                                   c.b, c.xfB)
                     .normal;
        if (n == Vec2{} || rc::dot(c.translation, n) >= 0.95f * len) {
          EXPECT_LE(measure, kTol + kFarError) << what;
          worstHeadOn = std::max(worstHeadOn, measure);
        }
        worst = std::max(worst, measure);
      }
    }
  }
  std::printf(
      "[ ShapeCast ] 1e4 m away: %d both hit, %d hit/miss differences (near tangent); "
      "|t - t_far| * |translation| worst %.3g m head-on, %.3g m overall\n",
      both, mismatched, worstHeadOn, worst);
  EXPECT_LE(mismatched, 16 * 500 / 200);
}

TEST(TimeOfImpact, SameAnswerFarFromOrigin) {
  // The random sweeps with every centre moved by the same exact offset, 1e4 m away. The far
  // fraction must be a correct time of impact for the problem at the origin to within kFarError:
  // the distance there within target +- (kTol + kFarError), and never past a deeper contact. (In
  // time the two may differ by more than the band in distance where the approach is slow next to
  // the motion bound, as near tangency; that measure is printed.) States may differ only near
  // tangency (the separated one never comes within kFarError + kTol below the target) or where
  // the start distance is within kFarError of the overlap threshold.
  rc::Random rng(56);
  const float target = rc::kLinearSlop;
  int both = 0, mismatched = 0;
  double worst = 0;
  for (Kind ka : kSolidKinds) {
    for (Kind kb : kSolidKinds) {
      for (int i = 0; i < 500; ++i) {
        SweepCase c = randomSweep(rng, ka, kb);
        c.sa.c1 = onGrid(c.sa.c1);
        c.sa.c2 = onGrid(c.sa.c2);
        c.sb.c1 = onGrid(c.sb.c1);
        c.sb.c2 = onGrid(c.sb.c2);
        SweepCase f = c;
        f.sa.c1 += kFar;
        f.sa.c2 += kFar;
        f.sb.c1 += kFar;
        f.sb.c2 += kFar;
        std::string what = std::string(rc::testing::kindName(ka)) + " vs " +
                           rc::testing::kindName(kb) + " case " + std::to_string(i);
        rc::ToiOutput o = rc::timeOfImpact(c.a, c.sa, c.b, c.sb);
        rc::ToiOutput g = rc::timeOfImpact(f.a, f.sa, f.b, f.sb);
        ASSERT_TRUE(rc::isFinite(g.point) && rc::isFinite(g.normal) && std::isfinite(g.fraction))
            << what;
        const float m = c.motion();
        if (g.state == rc::ToiState::hit) {
          float d = c.distanceAt(g.fraction);
          EXPECT_GE(d, target - kTol - kFarError) << what;
          EXPECT_LE(d, target + kTol + kFarError) << what;
          // No tunnelling: at the origin the shapes do not get deeper than the band before it.
          EXPECT_LE(g.fraction, firstBelowLipschitz(c, target - kTol - kFarError)) << what;
        }
        if (o.state != g.state) {
          ++mismatched;
          bool separatedVsHit =
              (o.state == rc::ToiState::separated) != (g.state == rc::ToiState::separated);
          if (separatedVsHit) {
            EXPECT_EQ(firstBelowLipschitz(c, target - kTol - kFarError), 2.0f) << what;
          } else {
            EXPECT_NEAR(c.distanceAt(0), target - kTol, kFarError) << what;
          }
          continue;
        }
        if (o.state != rc::ToiState::hit) continue;
        ++both;
        worst = std::max(worst, std::fabs(static_cast<double>(o.fraction) - g.fraction) * m);
      }
    }
  }
  std::printf(
      "[ TimeOfImpact ] 1e4 m away: %d both hit, %d state differences (near tangent); "
      "|t - t_far| * motion worst %.3g m\n",
      both, mismatched, worst);
  EXPECT_LE(mismatched, 16 * 500 / 200);
}

}  // namespace toi_test
