// Ray casts (physics/raycast.h): hand-worked cases for every shape type and for the documented
// rules (inside, along a segment, one-sided links, zero length, maxFraction), grazing rays, a
// brute-force cross-check against point containment, and robustness: far from the origin, very
// long rays, extreme magnitudes, NaN input.
//
// The brute-force reference marches along the ray with rc::containsPoint in steps of 1e-4 of its
// length and refines the first inside sample by bisection; it shares no code with the ray casts.
// A case whose hit decision changes when the ray moves by 1e-4 m (sideways, tilted by moving one
// end sideways, or either end moved along it) is "grazing": the two may disagree there.
// Everything else must agree, fractions within 1e-4 (of the ray length).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "physics/random.h"
#include "physics/raycast.h"
#include "support/random_shapes.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace raycast_test {

using rc::CastOutput;
using rc::RayCastInput;
using rc::Rot;
using rc::Shape;
using rc::Transform;
using rc::Vec2;

constexpr float kPi = 3.14159265358979f;

CastOutput cast(const Shape& s, Vec2 origin, Vec2 translation, float maxFraction = 1.0f,
                const Transform& xf = Transform{}) {
  return rc::rayCast(s, xf, RayCastInput{origin, translation, maxFraction});
}

#define EXPECT_VEC_NEAR(a, b, tol)  \
  do {                              \
    Vec2 a_ = (a), b_ = (b);        \
    EXPECT_NEAR(a_.x, b_.x, (tol)); \
    EXPECT_NEAR(a_.y, b_.y, (tol)); \
  } while (0)

// Checks a hit at the given fraction, point and normal.
void expectHit(const CastOutput& out, float fraction, Vec2 point, Vec2 normal, float tol = 1e-6f) {
  ASSERT_TRUE(out.hit);
  EXPECT_NEAR(out.fraction, fraction, tol);
  EXPECT_VEC_NEAR(out.point, point, tol);
  EXPECT_VEC_NEAR(out.normal, normal, tol);
}

// ---------------------------------------------------------------------------------------------
// Hand-worked cases.

TEST(RayCastCircle, HandWorked) {
  Shape c = rc::makeCircle({1.0f, 2.0f}, 0.5f);
  // Through the centre: enters at x = 0.5, 1.5 m along a 4 m ray.
  expectHit(cast(c, {-1.0f, 2.0f}, {4.0f, 0.0f}), 0.375f, {0.5f, 2.0f}, {-1.0f, 0.0f});
  // Offset by 0.3: half chord 0.4 (a 3-4-5 triangle), enters at x = 0.6.
  expectHit(cast(c, {-1.0f, 2.3f}, {4.0f, 0.0f}), 0.4f, {0.6f, 2.3f}, {-0.8f, 0.6f});
  // From above, straight down.
  expectHit(cast(c, {1.0f, 5.0f}, {0.0f, -5.0f}), 0.5f, {1.0f, 2.5f}, {0.0f, 1.0f});
  // Pointing away, passing beside, falling short.
  EXPECT_FALSE(cast(c, {3.0f, 2.0f}, {1.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(c, {-1.0f, 2.6f}, {4.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(c, {-1.0f, 2.0f}, {1.4f, 0.0f}).hit);
}

TEST(RayCastBox, HandWorked) {
  Shape b = rc::makeBox(2.0f, 1.0f);  // x in [-2, 2], y in [-1, 1]
  expectHit(cast(b, {-4.0f, 0.5f}, {8.0f, 0.0f}), 0.25f, {-2.0f, 0.5f}, {-1.0f, 0.0f});
  expectHit(cast(b, {1.0f, 3.0f}, {0.0f, -4.0f}), 0.5f, {1.0f, 1.0f}, {0.0f, 1.0f});
  expectHit(cast(b, {5.0f, -0.5f}, {-6.0f, 0.0f}), 0.5f, {2.0f, -0.5f}, {1.0f, 0.0f});
  expectHit(cast(b, {0.0f, -3.0f}, {0.0f, 4.0f}), 0.5f, {0.0f, -1.0f}, {0.0f, -1.0f});
  // Diagonal: crosses x = -2 at t = 0.25 (y = -2, outside), then y = -1 at t = 0.5.
  expectHit(cast(b, {-3.0f, -3.0f}, {4.0f, 4.0f}), 0.5f, {-1.0f, -1.0f}, {0.0f, -1.0f});
  EXPECT_FALSE(cast(b, {-3.0f, 1.5f}, {6.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(b, {-3.0f, 0.0f}, {0.9f, 0.0f}).hit);

  Shape off = rc::makeBox(0.5f, 0.25f, {3.0f, -1.0f});
  expectHit(cast(off, {3.25f, 1.0f}, {0.0f, -4.0f}), 0.4375f, {3.25f, -0.75f}, {0.0f, 1.0f});
}

TEST(RayCastPolygon, HandWorked) {
  // Right triangle (0,0) (4,0) (0,3); the hypotenuse 3x + 4y = 12 has normal (0.6, 0.8).
  Shape t = rc::makeTriangle({0.0f, 0.0f}, {4.0f, 0.0f}, {0.0f, 3.0f});
  expectHit(cast(t, {4.0f, 3.0f}, {-4.0f, -3.0f}), 0.5f, {2.0f, 1.5f}, {0.6f, 0.8f});
  expectHit(cast(t, {-1.0f, 1.0f}, {2.0f, 0.0f}), 0.5f, {0.0f, 1.0f}, {-1.0f, 0.0f});
  expectHit(cast(t, {1.0f, -2.0f}, {0.0f, 4.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, -1.0f});
  EXPECT_FALSE(cast(t, {3.0f, 3.0f}, {1.0f, -1.0f}).hit);
  EXPECT_FALSE(cast(t, {-1.0f, 4.0f}, {6.0f, -1.0f}).hit);  // passes above the apex (0, 3)

  // An oriented box rotated by 45 degrees: a diamond with vertices at distance sqrt(2).
  Shape d = rc::makeOrientedBox(1.0f, 1.0f, {}, 0.25f * kPi);
  float r2 = std::sqrt(2.0f);
  expectHit(cast(d, {-3.0f, -0.5f}, {6.0f, 0.0f}), (3.0f - (r2 - 0.5f)) / 6.0f, {0.5f - r2, -0.5f},
            {-std::sqrt(0.5f), -std::sqrt(0.5f)}, 2e-6f);
  expectHit(cast(d, {-3.0f, 0.5f}, {6.0f, 0.0f}), (3.0f - (r2 - 0.5f)) / 6.0f, {0.5f - r2, 0.5f},
            {-std::sqrt(0.5f), std::sqrt(0.5f)}, 2e-6f);
}

TEST(RayCastPolygon, RoundedHandWorked) {
  // A 2 x 2 square core rounded by 0.5: flat sides at distance 1.5, corner arcs about (+-1, +-1).
  Shape r = rc::makeOrientedBox(1.0f, 1.0f, {}, 0.0f, 0.5f);
  expectHit(cast(r, {-3.0f, 0.0f}, {6.0f, 0.0f}), 0.25f, {-1.5f, 0.0f}, {-1.0f, 0.0f});
  expectHit(cast(r, {0.3f, 4.0f}, {0.0f, -5.0f}), 0.5f, {0.3f, 1.5f}, {0.0f, 1.0f});
  // Into the corner arc about (1, 1) at height 1.3: 0.3 up, 0.4 across.
  expectHit(cast(r, {3.0f, 1.3f}, {-4.0f, 0.0f}), 0.4f, {1.4f, 1.3f}, {0.8f, 0.6f});
  // Diagonally at the corner: hits at (1, 1) + 0.5 (1, 1) / sqrt(2).
  float k = 0.5f * std::sqrt(0.5f);
  expectHit(cast(r, {3.0f, 3.0f}, {-2.0f, -2.0f}), (2.0f - k) / 2.0f, {1.0f + k, 1.0f + k},
            {std::sqrt(0.5f), std::sqrt(0.5f)}, 2e-6f);
  // From (1.45, 1.45), inside the bounding square [-1.5, 1.5]^2 but outside the arc, down.
  float dy = std::sqrt(0.25f - 0.45f * 0.45f);
  expectHit(cast(r, {1.45f, 1.45f}, {0.0f, -1.0f}), 0.45f - dy, {1.45f, 1.0f + dy},
            {0.9f, 2.0f * dy}, 2e-6f);
  // Lines x + y = c cut the corner of the bounding square [-1.5, 1.5]^2 for c < 3 but reach the
  // arc about (1, 1) only for c <= 2 + 0.5 sqrt(2) = 2.707.
  EXPECT_FALSE(cast(r, {3.0f, 0.0f}, {-3.0f, 3.0f}).hit);   // c = 3: the square's corner
  EXPECT_FALSE(cast(r, {2.85f, 0.0f}, {-3.0f, 3.0f}).hit);  // c = 2.85
  // c = 2.6: |(2.6 - 3t, 3t) - (1, 1)| = 0.5 gives 18 t^2 - 15.6 t + 3.31 = 0.
  double t = (15.6 - std::sqrt(15.6 * 15.6 - 72.0 * 3.31)) / 36.0;
  Vec2 p{static_cast<float>(2.6 - 3.0 * t), static_cast<float>(3.0 * t)};
  expectHit(cast(r, {2.6f, 0.0f}, {-3.0f, 3.0f}), static_cast<float>(t), p,
            2.0f * (p - Vec2{1.0f, 1.0f}), 2e-6f);
  // From the same point, running away: a miss.
  EXPECT_FALSE(cast(r, {1.45f, 1.45f}, {1.0f, 0.0f}).hit);
}

TEST(RayCastCapsule, HandWorked) {
  Shape c = rc::makeCapsule({-1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f);
  expectHit(cast(c, {0.0f, 2.0f}, {0.0f, -4.0f}), 0.375f, {0.0f, 0.5f}, {0.0f, 1.0f});
  expectHit(cast(c, {0.2f, -2.0f}, {0.0f, 3.0f}), 0.5f, {0.2f, -0.5f}, {0.0f, -1.0f});
  expectHit(cast(c, {-3.0f, 0.0f}, {4.0f, 0.0f}), 0.375f, {-1.5f, 0.0f}, {-1.0f, 0.0f});
  expectHit(cast(c, {3.0f, 0.3f}, {-4.0f, 0.0f}), 0.4f, {1.4f, 0.3f}, {0.8f, 0.6f});
  expectHit(cast(c, {-1.3f, -2.0f}, {0.0f, 2.0f}), 0.8f, {-1.3f, -0.4f}, {-0.6f, -0.8f});
  EXPECT_FALSE(cast(c, {-3.0f, 0.6f}, {6.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(c, {1.45f, 1.0f}, {0.0f, 2.0f}).hit);

  // Rotated capsule: a vertical one from (2, -1) to (2, 1).
  Shape v = rc::makeCapsule({2.0f, -1.0f}, {2.0f, 1.0f}, 0.25f);
  expectHit(cast(v, {0.0f, 0.5f}, {4.0f, 0.0f}), 0.4375f, {1.75f, 0.5f}, {-1.0f, 0.0f});
  expectHit(cast(v, {2.0f, 3.0f}, {0.0f, -4.0f}), 0.4375f, {2.0f, 1.25f}, {0.0f, 1.0f});
}

TEST(RayCastSegment, HandWorked) {
  // point1 -> point2 runs along +x, so its right side (its normal) is -y.
  Shape s = rc::makeSegment({0.0f, 0.0f}, {2.0f, 0.0f});
  expectHit(cast(s, {1.0f, -1.0f}, {0.0f, 2.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, -1.0f});
  expectHit(cast(s, {1.0f, 1.0f}, {0.0f, -2.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, 1.0f});
  expectHit(cast(s, {0.0f, 2.0f}, {2.0f, -4.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, 1.0f});
  // Endpoints count.
  expectHit(cast(s, {2.0f, -1.0f}, {0.0f, 2.0f}), 0.5f, {2.0f, 0.0f}, {0.0f, -1.0f});
  expectHit(cast(s, {0.0f, 1.0f}, {0.0f, -4.0f}), 0.25f, {0.0f, 0.0f}, {0.0f, 1.0f});
  // Past an end, short, pointing away.
  EXPECT_FALSE(cast(s, {2.01f, -1.0f}, {0.0f, 2.0f}).hit);
  EXPECT_FALSE(cast(s, {1.0f, -1.0f}, {0.0f, 0.9f}).hit);
  EXPECT_FALSE(cast(s, {1.0f, -1.0f}, {0.0f, -2.0f}).hit);
}

TEST(RayCastSegment, AlongTheSegmentNoHit) {
  Shape s = rc::makeSegment({0.0f, 0.0f}, {2.0f, 0.0f});
  EXPECT_FALSE(cast(s, {-1.0f, 0.0f}, {4.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(s, {3.0f, 0.0f}, {-4.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(s, {0.5f, 0.0f}, {1.0f, 0.0f}).hit);  // starting on it, running along it
  // The same for a diagonal segment, exactly representable: (1,1) -> (3,3).
  Shape d = rc::makeSegment({1.0f, 1.0f}, {3.0f, 3.0f});
  EXPECT_FALSE(cast(d, {0.0f, 0.0f}, {4.0f, 4.0f}).hit);
  EXPECT_FALSE(cast(d, {4.0f, 4.0f}, {-0.5f, -0.5f}, 10.0f).hit);
  // Chain links too, either sidedness.
  Vec2 pts[] = {{0.0f, 0.0f}, {2.0f, 0.0f}, {2.0f, 2.0f}};
  for (bool oneSided : {false, true}) {
    std::vector<rc::ChainSegment> chain = rc::makeChain(pts, false, oneSided);
    EXPECT_FALSE(cast(chain[0], {-1.0f, 0.0f}, {4.0f, 0.0f}).hit);
    EXPECT_FALSE(cast(chain[1], {2.0f, -1.0f}, {0.0f, 4.0f}).hit);
  }
}

TEST(RayCastChain, TwoSided) {
  Vec2 pts[] = {{0.0f, 0.0f}, {2.0f, 0.0f}, {2.0f, 2.0f}};
  std::vector<rc::ChainSegment> chain = rc::makeChain(pts, false, false);
  ASSERT_EQ(chain.size(), 2u);
  expectHit(cast(chain[0], {1.0f, -1.0f}, {0.0f, 2.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, -1.0f});
  expectHit(cast(chain[0], {1.0f, 1.0f}, {0.0f, -2.0f}), 0.5f, {1.0f, 0.0f}, {0.0f, 1.0f});
  expectHit(cast(chain[1], {3.0f, 1.0f}, {-2.0f, 0.0f}), 0.5f, {2.0f, 1.0f}, {1.0f, 0.0f});
  expectHit(cast(chain[1], {1.0f, 1.0f}, {2.0f, 0.0f}), 0.5f, {2.0f, 1.0f}, {-1.0f, 0.0f});
}

TEST(RayCastChain, OneSidedHitOnlyFromTheRight) {
  // A counter-clockwise square loop: the right side of every link is the outside.
  Vec2 pts[] = {{0.0f, 0.0f}, {4.0f, 0.0f}, {4.0f, 4.0f}, {0.0f, 4.0f}};
  std::vector<rc::ChainSegment> loop = rc::makeChain(pts, true, true);
  ASSERT_EQ(loop.size(), 4u);
  // From outside, into each side.
  expectHit(cast(loop[0], {2.0f, -2.0f}, {0.0f, 4.0f}), 0.5f, {2.0f, 0.0f}, {0.0f, -1.0f});
  expectHit(cast(loop[1], {6.0f, 1.0f}, {-4.0f, 0.0f}), 0.5f, {4.0f, 1.0f}, {1.0f, 0.0f});
  expectHit(cast(loop[2], {3.0f, 5.0f}, {0.0f, -2.0f}), 0.5f, {3.0f, 4.0f}, {0.0f, 1.0f});
  expectHit(cast(loop[3], {-1.0f, 3.0f}, {2.0f, 0.0f}), 0.5f, {0.0f, 3.0f}, {-1.0f, 0.0f});
  // From inside, out through each side: no hit.
  EXPECT_FALSE(cast(loop[0], {2.0f, 2.0f}, {0.0f, -4.0f}).hit);
  EXPECT_FALSE(cast(loop[1], {2.0f, 2.0f}, {4.0f, 0.0f}).hit);
  EXPECT_FALSE(cast(loop[2], {2.0f, 2.0f}, {0.0f, 4.0f}).hit);
  EXPECT_FALSE(cast(loop[3], {2.0f, 2.0f}, {-4.0f, 0.0f}).hit);
  // A ray from outside crossing the whole loop hits the near side only.
  Vec2 o{-1.0f, 1.0f}, d{6.0f, 0.0f};
  int hits = 0;
  for (const rc::ChainSegment& link : loop) {
    CastOutput out = cast(link, o, d);
    if (out.hit) {
      ++hits;
      EXPECT_VEC_NEAR(out.point, Vec2(0.0f, 1.0f), 1e-6f);
    }
  }
  EXPECT_EQ(hits, 1);
  // The segment overload with oneSided behaves the same.
  rc::Segment seg = rc::makeSegment({0.0f, 0.0f}, {2.0f, 0.0f});
  EXPECT_TRUE(rc::rayCast(seg, RayCastInput{{1.0f, -1.0f}, {0.0f, 2.0f}, 1.0f}, true).hit);
  EXPECT_FALSE(rc::rayCast(seg, RayCastInput{{1.0f, 1.0f}, {0.0f, -2.0f}, 1.0f}, true).hit);
}

// A ray starting inside a solid (boundary included) hits at fraction 0 at its origin, with the
// normal against its direction.
TEST(RayCastInside, HitsAtFractionZeroAgainstTheDirection) {
  Vec2 tri[] = {{-1.0f, -1.0f}, {2.0f, -1.0f}, {0.0f, 2.0f}};
  std::vector<Shape> shapes = {
      rc::makeCircle({0.1f, 0.0f}, 1.0f),
      rc::makeBox(1.0f, 0.5f),
      rc::makePolygon(tri),
      rc::makePolygon(tri, 0.25f),
      rc::makeOrientedBox(1.0f, 0.5f, {}, 0.3f),
      rc::makeCapsule({-1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f),
  };
  Transform xf{{5.0f, -3.0f}, Rot::fromAngle(0.7f)};
  for (const Shape& s : shapes) {
    for (Vec2 d : {Vec2{3.0f, 0.0f}, Vec2{0.0f, -0.5f}, Vec2{-3.0f, 4.0f}}) {
      Vec2 n = -rc::normalize(d);
      Vec2 o = rc::apply(xf, {0.05f, 0.1f});
      expectHit(cast(s, o, d, 1.0f, xf), 0.0f, o, n);
      // Unrotated, at the local origin.
      expectHit(cast(s, {0.05f, 0.1f}, d), 0.0f, {0.05f, 0.1f}, n);
    }
  }
  // On the boundary counts as inside.
  expectHit(cast(rc::makeCircle({}, 1.0f), {1.0f, 0.0f}, {2.0f, 0.0f}), 0.0f, {1.0f, 0.0f},
            {-1.0f, 0.0f});
  expectHit(cast(rc::makeBox(1.0f, 1.0f), {1.0f, 0.5f}, {0.0f, 2.0f}), 0.0f, {1.0f, 0.5f},
            {0.0f, -1.0f});
  expectHit(cast(rc::makeBox(1.0f, 1.0f), {-1.0f, -1.0f}, {-1.0f, 0.0f}), 0.0f, {-1.0f, -1.0f},
            {1.0f, 0.0f});
  expectHit(cast(rc::makeTriangle({0, 0}, {4, 0}, {0, 3}), {2.0f, 0.0f}, {0.0f, -1.0f}), 0.0f,
            {2.0f, 0.0f}, {0.0f, 1.0f});
  expectHit(cast(rc::makeCapsule({-1, 0}, {1, 0}, 0.5f), {0.0f, 0.5f}, {0.0f, 1.0f}), 0.0f,
            {0.0f, 0.5f}, {0.0f, -1.0f});
  // Even with maxFraction 0.
  EXPECT_TRUE(cast(rc::makeCircle({}, 1.0f), {0.0f, 0.0f}, {1.0f, 0.0f}, 0.0f).hit);
}

// A zero-length ray hits only what contains its origin, at fraction 0. It has no direction to
// oppose: the normal is finite, zero (what the casts report today) or of unit length.
TEST(RayCastZeroLength, HitsOnlyWhatContainsTheOrigin) {
  Vec2 tri[] = {{-1.0f, -1.0f}, {2.0f, -1.0f}, {0.0f, 2.0f}};
  std::vector<Shape> solids = {
      rc::makeCircle({}, 1.0f),
      rc::makeBox(1.0f, 0.5f),
      rc::makePolygon(tri),
      rc::makePolygon(tri, 0.25f),
      rc::makeOrientedBox(1.0f, 0.5f, {}, 0.3f),
      rc::makeCapsule({-1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f),
  };
  for (const Shape& s : solids) {
    CastOutput in = cast(s, {0.1f, 0.1f}, {0.0f, 0.0f});
    ASSERT_TRUE(in.hit);
    EXPECT_EQ(in.fraction, 0.0f);
    EXPECT_VEC_NEAR(in.point, Vec2(0.1f, 0.1f), 0.0f);
    EXPECT_TRUE(rc::isFinite(in.normal));
    float n = rc::length(in.normal);
    EXPECT_TRUE(n == 0.0f || std::fabs(n - 1.0f) < 1e-6f) << n;
    EXPECT_FALSE(cast(s, {5.0f, 0.1f}, {0.0f, 0.0f}).hit);
    EXPECT_FALSE(cast(s, {5.0f, 0.1f}, {0.0f, 0.0f}, 100.0f).hit);
  }
  // Segments and chain links contain nothing, even a point on them.
  EXPECT_FALSE(cast(rc::makeSegment({0, 0}, {2, 0}), {1.0f, 0.0f}, {0.0f, 0.0f}).hit);
  Vec2 pts[] = {{0.0f, 0.0f}, {2.0f, 0.0f}};
  EXPECT_FALSE(cast(rc::makeChain(pts, false, true)[0], {1.0f, 0.0f}, {0.0f, 0.0f}).hit);
  // maxFraction does not matter for a zero-length ray.
  EXPECT_TRUE(cast(rc::makeCircle({}, 1.0f), {0.0f, 0.0f}, {0.0f, 0.0f}, 5.0f).hit);
}

// maxFraction clips the ray (and may exceed 1 to lengthen it); hits exactly at maxFraction
// count.
TEST(RayCastMaxFraction, LimitsTheRay) {
  Vec2 tri[] = {{-1.0f, -1.0f}, {1.0f, -1.0f}, {0.0f, 1.0f}};
  std::vector<Shape> shapes = {
      rc::makeCircle({}, 1.0f),
      rc::makeBox(1.0f, 1.0f),
      rc::makePolygon(tri),
      rc::makePolygon(tri, 0.25f),
      rc::makeOrientedBox(1.0f, 1.0f, {}, 0.5f * kPi),
      rc::makeCapsule({0.0f, -1.0f}, {0.0f, 1.0f}, 1.0f),
      rc::makeSegment({-1.0f, -2.0f}, {-1.0f, 2.0f}),
  };
  Vec2 wall[] = {{-1.0f, 2.0f}, {-1.0f, -2.0f}};
  shapes.push_back(rc::makeChain(wall, false, true)[0]);  // running down: its right side is -x
  for (const Shape& s : shapes) {
    SCOPED_TRACE(rc::shapeTypeName(s.type));
    // Every shape but the triangles is first met at x = -1, half way along.
    CastOutput full = cast(s, {-5.0f, 0.0f}, {8.0f, 0.0f});
    ASSERT_TRUE(full.hit);
    float f = full.fraction;
    EXPECT_FALSE(cast(s, {-5.0f, 0.0f}, {8.0f, 0.0f}, f * 0.999f).hit);
    CastOutput atMax = cast(s, {-5.0f, 0.0f}, {8.0f, 0.0f}, f);
    ASSERT_TRUE(atMax.hit);
    EXPECT_EQ(atMax.fraction, f);
    // A quarter of the translation with maxFraction 4 reaches the same place.
    CastOutput longer = cast(s, {-5.0f, 0.0f}, {2.0f, 0.0f}, 4.0f);
    ASSERT_TRUE(longer.hit);
    EXPECT_NEAR(longer.fraction, 4.0f * f, 1e-6f);
    EXPECT_VEC_NEAR(longer.point, full.point, 1e-6f);
    EXPECT_FALSE(cast(s, {-5.0f, 0.0f}, {2.0f, 0.0f}, 1.0f).hit);
    EXPECT_FALSE(cast(s, {-5.0f, 0.0f}, {8.0f, 0.0f}, 0.0f).hit);
  }
}

// World-frame casts: the point is in the world frame and the normal rotated with the body.
TEST(RayCastTransform, WorldFrame) {
  Transform xf{{10.0f, 0.0f}, Rot::fromAngle(0.5f * kPi)};
  // The 4 x 2 box turned by 90 degrees spans x in [9, 11], y in [-2, 2].
  Shape b = rc::makeBox(2.0f, 1.0f);
  expectHit(cast(b, {10.5f, 5.0f}, {0.0f, -10.0f}, 1.0f, xf), 0.3f, {10.5f, 2.0f}, {0.0f, 1.0f},
            2e-6f);
  expectHit(cast(b, {0.0f, 1.0f}, {20.0f, 0.0f}, 1.0f, xf), 0.45f, {9.0f, 1.0f}, {-1.0f, 0.0f},
            2e-6f);
  // A segment from local (0,0) to (2,0) becomes (10,0) -> (10,2); its right side is +x.
  Shape s = rc::makeSegment({0.0f, 0.0f}, {2.0f, 0.0f});
  expectHit(cast(s, {12.0f, 1.0f}, {-4.0f, 0.0f}, 1.0f, xf), 0.5f, {10.0f, 1.0f}, {1.0f, 0.0f},
            2e-6f);
  expectHit(cast(s, {8.0f, 1.0f}, {4.0f, 0.0f}, 1.0f, xf), 0.5f, {10.0f, 1.0f}, {-1.0f, 0.0f},
            2e-6f);
  // A circle off the body origin moves with the body.
  Shape c = rc::makeCircle({1.0f, 0.0f}, 0.5f);  // world centre (10, 1)
  expectHit(cast(c, {10.0f, 4.0f}, {0.0f, -4.0f}, 1.0f, xf), 0.625f, {10.0f, 1.5f}, {0.0f, 1.0f},
            2e-6f);
}

// ---------------------------------------------------------------------------------------------
// Exact references in double precision for the grazing and robustness tests.

struct DVec {
  double x, y;
};
DVec toD(Vec2 v) {
  return {v.x, v.y};
}
struct Exact {
  bool hit = false;
  double t = 0.0;  // fraction
};

// Entry of the ray o + t d, t in [0, tMax], into the disc (c, r); origin outside.
Exact exactCircle(DVec c, double r, DVec o, DVec d, double tMax) {
  double a = d.x * d.x + d.y * d.y;
  double sx = c.x - o.x, sy = c.y - o.y;
  double tc = (sx * d.x + sy * d.y) / a;
  double px = sx - tc * d.x, py = sy - tc * d.y;
  double h2 = (r * r - (px * px + py * py)) / a;
  if (h2 < 0.0) return {};
  double t = tc - std::sqrt(h2);
  if (t < 0.0 || t > tMax) return {};
  return {true, t};
}

// Entry of the ray into the convex polygon with counter-clockwise vertices v; origin outside.
Exact exactPolygon(const std::vector<DVec>& v, DVec o, DVec d, double tMax) {
  double lower = 0.0, upper = tMax;
  bool entered = false;
  size_t n = v.size();
  for (size_t i = 0; i < n; ++i) {
    DVec a = v[i], b = v[(i + 1) % n];
    DVec nrm{b.y - a.y, a.x - b.x};  // outward for counter-clockwise order
    double num = nrm.x * (a.x - o.x) + nrm.y * (a.y - o.y);
    double den = nrm.x * d.x + nrm.y * d.y;
    if (den == 0.0) {
      if (num < 0.0) return {};
    } else if (den < 0.0) {
      if (num / den > lower) {
        lower = num / den;
        entered = true;
      }
    } else {
      upper = std::min(upper, num / den);
    }
    if (upper < lower) return {};
  }
  return {entered, lower};
}

std::vector<DVec> worldVertices(const rc::Polygon& p, const Transform& xf) {
  std::vector<DVec> out;
  for (int i = 0; i < p.count; ++i) {
    DVec v = toD(p.vertices[i]);
    out.push_back({static_cast<double>(xf.p.x) + xf.q.c * v.x - xf.q.s * v.y,
                   static_cast<double>(xf.p.y) + xf.q.s * v.x + xf.q.c * v.y});
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Grazing rays.

TEST(RayCastGrazing, CircleTangentHandWorked) {
  Shape c = rc::makeCircle({}, 1.0f);
  for (float delta : {1e-5f, 1e-4f, 1e-3f, 0.1f}) {
    SCOPED_TRACE(delta);
    EXPECT_FALSE(cast(c, {-3.0f, 1.0f + delta}, {6.0f, 0.0f}).hit);
    EXPECT_FALSE(cast(c, {-3.0f, -1.0f - delta}, {6.0f, 0.0f}).hit);
    EXPECT_FALSE(cast(c, {1.0f + delta, 3.0f}, {0.0f, -6.0f}).hit);
    float y = 1.0f - delta;
    double x = std::sqrt(1.0 - static_cast<double>(y) * y);
    CastOutput out = cast(c, {-3.0f, y}, {6.0f, 0.0f});
    ASSERT_TRUE(out.hit);
    EXPECT_NEAR(out.fraction, (3.0 - x) / 6.0, 2e-6);
    EXPECT_NEAR(out.normal.x, -x, 1e-4);
    EXPECT_NEAR(out.normal.y, y, 1e-6);
  }
  // Exactly tangent counts as touching (the boundary is part of the shape).
  CastOutput t = cast(c, {-3.0f, 1.0f}, {6.0f, 0.0f});
  ASSERT_TRUE(t.hit);
  EXPECT_NEAR(t.fraction, 0.5f, 1e-6f);
  EXPECT_VEC_NEAR(t.normal, Vec2(0.0f, 1.0f), 1e-6f);
}

TEST(RayCastGrazing, CircleTangentRandom) {
  rc::Random rng(2001);
  int hits = 0, misses = 0;
  for (int i = 0; i < 4000; ++i) {
    Vec2 center = rng.inBox({-8.0f, -8.0f}, {8.0f, 8.0f});
    float r = rng.uniform(0.05f, 3.0f);
    Vec2 dir = rc::normalize(rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}));
    if (dir == Vec2{}) continue;
    // Offset from tangency by 1e-5 to 1e-3 m, to either side.
    float delta =
        std::pow(10.0f, rng.uniform(-5.0f, -3.0f)) * (rng.uniform() < 0.5f ? -1.0f : 1.0f);
    float back = rng.uniform(0.01f, 6.0f) + r;
    Vec2 o = center - back * dir + (r + delta) * rc::leftPerp(dir);
    Vec2 d = rng.uniform(1.2f, 3.0f) * back * dir;
    // Decide from the float inputs in double precision.
    DVec od = toD(o), dd = toD(d), cd = toD(center);
    double len = std::sqrt(dd.x * dd.x + dd.y * dd.y);
    double dist = std::fabs(((cd.x - od.x) * dd.y - (cd.y - od.y) * dd.x) / len);
    if (std::fabs(dist - r) < 1e-5) continue;  // within 1e-5 of tangency: either answer
    bool expectHitHere = dist < r;
    CastOutput out = cast(rc::makeCircle(center, r), o, d);
    ASSERT_EQ(out.hit, expectHitHere) << "case " << i << " dist - r = " << dist - r;
    if (out.hit) {
      ++hits;
      Exact ex = exactCircle(cd, r, od, dd, 1.0);
      ASSERT_TRUE(ex.hit);
      EXPECT_NEAR(out.fraction * len, ex.t * len, 2e-4) << "case " << i;
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 1500);
  EXPECT_GT(misses, 1500);
}

TEST(RayCastGrazing, BoxEdgesAndCorners) {
  Shape b = rc::makeBox(2.0f, 1.0f, {0.5f, -0.25f});  // x in [-1.5, 2.5], y in [-1.25, 0.75]
  // Along the top edge's line: exactly on it touches (at the left corner); just above misses;
  // just below enters through the left side.
  expectHit(cast(b, {-3.0f, 0.75f}, {6.0f, 0.0f}), 0.25f, {-1.5f, 0.75f}, {-1.0f, 0.0f});
  for (float delta : {1e-5f, 1e-3f}) {
    EXPECT_FALSE(cast(b, {-3.0f, 0.75f + delta}, {6.0f, 0.0f}).hit);
    EXPECT_FALSE(cast(b, {2.5f + delta, 3.0f}, {0.0f, -6.0f}).hit);
    EXPECT_TRUE(cast(b, {-3.0f, 0.75f - delta}, {6.0f, 0.0f}).hit);
    expectHit(cast(b, {2.5f - delta, 3.0f}, {0.0f, -6.0f}), 2.25f / 6.0f, {2.5f - delta, 0.75f},
              {0.0f, 1.0f});
  }
  // Diagonal past the corner (-1.5, 0.75): the line x - y = -2.25 touches only that corner.
  CastOutput corner = cast(b, {-3.0f, -0.75f}, {3.0f, 3.0f});
  ASSERT_TRUE(corner.hit);
  EXPECT_NEAR(corner.fraction, 0.5f, 1e-6f);
  EXPECT_VEC_NEAR(corner.point, Vec2(-1.5f, 0.75f), 1e-6f);
  EXPECT_FALSE(cast(b, {-3.0f, -0.75f + 1e-5f}, {3.0f, 3.0f}).hit);
  CastOutput inside = cast(b, {-3.0f, -0.75f - 1e-5f}, {3.0f, 3.0f});
  ASSERT_TRUE(inside.hit);
  EXPECT_NEAR(inside.fraction, 0.5f, 1e-5f);

  // Shallow rays across the top edge's line y = 1 of the unit box: entering the y slab at t = 1/6
  // before the x slab at t = 1/3 (a hit on the left side), or leaving it at t = 1/6 before
  // entering the x slab (a miss).
  Shape unit = rc::makeBox(1.0f, 1.0f);
  expectHit(cast(unit, {-3.0f, 1.0001f}, {6.0f, -0.0006f}), 1.0f / 3.0f, {-1.0f, 0.9999f},
            {-1.0f, 0.0f}, 2e-6f);
  EXPECT_FALSE(cast(unit, {-3.0f, 0.9999f}, {6.0f, 0.0006f}).hit);

  // Random rotated boxes: rays parallel to an edge, 1e-5 m outside or inside it.
  rc::Random rng(2002);
  for (int i = 0; i < 2000; ++i) {
    float hx = rng.uniform(0.1f, 2.0f), hy = rng.uniform(0.1f, 2.0f);
    Shape box = rc::makeBox(hx, hy, rng.inBox({-0.5f, -0.5f}, {0.5f, 0.5f}));
    Transform xf{rng.inBox({-5.0f, -5.0f}, {5.0f, 5.0f}), Rot::fromAngle(rng.uniform(-3.1f, 3.1f))};
    // Local: the line y = top + delta, running along +x from the left.
    float top = box.box.center.y + hy;
    float delta = rng.uniform() < 0.5f ? 1e-5f : -1e-5f;
    float y = rng.uniform() < 0.5f ? top + delta : box.box.center.y - hy - delta;
    Vec2 oLocal{box.box.center.x - hx - rng.uniform(0.1f, 2.0f), y};
    Vec2 dLocal{2.0f * hx + 4.0f, 0.0f};
    Vec2 o = rc::apply(xf, oLocal);
    Vec2 d = rc::rotate(xf.q, dLocal);
    CastOutput out = cast(box, o, d, 1.0f, xf);
    if (delta > 0.0f) {
      EXPECT_FALSE(out.hit) << "case " << i;
    } else {
      ASSERT_TRUE(out.hit) << "case " << i;
      double expected = (box.box.center.x - hx - oLocal.x) / dLocal.x;
      EXPECT_NEAR(out.fraction, expected, 1e-5) << "case " << i;
      EXPECT_VEC_NEAR(out.normal, rc::rotate(xf.q, {-1.0f, 0.0f}), 1e-5f);
    }
  }
}

// An oriented box is cast as two slabs on its own axes (raycast.cpp); the same rectangle with
// its box extents cleared takes the general edge-by-edge clipping. Both are held to the exact
// cast in double precision: the same decision unless the ray's reach comes within 1e-5 m of the
// boundary without crossing it or crosses it by less (depth below, in the box's edge distances),
// a hit point within 1e-5 m of the boundary and near the exact entry, and the same face from
// both paths away from the corners.
TEST(RayCastOrientedBox, SlabsAndEdgeClippingAgreeWithTheExactCast) {
  rc::Random rng(2004);
  int hits = 0, inside = 0, misses = 0, shallow = 0;
  for (int i = 0; i < 100000; ++i) {
    float hx = rng.uniform(0.02f, 3.0f), hy = rng.uniform(0.02f, 3.0f);
    rc::Polygon box = rc::makeOrientedBox(hx, hy, rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}),
                                          rng.uniform(-3.2f, 3.2f));
    rc::Polygon edges = box;
    edges.boxHalfExtents = {};
    Transform xf{rng.inBox({-20.0f, -20.0f}, {20.0f, 20.0f}),
                 Rot::fromAngle(rng.uniform(-3.2f, 3.2f))};
    if (i % 4 == 0) xf.q = Rot{};  // axis-aligned in the world: parallel rays happen
    Vec2 o = xf.p + rng.inBox({-6.0f, -6.0f}, {6.0f, 6.0f});
    Vec2 target = xf.p + rng.inBox({-3.0f, -3.0f}, {3.0f, 3.0f});
    Vec2 d = rng.uniform(0.2f, 3.0f) * (target - o);
    if (i % 9 == 0) (rng.uniform() < 0.5f ? d.x : d.y) = 0.0f;
    float maxFraction = rng.uniform() < 0.8f ? 1.0f : rng.uniform(0.0f, 2.0f);
    RayCastInput in{o, d, maxFraction};
    CastOutput slab = rc::rayCast(Shape(box), xf, in);
    CastOutput clip = rc::rayCast(Shape(edges), xf, in);

    // The exact box: its corners placed in double. depth(t) is the least inward distance of
    // the ray's point from the four edge lines (negative outside), concave in t.
    const std::vector<DVec> v = worldVertices(box, xf);
    const DVec od = toD(o), dd = toD(d);
    auto depth = [&](double t) {
      double px = od.x + t * dd.x, py = od.y + t * dd.y, least = 1e300;
      for (size_t k = 0; k < 4; ++k) {
        DVec a = v[k], b = v[(k + 1) % 4];
        double ex = b.x - a.x, ey = b.y - a.y;
        least = std::min(least, (ex * (py - a.y) - ey * (px - a.x)) / std::hypot(ex, ey));
      }
      return least;
    };
    double lo = 0.0, hi = maxFraction;  // golden-section search for the deepest point
    for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
      const double m1 = lo + 0.382 * (hi - lo), m2 = hi - 0.382 * (hi - lo);
      if (depth(m1) < depth(m2))
        lo = m1;  // the deepest point is beyond m1
      else
        hi = m2;
    }
    const double deepest = std::max({depth(0.0), depth(maxFraction), depth(0.5 * (lo + hi))});
    const bool startsInside = depth(0.0) >= 0.0;
    Exact ref = startsInside ? Exact{true, 0.0} : exactPolygon(v, od, dd, maxFraction);
    const std::string what = "case " + std::to_string(i);
    if (std::fabs(deepest) < 1e-5) {
      ++shallow;  // either decision is right
    } else {
      ASSERT_EQ(slab.hit, ref.hit) << what << " (slabs), deepest " << deepest;
      ASSERT_EQ(clip.hit, ref.hit) << what << " (edges), deepest " << deepest;
    }
    if (!ref.hit) ++misses;
    if (!ref.hit || !slab.hit || !clip.hit) continue;
    ++hits;
    if (startsInside) ++inside;
    const double len = std::hypot(dd.x, dd.y);
    for (const CastOutput* out : {&slab, &clip}) {
      if (startsInside && depth(0.0) > 1e-5) {
        ASSERT_EQ(out->fraction, 0.0f) << what;
        continue;
      }
      ASSERT_LT(std::fabs(depth(out->fraction)), 1e-5) << what;
      ASSERT_NEAR(out->fraction * len, ref.t * len, 1e-3) << what;
    }
    // The same face, unless the entry is within 1e-4 m of a corner.
    double nearCorner = 1e300;
    for (const DVec& c : v)
      nearCorner =
          std::min(nearCorner, std::hypot(od.x + ref.t * dd.x - c.x, od.y + ref.t * dd.y - c.y));
    if (nearCorner > 1e-4) {
      SCOPED_TRACE(what);
      EXPECT_VEC_NEAR(slab.normal, clip.normal, 1e-6f);
    }
  }
  EXPECT_GT(hits, 40000);
  EXPECT_GT(inside, 5000);
  EXPECT_GT(misses, 20000);
  EXPECT_LT(shallow, 100);
  std::printf("oriented box: %d hits (%d from inside), %d misses, %d within 1e-5 m\n", hits, inside,
              misses, shallow);
}

// Rays along an oriented box's edges, just outside (miss) or inside (a hit through the side
// they meet first), at any angle and far from the world origin too.
TEST(RayCastOrientedBox, GrazingAlongTheEdges) {
  rc::Random rng(2005);
  for (int i = 0; i < 4000; ++i) {
    float hx = rng.uniform(0.1f, 2.0f), hy = rng.uniform(0.1f, 2.0f);
    float angle = rng.uniform(-3.2f, 3.2f);
    Shape box = rc::makeOrientedBox(hx, hy, {}, angle);
    Vec2 at = i % 2 ? Vec2{1e4f, -1e4f} : Vec2{};
    Transform xf{at + rng.inBox({-5.0f, -5.0f}, {5.0f, 5.0f}),
                 Rot::fromAngle(rng.uniform(-3.2f, 3.2f))};
    // In the box's own axes: the line y = +-(hy + delta), from the left along +x.
    // 1e-5 m near the origin; 1e-2 m at 1e4 m, where positions are known to 5e-4 m in float.
    float gap = i % 2 ? 1e-2f : 1e-5f;
    float delta = rng.uniform() < 0.5f ? gap : -gap;
    float side = rng.uniform() < 0.5f ? 1.0f : -1.0f;
    Vec2 oBox{-hx - rng.uniform(0.1f, 2.0f), side * (hy + delta)};
    Vec2 dBox{2.0f * hx + 4.0f, 0.0f};
    Rot boxAxes = Rot::fromAngle(angle);
    Vec2 o = rc::apply(xf, rc::rotate(boxAxes, oBox));
    Vec2 d = rc::rotate(xf.q, rc::rotate(boxAxes, dBox));
    CastOutput out = cast(box, o, d, 1.0f, xf);
    if (delta > 0.0f) {
      EXPECT_FALSE(out.hit) << "case " << i;
    } else {
      ASSERT_TRUE(out.hit) << "case " << i;
      double expected = (-hx - oBox.x) / dBox.x;
      EXPECT_NEAR(out.fraction * dBox.x, expected * dBox.x, i % 2 ? 4e-3 : 1e-5) << "case " << i;
      EXPECT_VEC_NEAR(out.normal, rc::rotate(xf.q, rc::rotate(boxAxes, {-1.0f, 0.0f})), 1e-5f);
    }
  }
}

// Rays along a supporting line of a random polygon through one of its vertices, moved 1e-5 m
// out (miss) or in (a short chord next to the vertex).
TEST(RayCastGrazing, PolygonVertices) {
  rc::Random rng(2003);
  int tested = 0;
  for (int i = 0; i < 1500; ++i) {
    std::vector<Vec2> pts;
    int n = 3 + static_cast<int>(rng.below(6));
    for (int k = 0; k < n; ++k)
      pts.push_back(rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}));
    rc::Polygon poly;
    try {
      poly = rc::makePolygon(pts);
    } catch (const rc::InvalidShape&) {
      continue;
    }
    Transform xf{rng.inBox({-5.0f, -5.0f}, {5.0f, 5.0f}), Rot::fromAngle(rng.uniform(-3.1f, 3.1f))};
    int k = static_cast<int>(rng.below(static_cast<std::uint32_t>(poly.count)));
    Vec2 n0 = poly.normals[(k + poly.count - 1) % poly.count], n1 = poly.normals[k];
    // The exterior angle at the vertex; skip nearly straight vertices where the chord next to
    // the vertex is long and the test is not about the vertex any more.
    if (rc::cross(n0, n1) < 0.2f) continue;
    float a = rng.uniform(0.25f, 0.75f);
    Vec2 m = rc::normalize(a * n0 + (1.0f - a) * n1);  // supporting line's outward normal
    Vec2 dirLocal = rc::leftPerp(m);
    for (float delta : {1e-5f, -1e-5f}) {
      Vec2 through = rc::mulAdd(poly.vertices[k], delta, m);
      Vec2 oLocal = rc::mulSub(through, rng.uniform(0.5f, 3.0f), dirLocal);
      Vec2 o = rc::apply(xf, oLocal);
      Vec2 d = rc::rotate(xf.q, rng.uniform(4.0f, 6.0f) * dirLocal);
      CastOutput out = cast(poly, o, d, 1.0f, xf);
      Exact ex = exactPolygon(worldVertices(poly, xf), toD(o), toD(d), 1.0);
      ASSERT_EQ(out.hit, delta < 0.0f) << "case " << i << " delta " << delta;
      ASSERT_EQ(ex.hit, out.hit) << "case " << i;
      if (out.hit) {
        double len = rc::length(d);
        EXPECT_NEAR(out.fraction * len, ex.t * len, 1e-4) << "case " << i;
        EXPECT_LT(rc::distance(out.point, rc::apply(xf, poly.vertices[k])), 1e-3f) << i;
        // The normal is one of the two edges' at the vertex.
        Vec2 w0 = rc::rotate(xf.q, n0), w1 = rc::rotate(xf.q, n1);
        float e = std::min(rc::distance(out.normal, w0), rc::distance(out.normal, w1));
        EXPECT_LT(e, 1e-5f) << "case " << i;
      }
    }
    ++tested;
  }
  EXPECT_GT(tested, 500);
}

// ---------------------------------------------------------------------------------------------
// Brute force: march along the ray with containsPoint.

using rc::testing::Kind;
using rc::testing::kindName;
// The solid kinds (rc::testing::Kind without segments), sized here by randomSolid.
constexpr Kind kKinds[] = {Kind::circle,         Kind::box,         Kind::polygon,
                           Kind::roundedPolygon, Kind::orientedBox, Kind::capsule};

Shape randomSolid(rc::Random& rng, Kind kind) {
  switch (kind) {
    case Kind::circle:
      return rc::makeCircle(rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}), rng.uniform(0.05f, 1.0f));
    case Kind::box:
      return rc::makeBox(rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f),
                         rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}));
    case Kind::orientedBox:
      return rc::makeOrientedBox(rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f),
                                 rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}), rng.uniform(-3.1f, 3.1f));
    case Kind::polygon:
    case Kind::roundedPolygon: {
      float radius = kind == Kind::roundedPolygon ? rng.uniform(0.02f, 0.4f) : 0.0f;
      for (;;) {
        int n = 3 + static_cast<int>(rng.below(6));
        float size = rng.uniform(0.1f, 1.2f);
        std::vector<Vec2> pts;
        for (int i = 0; i < n; ++i)
          pts.push_back(size * rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}));
        try {
          return rc::makePolygon(pts, radius);
        } catch (const rc::InvalidShape&) {
        }
      }
    }
    case Kind::capsule: {
      Vec2 a = rng.inBox({-0.8f, -0.8f}, {0.8f, 0.8f});
      Vec2 b = rng.inBox({-0.8f, -0.8f}, {0.8f, 0.8f});
      if (rc::distanceSquared(a, b) < 1e-4f) b = a + Vec2{0.3f, 0.1f};
      return rc::makeCapsule(a, b, rng.uniform(0.02f, 0.6f));
    }
    case Kind::segment:  // not solids: not in kKinds
    case Kind::chainLink:
      break;
  }
  return rc::makeCircle({}, 1.0f);
}

// A circle in the world frame holding the whole shape, computed here from the definition.
struct Bound {
  DVec center;
  double radius;
};
Bound boundOf(const Shape& s, const Transform& xf) {
  Vec2 c{};
  double r = 0.0;
  switch (s.type) {
    case rc::ShapeType::circle:
      c = s.circle.center;
      r = s.circle.radius;
      break;
    case rc::ShapeType::box:
      c = s.box.center;
      r = rc::length(s.box.halfExtents);
      break;
    case rc::ShapeType::polygon:
      c = s.polygon.centroid;
      for (int i = 0; i < s.polygon.count; ++i)
        r = std::max(r, static_cast<double>(rc::distance(c, s.polygon.vertices[i])));
      r += s.polygon.radius;
      break;
    case rc::ShapeType::capsule:
      c = 0.5f * (s.capsule.center1 + s.capsule.center2);
      r = 0.5 * rc::distance(s.capsule.center1, s.capsule.center2) + s.capsule.radius;
      break;
    default:
      break;
  }
  return {toD(rc::apply(xf, c)), r * 1.001 + 1e-4};
}

// The shape's farthest point in the direction m (shape frame): its supporting line with outward
// normal m touches it there.
Vec2 support(const Shape& s, Vec2 m) {
  auto best = [m](const Vec2* v, int n) {
    Vec2 b = v[0];
    for (int i = 1; i < n; ++i)
      if (rc::dot(v[i], m) > rc::dot(b, m)) b = v[i];
    return b;
  };
  switch (s.type) {
    case rc::ShapeType::circle:
      return rc::mulAdd(s.circle.center, s.circle.radius, m);
    case rc::ShapeType::box:
      return s.box.center + Vec2{m.x < 0.0f ? -s.box.halfExtents.x : s.box.halfExtents.x,
                                 m.y < 0.0f ? -s.box.halfExtents.y : s.box.halfExtents.y};
    case rc::ShapeType::polygon:
      return rc::mulAdd(best(s.polygon.vertices, s.polygon.count), s.polygon.radius, m);
    case rc::ShapeType::capsule: {
      Vec2 c[2] = {s.capsule.center1, s.capsule.center2};
      return rc::mulAdd(best(c, 2), s.capsule.radius, m);
    }
    default:
      return {};
  }
}

struct Truth {
  bool hit = false;
  double fraction = 0.0;
};

Vec2 pointAt(const RayCastInput& in, double t) {
  return {static_cast<float>(in.origin.x + t * in.translation.x),
          static_cast<float>(in.origin.y + t * in.translation.y)};
}

// The first t in [t0, t1] (fractions) where containsPoint holds, sampling every `step` and
// bisecting between the first inside sample and the sample before it (the origin, known to be
// outside, before the first). A ray starting inside hits at 0, as documented.
Truth marchRange(const Shape& s, const Transform& xf, const RayCastInput& in, double t0, double t1,
                 double step) {
  if (rc::containsPoint(s, xf, in.origin)) return {true, 0.0};
  if (!(t0 <= t1)) return {};
  double prev = 0.0;
  for (double t = t0;; t += step) {
    bool last = t >= t1;
    if (last) t = t1;
    if (rc::containsPoint(s, xf, pointAt(in, t))) {
      double lo = prev, hi = t;
      for (int k = 0; k < 60 && hi - lo > 1e-10; ++k) {
        double mid = 0.5 * (lo + hi);
        (rc::containsPoint(s, xf, pointAt(in, mid)) ? hi : lo) = mid;
      }
      return {true, hi};
    }
    if (last) return {};
    prev = t;
  }
}

// March over the part of the ray inside the shape's bounding circle in steps of `step`.
Truth march(const Shape& s, const Transform& xf, const RayCastInput& in, double step) {
  DVec o = toD(in.origin), d = toD(in.translation);
  double a = d.x * d.x + d.y * d.y;
  Bound b = boundOf(s, xf);
  double sx = b.center.x - o.x, sy = b.center.y - o.y;
  if (a == 0.0) return marchRange(s, xf, in, 1.0, 0.0, step);  // origin only
  double tc = (sx * d.x + sy * d.y) / a;
  double px = sx - tc * d.x, py = sy - tc * d.y;
  double h2 = (b.radius * b.radius - (px * px + py * py)) / a;
  if (h2 < 0.0) return marchRange(s, xf, in, 1.0, 0.0, step);
  double h = std::sqrt(h2);
  return marchRange(s, xf, in, std::max(0.0, tc - h),
                    std::min(static_cast<double>(in.maxFraction), tc + h), step);
}

// A fine march (1e-7 m steps) over the part of the ray within `halfWidth` metres of the
// projection of the point p.
Truth marchNear(const Shape& s, const Transform& xf, const RayCastInput& in, Vec2 p,
                double halfWidth) {
  DVec o = toD(in.origin), d = toD(in.translation);
  double len = std::sqrt(d.x * d.x + d.y * d.y);
  if (len == 0.0) return marchRange(s, xf, in, 1.0, 0.0, 1.0);
  double tc = ((p.x - o.x) * d.x + (p.y - o.y) * d.y) / (len * len);
  double w = halfWidth / len;
  return marchRange(s, xf, in, std::max(0.0, tc - w),
                    std::min(static_cast<double>(in.maxFraction), tc + w), 1e-7 / len);
}

// True when moving the ray by 1e-4 m (sideways either way, tilting it by moving its origin or
// the end of the cast sideways, its origin along itself either way, its end along itself either
// way) changes the fine march's hit decision near the point p.
bool isGrazing(const Shape& s, const Transform& xf, const RayCastInput& in, Vec2 p) {
  float len = rc::length(in.translation) * in.maxFraction;
  Vec2 dir = rc::normalize(in.translation);
  std::vector<RayCastInput> family;
  const float e = 1e-4f;
  if (len == 0.0f) {
    for (Vec2 off : {Vec2{e, 0.0f}, Vec2{-e, 0.0f}, Vec2{0.0f, e}, Vec2{0.0f, -e}})
      family.push_back({in.origin + off, in.translation, in.maxFraction});
  } else {
    Vec2 side = e * rc::leftPerp(dir);
    family.push_back({in.origin + side, in.translation, in.maxFraction});
    family.push_back({in.origin - side, in.translation, in.maxFraction});
    Vec2 end = rc::mulAdd(in.origin, in.maxFraction, in.translation);
    family.push_back({in.origin + side, end - (in.origin + side), 1.0f});
    family.push_back({in.origin - side, end - (in.origin - side), 1.0f});
    family.push_back({in.origin, end + side - in.origin, 1.0f});
    family.push_back({in.origin, end - side - in.origin, 1.0f});
    for (float sign : {1.0f, -1.0f}) {
      family.push_back({in.origin, in.translation, in.maxFraction * (1.0f + sign * e / len)});
      Vec2 o = rc::mulAdd(in.origin, sign * e, dir);
      family.push_back({o, end - o, 1.0f});
    }
  }
  bool hit = marchNear(s, xf, in, p, 2e-3).hit;
  for (const RayCastInput& f : family)
    if (marchNear(s, xf, f, p, 2e-3).hit != hit) return true;
  return false;
}

TEST(RayCastBruteForce, AgreesWithPointContainment) {
  rc::Random rng(2010);
  int hits = 0, misses = 0, grazing = 0, inside = 0, refined = 0;
  for (int i = 0; i < 20000; ++i) {
    Kind kind = kKinds[i % 6];
    Shape s = randomSolid(rng, kind);
    Transform xf{rng.inBox({-3.0f, -3.0f}, {3.0f, 3.0f}), Rot::fromAngle(rng.uniform(-3.2f, 3.2f))};
    Vec2 o = xf.p + rng.inBox({-3.0f, -3.0f}, {3.0f, 3.0f});
    Vec2 target = xf.p + rng.inBox({-0.6f, -0.6f}, {0.6f, 0.6f});
    Vec2 d = rng.uniform(0.5f, 1.5f) * (target - o);
    float maxFraction = rng.uniform() < 0.8f ? 1.0f : rng.uniform(0.2f, 1.5f);
    if (i % 100 == 7) d = {};
    if (i % 10 == 3) {
      // Nearly axis-parallel in an unrotated body: slabs and edges met at grazing angles.
      xf.q = Rot{};
      (rng.uniform() < 0.5f ? d.x : d.y) *= std::pow(10.0f, rng.uniform(-6.0f, -2.0f));
    } else if (i % 20 == 11) {
      // Along a supporting line moved 1e-7 to 1e-3 m out (or in, when delta < 0).
      Vec2 m = rc::normalize(rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}));
      if (m == Vec2{}) m = {1.0f, 0.0f};
      float delta =
          std::pow(10.0f, rng.uniform(-7.0f, -3.0f)) * (rng.uniform() < 0.5f ? -1.0f : 1.0f);
      Vec2 dir = rc::rotate(xf.q, rng.uniform() < 0.5f ? rc::leftPerp(m) : rc::rightPerp(m));
      Vec2 through = rc::apply(xf, rc::mulAdd(support(s, m), delta, m));
      o = rc::mulSub(through, rng.uniform(0.2f, 3.0f), dir);
      d = rng.uniform(0.5f, 5.0f) * dir;
    }
    RayCastInput in{o, d, maxFraction};
    CastOutput out = rc::rayCast(s, xf, in);
    Truth truth = march(s, xf, in, 1e-4);
    std::string what = std::string(kindName(kind)) + " case " + std::to_string(i);
    if (out.hit != truth.hit) {
      // A chord shorter than a step, or a graze: look again finely where either saw the hit.
      Vec2 p = out.hit ? out.point : pointAt(in, truth.fraction);
      Truth fine = marchNear(s, xf, in, p, 2e-3);
      if (fine.hit != out.hit) {
        ASSERT_TRUE(isGrazing(s, xf, in, p))
            << what << ": ours " << out.hit << " at " << out.fraction << ", march " << fine.hit
            << " at " << fine.fraction << "; o (" << o.x << ", " << o.y << ") d (" << d.x << ", "
            << d.y << ") maxFraction " << maxFraction;
        ++grazing;
        continue;
      }
      truth = fine;
      ++refined;
    }
    if (!out.hit) {
      ++misses;
      continue;
    }
    ++hits;
    if (truth.fraction == 0.0) ++inside;
    ASSERT_NEAR(out.fraction, truth.fraction, 1e-4) << what;
    ASSERT_TRUE(rc::isFinite(out.normal) && rc::isFinite(out.point)) << what;
    if (out.fraction > 0.0f) {
      EXPECT_NEAR(rc::length(out.normal), 1.0f, 1e-5f) << what;
      // The normal faces the ray and the point is where the ray is.
      EXPECT_LE(rc::dot(out.normal, d), 0.0f) << what;
      EXPECT_VEC_NEAR(out.point, rc::mulAdd(o, out.fraction, d), 1e-5f);
    }
  }
  EXPECT_GT(hits, 8000);
  EXPECT_GT(misses, 4000);
  EXPECT_GT(inside, 400);
  // The coarse march steps over chords shorter than 1e-4 of the ray (the deliberately grazing
  // rays make them); the fine march then decides. Grazing within 1e-4 m stays rare.
  EXPECT_LT(grazing, 40);
  std::printf("brute force: %d hits (%d from inside), %d misses, %d refined, %d grazing\n", hits,
              inside, misses, refined, grazing);
}

// ---------------------------------------------------------------------------------------------
// Robustness.

// The same configuration placed 1e4 m from the world origin gives the same answer as at the
// origin, within 1e-3 m. Positions are on the 2^-10 grid so both placements are exact.
TEST(RayCastRobustness, FarFromTheOrigin) {
  rc::Random rng(2020);
  auto grid = [](Vec2 v) {
    return Vec2{std::round(v.x * 1024.0f) / 1024.0f, std::round(v.y * 1024.0f) / 1024.0f};
  };
  int hits = 0;
  for (int i = 0; i < 6000; ++i) {
    Kind kind = kKinds[i % 6];
    Shape s = randomSolid(rng, kind);
    if (i % 7 == 0) s = rc::makeSegment(rng.inBox({-1, -1}, {1, 1}), rng.inBox({-1, -1}, {1, 1}));
    Rot q = Rot::fromAngle(rng.uniform(-3.2f, 3.2f));
    Vec2 far = grid(Vec2{1e4f, -1e4f} + rng.inBox({-500.0f, -500.0f}, {500.0f, 500.0f}));
    Vec2 oLocal = grid(rng.inBox({-3.0f, -3.0f}, {3.0f, 3.0f}));
    Vec2 d = rng.uniform(0.3f, 1.5f) * (rng.inBox({-1.2f, -1.2f}, {1.2f, 1.2f}) - oLocal);
    CastOutput near = cast(s, oLocal, d, 1.0f, Transform{{}, q});
    CastOutput away = cast(s, far + oLocal, d, 1.0f, Transform{far, q});
    ASSERT_EQ(near.hit, away.hit) << "case " << i;
    if (!near.hit) continue;
    ++hits;
    float len = rc::length(d);
    EXPECT_NEAR(near.fraction * len, away.fraction * len, 1e-3f) << "case " << i;
    EXPECT_VEC_NEAR(near.normal, away.normal, 1e-5f);
    EXPECT_VEC_NEAR(away.point - far, near.point, 2e-3f);
  }
  EXPECT_GT(hits, 1500);
}

// Rays 1e4 m long against circles of 1 cm to 1 m, starting near them or 5 km away.
TEST(RayCastRobustness, VeryLongRaysAgainstSmallCircles) {
  rc::Random rng(2021);
  for (int i = 0; i < 4000; ++i) {
    Vec2 center = rng.inBox({-10.0f, -10.0f}, {10.0f, 10.0f});
    float r = std::pow(10.0f, rng.uniform(-2.0f, 0.0f));
    Vec2 dir = rc::normalize(rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f}));
    if (dir == Vec2{}) continue;
    bool startFar = i % 2 == 1;
    float back = startFar ? 5000.0f : rng.uniform(0.1f, 5.0f) + r;
    // Aim within 0.8 r of the centre: a clear hit.
    Vec2 o = center - back * dir + rng.uniform(-0.8f, 0.8f) * r * rc::leftPerp(dir);
    Vec2 d = 1e4f * dir;
    CastOutput out = cast(rc::makeCircle(center, r), o, d);
    Exact ex = exactCircle(toD(center), r, toD(o), toD(d), 1.0);
    ASSERT_TRUE(ex.hit);
    ASSERT_TRUE(out.hit) << "case " << i;
    double len = std::sqrt(static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y);
    // Near: 1e-4 m. From 5 km the ray's own direction is only known to ~3e-4 m over that
    // distance in float; allow 5e-3 m there.
    EXPECT_NEAR(out.fraction * len, ex.t * len, startFar ? 5e-3 : 1e-4) << "case " << i;
    EXPECT_NEAR(rc::length(out.normal), 1.0f, 1e-5f);
  }
}

bool allFinite(const CastOutput& out) {
  return std::isfinite(out.fraction) && rc::isFinite(out.point) && rc::isFinite(out.normal);
}

// Finite input never yields NaN (or infinity): random magnitudes from 1e-6 to 1e6 for positions
// and translations, and maxFraction from 0 to 1e3, aimed at the shapes and not.
TEST(RayCastRobustness, NoNanForFiniteInput) {
  rc::Random rng(2022);
  auto mag = [&](float lo, float hi) {
    float v = std::pow(10.0f, rng.uniform(lo, hi));
    return rng.uniform() < 0.5f ? -v : v;
  };
  Vec2 pts[] = {{0.0f, 0.0f}, {2.0f, 0.0f}, {2.0f, 2.0f}};
  std::vector<Shape> extra = {rc::makeSegment({-1.0f, 0.5f}, {1.0f, -0.5f}),
                              rc::makeChain(pts, false, true)[0],
                              rc::makeChain(pts, false, false)[1]};
  int hits = 0;
  for (int i = 0; i < 60000; ++i) {
    Shape s = i % 8 < 6 ? randomSolid(rng, kKinds[i % 8]) : extra[static_cast<size_t>(i % 3)];
    Transform xf{{mag(-6.0f, 6.0f), mag(-6.0f, 6.0f)}, Rot::fromAngle(rng.uniform(-4.0f, 4.0f))};
    if (i % 5 == 0) xf.q = Rot{};
    Vec2 o = i % 2 ? Vec2{mag(-6.0f, 6.0f), mag(-6.0f, 6.0f)}
                   : xf.p + rng.inBox({-2.0f, -2.0f}, {2.0f, 2.0f});
    Vec2 d{mag(-6.0f, 6.0f), mag(-6.0f, 6.0f)};
    if (i % 3 == 0) d = std::pow(10.0f, rng.uniform(-6.0f, 6.0f)) * rc::normalize(xf.p - o);
    if (i % 11 == 0) d.x = 0.0f;
    if (i % 13 == 0) d.y = 0.0f;
    if (i % 97 == 0) d = {};
    float maxFraction = i % 4 ? 1.0f : (i % 8 ? std::pow(10.0f, rng.uniform(-6.0f, 3.0f)) : 0.0f);
    CastOutput out = rc::rayCast(s, xf, {o, d, maxFraction});
    if (!out.hit) continue;
    ++hits;
    ASSERT_TRUE(allFinite(out)) << "case " << i << " " << rc::shapeTypeName(s.type) << " o (" << o.x
                                << ", " << o.y << ") d (" << d.x << ", " << d.y << ")";
    EXPECT_GE(out.fraction, 0.0f);
    EXPECT_LE(out.fraction, maxFraction);
  }
  EXPECT_GT(hits, 5000);
}

// Names for messages: shapeTypeName does not tell a rounded polygon from a sharp one.
std::string label(const Shape& s) {
  if (s.type == rc::ShapeType::polygon && s.polygon.radius > 0.0f) return "rounded polygon";
  return rc::shapeTypeName(s.type);
}

std::vector<Shape> everyShapeType() {
  static const Vec2 tri[] = {{-1.0f, -1.0f}, {1.0f, -1.0f}, {0.0f, 1.0f}};
  static const Vec2 wall[] = {{-2.0f, 0.5f}, {2.0f, 0.5f}};
  return {rc::makeCircle({}, 1.0f),
          rc::makeBox(1.0f, 1.0f),
          rc::makePolygon(tri),
          rc::makePolygon(tri, 0.25f),
          rc::makeOrientedBox(1.0f, 0.75f, {}, 0.3f),
          rc::makeCapsule({-1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f),
          rc::makeSegment({-2.0f, 0.5f}, {2.0f, 0.5f}),
          rc::makeChain(wall, false, false)[0]};
}

// Finite input at the very end of the float range: the ray's origin 6e38 m from the body, which
// overflows origin - position. "No NaN is ever produced from finite input" (raycast.h), and the
// shape is 6e38 m beyond the ray's reach, so no hit either.
TEST(RayCastRobustness, NoNanWhenTheOffsetOverflows) {
  for (const Shape& s : everyShapeType()) {
    for (Vec2 d : {Vec2{-1.0f, 0.5f}, Vec2{-1e38f, 1e38f}}) {
      CastOutput out = cast(s, {3e38f, 0.0f}, d, 1.0f, Transform{{-3e38f, 0.0f}, Rot{}});
      EXPECT_FALSE(std::isnan(out.fraction) || std::isnan(out.point.x) || std::isnan(out.point.y) ||
                   std::isnan(out.normal.x) || std::isnan(out.normal.y))
          << label(s) << " d (" << d.x << ", " << d.y << "): hit " << out.hit << " fraction "
          << out.fraction;
      EXPECT_FALSE(out.hit) << label(s) << " d (" << d.x << ", " << d.y << "): fraction "
                            << out.fraction;
    }
  }
}

// Translations whose squared length overflows float (|d| > 1.8e19 m): still rays, hitting where
// a short ray in the same direction does, at the same distance; from inside, the normal still
// opposes the direction.
TEST(RayCastRobustness, HugeTranslations) {
  for (const Shape& s : everyShapeType()) {
    SCOPED_TRACE(label(s));
    CastOutput ref = cast(s, {0.1f, 5.0f}, {0.0f, -10.0f});
    ASSERT_TRUE(ref.hit);
    for (float len : {1e20f, 3e38f}) {
      CastOutput out = cast(s, {0.1f, 5.0f}, {0.0f, -len});
      SCOPED_TRACE(len);
      if (!out.hit) {
        ADD_FAILURE() << "no hit";
        continue;
      }
      EXPECT_NEAR(out.fraction * len, ref.fraction * 10.0f, 1e-5f);
      EXPECT_VEC_NEAR(out.point, ref.point, 1e-5f);
      EXPECT_VEC_NEAR(out.normal, ref.normal, 1e-6f);
    }
    if (s.isSolid()) {
      CastOutput inside = cast(s, {0.0f, 0.0f}, {0.0f, -1e20f});
      EXPECT_TRUE(inside.hit);
      EXPECT_VEC_NEAR(inside.normal, Vec2(0.0f, 1.0f), 1e-6f);
    }
  }
}

// NaN anywhere in the input must not crash; any output is acceptable and none is promised.
// What happens at the time of writing (every comparison with NaN is false, so each cast takes
// whichever branch its rejection tests fall through to):
//   - box and sharp polygon: no hit;
//   - circle and capsule: hit = true with a NaN fraction, point and normal;
//   - segment: hit = true with a NaN fraction and point for a NaN origin; a NaN translation may
//     miss or hit depending on the side the origin is on; a one-sided chain link may miss;
//   - rounded polygon: a NaN origin counts as inside (std::max skips the NaN separations), so a
//     hit at fraction 0 with the NaN origin as point; a NaN translation gives a NaN fraction;
//   - a NaN maxFraction leaves the ray unbounded for every shape.
// So a caller must not cast NaN rays: "hit" alone does not mean a usable result then.
TEST(RayCastRobustness, NanInputDoesNotCrash) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Vec2 tri[] = {{0.0f, 0.0f}, {2.0f, 0.0f}, {1.0f, 2.0f}};
  Vec2 pts[] = {{0.0f, 0.0f}, {2.0f, 0.0f}};
  std::vector<Shape> shapes = {rc::makeCircle({0.5f, 0.0f}, 1.0f),
                               rc::makeBox(1.0f, 1.0f),
                               rc::makePolygon(tri),
                               rc::makePolygon(tri, 0.2f),
                               rc::makeCapsule({-1.0f, 0.0f}, {1.0f, 0.0f}, 0.5f),
                               rc::makeSegment({-1.0f, -1.0f}, {1.0f, 1.0f}),
                               rc::makeChain(pts, false, true)[0],
                               rc::makeChain(pts, false, false)[0]};
  int calls = 0;
  for (const Shape& s : shapes) {
    for (int field = 0; field < 6; ++field) {
      RayCastInput in{{0.5f, 5.0f}, {0.0f, -10.0f}, 1.0f};
      Transform xf{};
      switch (field) {
        case 0:
          in.origin.x = nan;
          break;
        case 1:
          in.origin.y = nan;
          break;
        case 2:
          in.translation.x = nan;
          break;
        case 3:
          in.translation.y = nan;
          break;
        case 4:
          in.maxFraction = nan;
          break;
        case 5:
          xf.p.x = nan;
          break;
      }
      CastOutput out = rc::rayCast(s, xf, in);
      ++calls;
      if (out.hit && !std::isnan(out.fraction)) {
        // Whatever is reported as a finite fraction stays in range.
        EXPECT_GE(out.fraction, 0.0f);
      }
    }
  }
  EXPECT_EQ(calls, 48);
}

// ---------------------------------------------------------------------------------------------
// Polygons from 1 mm to 100 m: a ray answers for the polygon that was asked for.
//
// The polygons of shapes_test.cpp (rc::testing::randomConvexPolygon: regular and irregular, 3 to
// 8 vertices, circumradius R from 1 mm to 100 m, centred within 3 R of the origin) built from
// their float vertices, cast in their own frame and held to the exact polygon's entry in long
// double (rc::testing::exactEntry) for the same float origin and translation. Rays start 2 R to
// 4 R from the centre and aim at a point within half the inradius of the vertices' mean (a hit,
// never grazing), or pass 1.05 R to 2 R from the centre (a miss).
// Tolerance on the distance travelled to the hit: rounding the vertices to float moves each by
// at most delta = sqrt(2) u M (u = 2^-24, M the largest coordinate), so the entered edge by at
// most delta, and the entry by delta / s along the ray (s the cosine of the incidence); the
// cast's float arithmetic (v - o and the float normal's direction, a few roundings each) adds at
// most 8 u (L + t |d|) / s, L = |o - c| + R bounding |v - o|; the fraction's own rounding 2 u t
// |d|. The normal is the exact edge's to 2 delta / (edge length) + 4 u, checked where the entry is
// farther than 100 tolerances from the edge's ends (near a corner either edge's is right).
TEST(RayCastPolygon, PolygonsFrom1mmTo100mAgreeWithTheExactCast) {
  constexpr long double kU = 0x1p-24L, kTwoPi = 6.283185307179586476925286766559L;
  rc::Random rng(2040);
  int failures = 0, hits = 0, misses = 0, normals = 0, cases = 0;
  double worst = 0.0, worstNormal = 0.0;
  std::string first;
  auto fail = [&](const std::string& what) {
    if (failures++ == 0) first = what;
  };
  char buf[320];
  for (int n = 3; n <= rc::kMaxPolygonVertices; ++n) {
    for (int i = 0; i < 200; ++i, ++cases) {
      const long double R =
          i < 4 ? (i < 2 ? 1e-3L : 1e2L) : 1e-3L * std::pow(10.0L, 5.0L * rng.uniformDouble());
      const rc::testing::TestPolygon t = rc::testing::randomConvexPolygon(rng, n, R, i % 2 == 0);
      const rc::testing::ExactPolygon& e = t.exact;
      rc::Polygon poly;
      try {
        poly = rc::makePolygon(t.points);
      } catch (const rc::InvalidShape& ex) {
        std::snprintf(buf, sizeof buf, "n %d R %Lg: %s", n, R, ex.what());
        fail(buf);
        continue;
      }
      long double mx = 0, my = 0, far = 0;
      for (int k = 0; k < n; ++k) {
        mx += e.x[k] / n;
        my += e.y[k] / n;
        far = std::max({far, std::fabs(e.x[k]), std::fabs(e.y[k])});
      }
      long double inradius = std::numeric_limits<long double>::infinity();
      for (int k = 0; k < n; ++k) {
        const int l = (k + 1) % n;
        const long double ex = e.x[l] - e.x[k], ey = e.y[l] - e.y[k];
        inradius =
            std::min(inradius, ((mx - e.x[k]) * ey - (my - e.y[k]) * ex) / -std::hypot(ex, ey));
      }
      const long double delta = std::sqrt(2.0L) * kU * far;
      for (int r = 0; r < 20; ++r) {
        const long double beta = kTwoPi * rng.uniformDouble(), gamma = kTwoPi * rng.uniformDouble();
        const bool aimed = r < 15;
        Vec2 o, d;
        if (aimed) {
          const long double away = R * (2 + 2 * rng.uniformDouble());
          const long double off = 0.5L * inradius * std::sqrt(rng.uniformDouble());
          const long double tx = mx + off * std::cos(gamma), ty = my + off * std::sin(gamma);
          o = {static_cast<float>(t.centerX + away * std::cos(beta)),
               static_cast<float>(t.centerY + away * std::sin(beta))};
          const long double reach = 1.2L + 0.8L * rng.uniformDouble();
          d = {static_cast<float>((tx - o.x) * reach), static_cast<float>((ty - o.y) * reach)};
        } else {
          const long double h = R * (1.05L + 0.95L * rng.uniformDouble());
          const long double ax = std::cos(gamma), ay = std::sin(gamma);
          o = {static_cast<float>(t.centerX - h * ay - 3 * R * ax),
               static_cast<float>(t.centerY + h * ax - 3 * R * ay)};
          d = {static_cast<float>(6 * R * ax), static_cast<float>(6 * R * ay)};
        }
        const long double ox = o.x, oy = o.y, dx = d.x, dy = d.y;
        const rc::testing::ExactEntry ex = rc::testing::exactEntry(e, ox, oy, dx, dy, 1);
        const CastOutput out = rc::rayCast(poly, RayCastInput{o, d, 1.0f});
        if (!aimed) {
          ++misses;
          if (out.hit || ex.hit) {
            std::snprintf(buf, sizeof buf, "n %d R %Lg ray %d: a miss was a hit", n, R, r);
            fail(buf);
          }
          continue;
        }
        if (!ex.hit || !out.hit) {
          std::snprintf(buf, sizeof buf, "n %d R %Lg ray %d: hit %d, exact %d", n, R, r, out.hit,
                        ex.hit);
          fail(buf);
          continue;
        }
        ++hits;
        const int k = ex.edge, l = (k + 1) % n;
        const long double edge = std::hypot(e.x[l] - e.x[k], e.y[l] - e.y[k]);
        const long double nx = (e.y[l] - e.y[k]) / edge, ny = (e.x[k] - e.x[l]) / edge;
        const long double len = std::hypot(dx, dy), travel = ex.t * len;
        const long double s = std::fabs(nx * dx + ny * dy) / len;
        const long double L = std::hypot(ox - t.centerX, oy - t.centerY) + R;
        const long double tol = (delta + 8 * kU * (L + travel)) / s + 2 * kU * travel;
        const long double px = ox + ex.t * dx, py = oy + ex.t * dy;
        const long double along = std::fabs(out.fraction - ex.t) * len;
        const long double point = std::hypot(out.point.x - px, out.point.y - py);
        const long double tolPoint =
            tol + 2 * std::sqrt(2.0L) * kU * (std::max(std::fabs(ox), std::fabs(oy)) + travel);
        worst = std::max(worst, static_cast<double>(std::max(along / tol, point / tolPoint)));
        if (along > tol || point > tolPoint) {
          std::snprintf(buf, sizeof buf,
                        "n %d R %Lg ray %d: fraction %.9g, exact %.12Lg (%.3Lg m apart, tolerance "
                        "%.3Lg); point %.3Lg m apart (%.3Lg)",
                        n, R, r, static_cast<double>(out.fraction), ex.t, along, tol, point,
                        tolPoint);
          fail(buf);
          continue;
        }
        const long double fromEnds =
            std::min(std::hypot(px - e.x[k], py - e.y[k]), std::hypot(px - e.x[l], py - e.y[l]));
        if (fromEnds < 100 * tol) continue;
        ++normals;
        const long double tilt = std::hypot(out.normal.x - nx, out.normal.y - ny);
        worstNormal =
            std::max(worstNormal, static_cast<double>(tilt / (2 * delta / edge + 4 * kU)));
        if (tilt > 2 * delta / edge + 4 * kU) {
          std::snprintf(buf, sizeof buf, "n %d R %Lg ray %d: normal %.3Lg off (tolerance %.3Lg)", n,
                        R, r, tilt, 2 * delta / edge + 4 * kU);
          fail(buf);
        }
      }
    }
  }
  EXPECT_EQ(failures, 0) << failures << " failures over " << cases
                         << " polygons; the first: " << first;
  EXPECT_GT(hits, cases * 14);
  EXPECT_EQ(misses, cases * 5);
  EXPECT_GT(normals, cases * 13);
  std::snprintf(buf, sizeof buf, "%.3g", worst);
  RecordProperty("worst_hit_error_over_tolerance", buf);
  std::snprintf(buf, sizeof buf, "%.3g", worstNormal);
  RecordProperty("worst_normal_error_over_tolerance", buf);
}

}  // namespace raycast_test
