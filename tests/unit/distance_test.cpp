// Distance queries (physics/distance.h): hand-worked cases, references computed independently here
// in double / long double (a brute-force sampler for segment distance, orientation tests for
// triangle overlap, vertex-to-edge distances for convex shapes), and properties on random shape
// pairs: symmetry, invariance under a common rigid motion, the same answer 1e4 m from the origin,
// and never a NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "physics/distance.h"
#include "physics/random.h"
#include "physics/shapes.h"
#include "support/reference_geometry.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace distance_test {

using rc::Vec2;
using rc::testing::Core;
using rc::testing::coreContains;
using rc::testing::dist;
using rc::testing::edgeCount;
using rc::testing::edgeEnd;
using rc::testing::edgeStart;
using rc::testing::orient;
using rc::testing::P2;
using rc::testing::pointSegmentDistance;
using rc::testing::signedSurfaceDistance;
using rc::testing::toP2;
constexpr double kFloatUnitRoundoff = 1.0 / 16777216.0;  // 2^-24: float rounding, relative

// ---------------------------------------------------------------------------------------------
// Reference geometry in double, independent of physics/ (only rc::Vec2 and the shape structs are
// read).

bool inBoundingBox(P2 a, P2 b, P2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
// Closed segments [a, b] and [c, d] share a point (the textbook orientation test).
bool segmentsIntersectRef(P2 a, P2 b, P2 c, P2 d) {
  int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) {
    if (o1 != 0 || o2 != 0) return true;
  }
  if (o1 == 0 && inBoundingBox(a, b, c)) return true;
  if (o2 == 0 && inBoundingBox(a, b, d)) return true;
  if (o3 == 0 && inBoundingBox(c, d, a)) return true;
  if (o4 == 0 && inBoundingBox(c, d, b)) return true;
  return false;
}

// The core of a shape in world coordinates, built from the shape fields directly, not through
// rc::makeProxy.
Core worldCore(const rc::Shape& s, const rc::Transform& xf) {
  Vec2 local[rc::kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;
  switch (s.type) {
    case rc::ShapeType::circle:
      local[0] = s.circle.center;
      count = 1;
      radius = s.circle.radius;
      break;
    case rc::ShapeType::box: {
      Vec2 m = s.box.center, h = s.box.halfExtents;
      local[0] = {m.x - h.x, m.y - h.y};
      local[1] = {m.x + h.x, m.y - h.y};
      local[2] = {m.x + h.x, m.y + h.y};
      local[3] = {m.x - h.x, m.y + h.y};
      count = 4;
      break;
    }
    case rc::ShapeType::polygon:
      for (int i = 0; i < s.polygon.count; ++i)
        local[i] = s.polygon.vertices[i];
      count = s.polygon.count;
      radius = s.polygon.radius;
      break;
    case rc::ShapeType::capsule:
      local[0] = s.capsule.center1;
      local[1] = s.capsule.center2;
      count = 2;
      radius = s.capsule.radius;
      break;
    case rc::ShapeType::segment:
      local[0] = s.segment.point1;
      local[1] = s.segment.point2;
      count = 2;
      break;
    case rc::ShapeType::chainSegment:
      local[0] = s.chainSegment.segment.point1;
      local[1] = s.chainSegment.segment.point2;
      count = 2;
      break;
  }
  return rc::testing::worldCore(local, count, radius, xf);
}

// Distance from p to the core; 0 inside.
double pointCoreDistance(const Core& c, P2 p) {
  if (coreContains(c, p)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < edgeCount(c); ++i)
    best = std::min(best, pointSegmentDistance(p, edgeStart(c, i), edgeEnd(c, i)));
  return best;
}

// Distance between two rounded convex shapes: the cores are at distance 0 when a vertex of one is
// inside the other or two edges cross; otherwise the closest pair of two disjoint convex polygons
// always has a vertex of one of them in it, so the minimum vertex-to-other-core distance is exact.
double referenceDistance(const Core& a, const Core& b) {
  double core = std::numeric_limits<double>::infinity();
  for (int i = 0; i < a.count; ++i)
    core = std::min(core, pointCoreDistance(b, a.pts[i]));
  for (int i = 0; i < b.count; ++i)
    core = std::min(core, pointCoreDistance(a, b.pts[i]));
  for (int i = 0; i < edgeCount(a) && core > 0.0; ++i) {
    for (int j = 0; j < edgeCount(b); ++j) {
      if (segmentsIntersectRef(edgeStart(a, i), edgeEnd(a, i), edgeStart(b, j), edgeEnd(b, j))) {
        core = 0.0;
        break;
      }
    }
  }
  return std::max(0.0, core - a.radius - b.radius);
}

// Whether an output is a valid closest pair for separated shapes: both points on their own
// surface and |pointB - pointA| equal to the distance. Two different outputs that both pass are
// equally right: the closest feature is not unique (parallel edges). For overlapping shapes the
// only contract is one common point (see OverlapGivesZero for where it lies).
bool isClosestPair(const rc::DistanceOutput& o, const Core& a, const Core& b, double tol) {
  P2 pa = toP2(o.pointA), pb = toP2(o.pointB);
  if (o.distance > 0.0f) {
    return std::fabs(signedSurfaceDistance(a, pa)) <= tol &&
           std::fabs(signedSurfaceDistance(b, pb)) <= tol &&
           std::fabs(dist(pa, pb) - o.distance) <= tol;
  }
  return dist(pa, pb) <= tol;
}

bool allFinite(const rc::DistanceOutput& o) {
  return rc::isFinite(o.pointA) && rc::isFinite(o.pointB) && rc::isFinite(o.normal) &&
         rc::isFinite(o.distance);
}

void expectVecNear(Vec2 got, Vec2 want, double tol, const char* what) {
  EXPECT_NEAR(got.x, want.x, tol) << what;
  EXPECT_NEAR(got.y, want.y, tol) << what;
}

// ---------------------------------------------------------------------------------------------
// Hand-worked shape distances.

TEST(DistanceHandWorked, TwoCircles) {
  // |c2 - c1| = 5 along (0.6, 0.8); distance = 5 - 1 - 2 = 2.
  rc::Shape a = rc::makeCircle({1, 2}, 1.0f), b = rc::makeCircle({4, 6}, 2.0f);
  rc::DistanceOutput o = rc::shapeDistance(a, {}, b, {});
  EXPECT_NEAR(o.distance, 2.0f, 1e-6f);
  expectVecNear(o.pointA, {1.6f, 2.8f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {2.8f, 4.4f}, 1e-6, "pointB");
  expectVecNear(o.normal, {0.6f, 0.8f}, 1e-6, "normal");
  // The same circles placed by transforms: centres at (2, 1) and (2, -2.5) after a quarter turn.
  rc::Shape c = rc::makeCircle({0, 0.5f}, 0.25f);
  rc::Transform xfA{{2, 1}, {}}, xfB{{2, -3}, rc::Rot::fromAngle(rc::kPi / 2)};
  rc::Shape d = rc::makeCircle({0.5f, 0}, 0.75f);  // (0.5, 0) turned a quarter: (0, 0.5)
  o = rc::shapeDistance(c, xfA, d, xfB);
  // Centres (2, 1.5) and (2, -2.5): 4 apart, distance 4 - 1 = 3, normal (0, -1).
  EXPECT_NEAR(o.distance, 3.0f, 1e-6f);
  expectVecNear(o.pointA, {2.0f, 1.25f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {2.0f, -1.75f}, 1e-6, "pointB");
  expectVecNear(o.normal, {0.0f, -1.0f}, 1e-6, "normal");
}

TEST(DistanceHandWorked, CircleBox) {
  rc::Shape box = rc::makeBox(1.0f, 0.5f);
  // Facing the right side: closest box point (1, 0.2), distance 2 - 0.5.
  rc::DistanceOutput o = rc::shapeDistance(box, {}, rc::makeCircle({3, 0.2f}, 0.5f), {});
  EXPECT_NEAR(o.distance, 1.5f, 1e-6f);
  expectVecNear(o.pointA, {1.0f, 0.2f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {2.5f, 0.2f}, 1e-6, "pointB");
  expectVecNear(o.normal, {1.0f, 0.0f}, 1e-6, "normal");
  // Facing the corner (1, 0.5): centre (4, 4.5) is (3, 4) away, distance 5 - 1.
  o = rc::shapeDistance(box, {}, rc::makeCircle({4, 4.5f}, 1.0f), {});
  EXPECT_NEAR(o.distance, 4.0f, 1e-6f);
  expectVecNear(o.pointA, {1.0f, 0.5f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {3.4f, 3.7f}, 1e-6, "pointB");
  expectVecNear(o.normal, {0.6f, 0.8f}, 1e-6, "normal");
  // Circle first: everything swaps and the normal flips.
  o = rc::shapeDistance(rc::makeCircle({4, 4.5f}, 1.0f), {}, box, {});
  EXPECT_NEAR(o.distance, 4.0f, 1e-6f);
  expectVecNear(o.pointA, {3.4f, 3.7f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {1.0f, 0.5f}, 1e-6, "pointB");
  expectVecNear(o.normal, {-0.6f, -0.8f}, 1e-6, "normal");
}

TEST(DistanceHandWorked, BoxBoxCornerToCorner) {
  // Unit boxes on the diagonal: corners (1, 1) and (4, 4), distance 3 sqrt(2).
  rc::Shape box = rc::makeBox(1.0f, 1.0f);
  rc::DistanceOutput o = rc::shapeDistance(box, {}, box, {{5, 5}, {}});
  EXPECT_NEAR(o.distance, 3.0 * std::sqrt(2.0), 2e-6);
  expectVecNear(o.pointA, {1, 1}, 1e-6, "pointA");
  expectVecNear(o.pointB, {4, 4}, 1e-6, "pointB");
  expectVecNear(o.normal, {static_cast<float>(std::sqrt(0.5)), static_cast<float>(std::sqrt(0.5))},
                1e-6, "normal");
  // Both turned 45 degrees: the corners (sqrt 2, 0) and (5 - sqrt 2, 0) face each other.
  rc::Rot q = rc::Rot::fromAngle(rc::kPi / 4);
  o = rc::shapeDistance(box, {{0, 0}, q}, box, {{5, 0}, q});
  const double r2 = std::sqrt(2.0);
  EXPECT_NEAR(o.distance, 5.0 - 2.0 * r2, 2e-6);
  expectVecNear(o.pointA, {static_cast<float>(r2), 0.0f}, 1e-6, "pointA");
  expectVecNear(o.pointB, {static_cast<float>(5.0 - r2), 0.0f}, 1e-6, "pointB");
  expectVecNear(o.normal, {1, 0}, 1e-6, "normal");
}

TEST(DistanceHandWorked, ParallelCapsules) {
  // Axes y = 0 (x in [-1, 1]) and y = 2 (x in [-0.5, 2]): distance 2 - 0.25 - 0.5. The closest
  // points are not unique: any x in [-0.5, 1], the same x on both.
  rc::Shape a = rc::makeCapsule({-1, 0}, {1, 0}, 0.25f);
  rc::Shape b = rc::makeCapsule({-0.5f, 2}, {2, 2}, 0.5f);
  rc::DistanceOutput o = rc::shapeDistance(a, {}, b, {});
  EXPECT_NEAR(o.distance, 1.25f, 1e-6f);
  EXPECT_NEAR(o.pointA.y, 0.25f, 1e-6f);
  EXPECT_NEAR(o.pointB.y, 1.5f, 1e-6f);
  EXPECT_NEAR(o.pointA.x, o.pointB.x, 1e-6f);
  EXPECT_GE(o.pointA.x, -0.5f - 1e-6f);
  EXPECT_LE(o.pointA.x, 1.0f + 1e-6f);
  expectVecNear(o.normal, {0, 1}, 1e-6, "normal");
  // The same pair turned 30 degrees about (3, -1) as one rigid body.
  rc::Rot q = rc::Rot::fromAngle(rc::kPi / 6);
  rc::Transform xf{{3, -1}, q};
  o = rc::shapeDistance(a, xf, b, xf);
  EXPECT_NEAR(o.distance, 1.25f, 2e-6f);
  expectVecNear(o.normal, rc::rotate(q, {0, 1}), 1e-6, "normal");
}

TEST(DistanceHandWorked, OverlapGivesZero) {
  // Circles whose cores are apart but discs overlap: the point is midway between the surfaces.
  rc::DistanceOutput o =
      rc::shapeDistance(rc::makeCircle({0, 0}, 1), {}, rc::makeCircle({1.5f, 0}, 1), {});
  EXPECT_EQ(o.distance, 0.0f);
  EXPECT_EQ(o.pointA, o.pointB);
  expectVecNear(o.pointA, {0.75f, 0}, 1e-6, "point");
  // Boxes whose cores overlap, a circle inside a box, crossing capsules, a segment through a box,
  // a rounded polygon touched only by its rounding, identical shapes in the same place.
  struct Case {
    rc::Shape a;
    rc::Transform xfA;
    rc::Shape b;
    rc::Transform xfB;
  };
  const Case cases[] = {
      {rc::makeBox(1, 1), {}, rc::makeBox(1, 1), {{1.5f, 0.5f}, rc::Rot::fromAngle(0.3f)}},
      {rc::makeBox(2, 2), {}, rc::makeCircle({0.5f, 0.5f}, 0.5f), {}},
      {rc::makeCapsule({-1, 0}, {1, 0}, 0.1f), {}, rc::makeCapsule({0, -1}, {0, 1}, 0.1f), {}},
      {rc::makeBox(1, 1), {}, rc::makeSegment({-3, 0.5f}, {3, 0.5f}), {}},
      {rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}, 0.3f),
       {},
       rc::makeCircle({1.0f, 1.0f}, 0.5f),
       {}},
      {rc::makeBox(1, 1), {{3, 3}, {}}, rc::makeBox(1, 1), {{3, 3}, {}}},
      {rc::makeBox(1, 1), {}, rc::makeBox(1, 1), {{2, 0}, {}}},  // sharing an edge
  };
  for (const Case& c : cases) {
    o = rc::shapeDistance(c.a, c.xfA, c.b, c.xfB);
    SCOPED_TRACE(std::string(rc::shapeTypeName(c.a.type)) + " / " + rc::shapeTypeName(c.b.type));
    EXPECT_EQ(o.distance, 0.0f);
    EXPECT_EQ(o.pointA, o.pointB);
    EXPECT_TRUE(allFinite(o));
    Core ca = worldCore(c.a, c.xfA), cb = worldCore(c.b, c.xfB);
    EXPECT_LE(signedSurfaceDistance(ca, toP2(o.pointA)), 1e-6);
    EXPECT_LE(signedSurfaceDistance(cb, toP2(o.pointA)), 1e-6);
  }
}

// ---------------------------------------------------------------------------------------------
// rc::segmentDistance

TEST(SegmentDistance, Crossing) {
  rc::SegmentDistanceResult r = rc::segmentDistance({0, 0}, {2, 2}, {0, 2}, {2, 0});
  EXPECT_EQ(r.distanceSquared, 0.0f);
  expectVecNear(r.closest1, {1, 1}, 1e-7, "closest1");
  expectVecNear(r.closest2, {1, 1}, 1e-7, "closest2");
  EXPECT_NEAR(r.fraction1, 0.5f, 1e-7f);
  EXPECT_NEAR(r.fraction2, 0.5f, 1e-7f);
}

TEST(SegmentDistance, ParallelOverlapping) {
  // Any x in [1, 3] is a closest pair; both points must share it.
  rc::SegmentDistanceResult r = rc::segmentDistance({0, 0}, {4, 0}, {1, 1}, {3, 1});
  EXPECT_FLOAT_EQ(r.distanceSquared, 1.0f);
  EXPECT_EQ(r.closest1.y, 0.0f);
  EXPECT_EQ(r.closest2.y, 1.0f);
  EXPECT_NEAR(r.closest1.x, r.closest2.x, 1e-7f);
  EXPECT_GE(r.closest1.x, 1.0f);
  EXPECT_LE(r.closest1.x, 3.0f);
  // Opposite directions, same answer.
  r = rc::segmentDistance({4, 0}, {0, 0}, {3, 1}, {1, 1});
  EXPECT_FLOAT_EQ(r.distanceSquared, 1.0f);
  EXPECT_NEAR(r.closest1.x, r.closest2.x, 1e-7f);
  EXPECT_GE(r.closest1.x, 1.0f);
  EXPECT_LE(r.closest1.x, 3.0f);
}

TEST(SegmentDistance, ParallelDisjoint) {
  rc::SegmentDistanceResult r = rc::segmentDistance({0, 0}, {1, 0}, {3, 1}, {5, 1});
  EXPECT_FLOAT_EQ(r.distanceSquared, 5.0f);
  expectVecNear(r.closest1, {1, 0}, 1e-7, "closest1");
  expectVecNear(r.closest2, {3, 1}, 1e-7, "closest2");
  EXPECT_FLOAT_EQ(r.fraction1, 1.0f);
  EXPECT_FLOAT_EQ(r.fraction2, 0.0f);
  // Collinear with a gap.
  r = rc::segmentDistance({0, 0}, {1, 0}, {5, 0}, {3, 0});
  EXPECT_FLOAT_EQ(r.distanceSquared, 4.0f);
  expectVecNear(r.closest1, {1, 0}, 1e-7, "closest1");
  expectVecNear(r.closest2, {3, 0}, 1e-7, "closest2");
  EXPECT_FLOAT_EQ(r.fraction2, 1.0f);
}

TEST(SegmentDistance, DegeneratePointSegments) {
  rc::SegmentDistanceResult r = rc::segmentDistance({1, 1}, {1, 1}, {4, 5}, {4, 5});
  EXPECT_FLOAT_EQ(r.distanceSquared, 25.0f);
  expectVecNear(r.closest1, {1, 1}, 0, "closest1");
  expectVecNear(r.closest2, {4, 5}, 0, "closest2");
  // Point against a segment: projection inside, and beyond either end.
  r = rc::segmentDistance({0, 0}, {4, 0}, {2, 3}, {2, 3});
  EXPECT_FLOAT_EQ(r.distanceSquared, 9.0f);
  expectVecNear(r.closest1, {2, 0}, 1e-7, "closest1");
  EXPECT_FLOAT_EQ(r.fraction1, 0.5f);
  r = rc::segmentDistance({0, 0}, {4, 0}, {6, 3}, {6, 3});
  EXPECT_FLOAT_EQ(r.distanceSquared, 13.0f);
  expectVecNear(r.closest1, {4, 0}, 0, "closest1");
  r = rc::segmentDistance({-2, 3}, {-2, 3}, {0, 0}, {4, 0});
  EXPECT_FLOAT_EQ(r.distanceSquared, 13.0f);
  expectVecNear(r.closest2, {0, 0}, 0, "closest2");
  EXPECT_FLOAT_EQ(r.fraction2, 0.0f);
  // A point on the segment.
  r = rc::segmentDistance({1, 1}, {3, 3}, {2, 2}, {2, 2});
  EXPECT_EQ(r.distanceSquared, 0.0f);
}

// Brute force: 2000 evenly spaced samples on each segment, each measured exactly (closed-form
// projection, double) to the other segment. The sampled minimum is never below the true distance
// and at most half a sampling step above it.
double bruteSegmentDistance(P2 p1, P2 q1, P2 p2, P2 q2, double* step) {
  constexpr int kSamples = 2000;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kSamples; ++i) {
    double s = static_cast<double>(i) / (kSamples - 1);
    P2 a{p1.x + s * (q1.x - p1.x), p1.y + s * (q1.y - p1.y)};
    P2 b{p2.x + s * (q2.x - p2.x), p2.y + s * (q2.y - p2.y)};
    best = std::min(best, pointSegmentDistance(a, p2, q2));
    best = std::min(best, pointSegmentDistance(b, p1, q1));
  }
  *step = std::max(dist(p1, q1), dist(p2, q2)) / (kSamples - 1);
  return best;
}

// Exact reference (up to double rounding): 0 when the segments meet, otherwise the closest pair of
// two disjoint segments always has an endpoint of one of them in it.
double exactSegmentDistance(P2 p1, P2 q1, P2 p2, P2 q2) {
  if (segmentsIntersectRef(p1, q1, p2, q2)) return 0.0;
  return std::min(std::min(pointSegmentDistance(p1, p2, q2), pointSegmentDistance(q1, p2, q2)),
                  std::min(pointSegmentDistance(p2, p1, q1), pointSegmentDistance(q2, p1, q1)));
}

TEST(SegmentDistance, MatchesBruteForceSampler) {
  rc::Random rng(2024);
  int parallel = 0, points = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec2 p1 = rng.inBox({-5, -5}, {5, 5}), q1 = rng.inBox({-5, -5}, {5, 5});
    Vec2 p2 = rng.inBox({-5, -5}, {5, 5}), q2 = rng.inBox({-5, -5}, {5, 5});
    switch (i % 8) {
      case 0:  // parallel (up to float rounding), overlapping or not
        q2 = p2 + rng.uniform(-1.5f, 1.5f) * (q1 - p1);
        ++parallel;
        break;
      case 1:  // nearly parallel and close
        p2 = p1 + rng.inBox({-0.01f, -0.01f}, {0.01f, 0.01f});
        q2 = q1 + rng.inBox({-0.01f, -0.01f}, {0.01f, 0.01f});
        ++parallel;
        break;
      case 2:  // exactly collinear, on an axis
        p1.y = q1.y = p2.y = q2.y = 1.0f;
        ++parallel;
        break;
      case 3:  // a point segment
        q2 = p2;
        ++points;
        break;
      case 4:  // both points
        q1 = p1;
        q2 = p2;
        ++points;
        break;
      case 5:  // sharing an endpoint
        p2 = q1;
        break;
      default:
        break;
    }
    rc::SegmentDistanceResult r = rc::segmentDistance(p1, q1, p2, q2);
    ASSERT_TRUE(rc::isFinite(r.closest1) && rc::isFinite(r.closest2) &&
                rc::isFinite(r.distanceSquared) && rc::isFinite(r.fraction1) &&
                rc::isFinite(r.fraction2))
        << "case " << i;
    double step = 0.0;
    double brute = bruteSegmentDistance(toP2(p1), toP2(q1), toP2(p2), toP2(q2), &step);
    double ours = std::sqrt(static_cast<double>(r.distanceSquared));
    EXPECT_NEAR(ours, brute, 1e-4 + step) << "case " << i;
    // The sampler's tolerance is loose (segments up to 14 m: steps of 7 mm); the exact reference
    // pins the distance to float rounding.
    EXPECT_NEAR(ours, exactSegmentDistance(toP2(p1), toP2(q1), toP2(p2), toP2(q2)), 1e-5)
        << "case " << i;
    // The points are on their segments, at the fractions reported, and as far apart as reported.
    EXPECT_LE(pointSegmentDistance(toP2(r.closest1), toP2(p1), toP2(q1)), 1e-5) << i;
    EXPECT_LE(pointSegmentDistance(toP2(r.closest2), toP2(p2), toP2(q2)), 1e-5) << i;
    EXPECT_GE(r.fraction1, 0.0f);
    EXPECT_LE(r.fraction1, 1.0f);
    EXPECT_GE(r.fraction2, 0.0f);
    EXPECT_LE(r.fraction2, 1.0f);
    expectVecNear(r.closest1, rc::lerp(p1, q1, r.fraction1), 1e-5, "fraction1");
    expectVecNear(r.closest2, rc::lerp(p2, q2, r.fraction2), 1e-5, "fraction2");
    EXPECT_NEAR(ours, dist(toP2(r.closest1), toP2(r.closest2)), 1e-5) << i;
  }
  EXPECT_EQ(parallel, 750);
  EXPECT_EQ(points, 500);
}

TEST(SegmentDistance, NearParallelMatchesExactReference) {
  // The second segment is the first turned by a tiny angle about a point on it and moved sideways
  // by a gap: crossing (gap 0) or apart, at angles where the parallel test must not kick in early.
  rc::Random rng(2025);
  const double angles[] = {1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 1e-1};
  const double gaps[] = {0.0, 1e-6, 1e-4, 1e-2, 0.5};
  for (double angle : angles) {
    for (double gap : gaps) {
      for (int k = 0; k < 50; ++k) {
        Vec2 p1 = rng.inBox({-5, -5}, {5, 5}), q1 = rng.inBox({-5, -5}, {5, 5});
        double pivot = rng.uniformDouble() * 1.4 - 0.2;  // may lie beyond either end
        double ox = p1.x + pivot * (static_cast<double>(q1.x) - p1.x);
        double oy = p1.y + pivot * (static_cast<double>(q1.y) - p1.y);
        double len = dist(toP2(p1), toP2(q1));
        double ux = (static_cast<double>(q1.x) - p1.x) / len,
               uy = (q1.y - static_cast<double>(p1.y)) / len;
        double cs = std::cos(angle), sn = std::sin(angle);
        double vx = cs * ux - sn * uy, vy = sn * ux + cs * uy;  // turned direction
        double h1 = rng.uniformDouble() * 4, h2 = rng.uniformDouble() * 4;
        double nx = -vy * gap, ny = vx * gap;
        Vec2 p2{static_cast<float>(ox - h1 * vx + nx), static_cast<float>(oy - h1 * vy + ny)};
        Vec2 q2{static_cast<float>(ox + h2 * vx + nx), static_cast<float>(oy + h2 * vy + ny)};
        rc::SegmentDistanceResult r = rc::segmentDistance(p1, q1, p2, q2);
        double want = exactSegmentDistance(toP2(p1), toP2(q1), toP2(p2), toP2(q2));
        EXPECT_NEAR(std::sqrt(static_cast<double>(r.distanceSquared)), want, 1e-5)
            << "angle " << angle << " gap " << gap << " k " << k;
        EXPECT_NEAR(dist(toP2(r.closest1), toP2(r.closest2)), want, 1e-5)
            << "angle " << angle << " gap " << gap << " k " << k;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// rc::intersectSegments

// Builds segments crossing at the known point (x0, 0), mapped to the plane by one of four
// reflections/axis swaps (v = 0 is the x axis or the y axis). The base segment lies on v = 0
// exactly; the other is the base turned by `angle` about the crossing point, computed in double
// and rounded to float once.
struct NearParallelCase {
  Vec2 p1, q1, p2, q2;  // p1-q1 on v = 0, p2-q2 turned
  Vec2 crossing;
  double tolerance;
};

Vec2 mapUV(double u, double v, int frame) {
  switch (frame) {
    case 0:
      return {static_cast<float>(u), static_cast<float>(v)};
    case 1:
      return {static_cast<float>(v), static_cast<float>(u)};
    case 2:
      return {static_cast<float>(-u), static_cast<float>(-v)};
    default:
      return {static_cast<float>(-v), static_cast<float>(u)};
  }
}

// Tolerance (stated once, used for every angle). Rounding the turned segment's endpoints to float
// moves each u coordinate by at most 2^-24 (|x0| + h) and each v coordinate by at most
// 2^-24 |v| = 2^-24 h sin(angle): relative to v itself. The rounded line crosses v = 0 at the
// fraction lambda = -v1 / (v2 - v1) of the way from its first to its second endpoint, which
// therefore moves by at most 2^-24 / 2, and the crossing by at most
//   2^-24 (|x0| + h) + 2^-24 / 2 (h1 + h2):
// the sin(angle) cancels, which is why the base segment lies on an axis (a tilted base would put
// ulp / sin(angle) into the answer: metres at 1e-8 rad). intersectSegments then rounds the fraction
// and the point to float (2^-24 of the segment length and of |x0| + length). Summing and doubling:
// tolerance = 4 * 2^-24 * (|x0| + h1 + h2 + L1 + L2), at most 4e-6 m for the values below.
NearParallelCase makeNearParallel(double x0, double angle, double h1, double h2, double l1,
                                  double l2, int frame) {
  NearParallelCase c;
  c.p1 = mapUV(x0 - l1, 0.0, frame);
  c.q1 = mapUV(x0 + l2, 0.0, frame);
  double cs = std::cos(angle), sn = std::sin(angle);
  c.p2 = mapUV(x0 - h1 * cs, -h1 * sn, frame);
  c.q2 = mapUV(x0 + h2 * cs, h2 * sn, frame);
  c.crossing = mapUV(x0, 0.0, frame);
  c.tolerance = 4.0 * kFloatUnitRoundoff * (std::fabs(x0) + h1 + h2 + l1 + l2);
  return c;
}

TEST(SegmentIntersection, NearParallelCrossingAtKnownPoint) {
  const double angles[] = {1e-8, 1e-6, 1e-4, 1e-2, 1e-1};
  const float origins[] = {0.0f, 0.3f, -1.7f, 3.25f, 7.1f};  // floats, so (x0, 0) is exact
  for (double angle : angles) {
    for (float x0f : origins) {
      for (int frame = 0; frame < 4; ++frame) {
        double x0 = x0f;
        NearParallelCase c = makeNearParallel(x0, angle, 1.3, 0.7, 0.9, 2.1, frame);
        SCOPED_TRACE(::testing::Message() << "angle " << angle << " x0 " << x0 << " frame " << frame
                                          << " tolerance " << c.tolerance);
        rc::SegmentIntersection r = rc::intersectSegments(c.p1, c.q1, c.p2, c.q2);
        ASSERT_TRUE(r.hit);
        EXPECT_NEAR(r.point.x, c.crossing.x, c.tolerance);
        EXPECT_NEAR(r.point.y, c.crossing.y, c.tolerance);
        EXPECT_NEAR(r.fraction, 0.9 / 3.0, c.tolerance / 3.0);
        // Turned segment first.
        r = rc::intersectSegments(c.p2, c.q2, c.p1, c.q1);
        ASSERT_TRUE(r.hit);
        EXPECT_NEAR(r.point.x, c.crossing.x, c.tolerance);
        EXPECT_NEAR(r.point.y, c.crossing.y, c.tolerance);
        EXPECT_NEAR(r.fraction, 1.3 / 2.0, c.tolerance / 2.0);
      }
    }
  }
}

TEST(SegmentIntersection, NearParallelGapMisses) {
  const double angles[] = {1e-8, 1e-6, 1e-4, 1e-2, 1e-1};
  for (double angle : angles) {
    for (int frame = 0; frame < 4; ++frame) {
      SCOPED_TRACE(::testing::Message() << "angle " << angle << " frame " << frame);
      double x0 = 1.7, cs = std::cos(angle), sn = std::sin(angle);
      Vec2 p1 = mapUV(x0 - 2.0, 0.0, frame), q1 = mapUV(x0 + 2.0, 0.0, frame);
      // The turned segment stops 1e-3 m (along itself) short of the crossing, on either side:
      // its v coordinates keep their sign through rounding, so it never reaches v = 0.
      for (double side : {1.0, -1.0}) {
        double g = 1e-3, h = 1.5;
        Vec2 a = mapUV(x0 + side * g * cs, side * g * sn, frame);
        Vec2 b = mapUV(x0 + side * (g + h) * cs, side * (g + h) * sn, frame);
        EXPECT_FALSE(rc::intersectSegments(p1, q1, a, b).hit);
        EXPECT_FALSE(rc::intersectSegments(a, b, p1, q1).hit);
        EXPECT_FALSE(rc::intersectSegments(q1, p1, b, a).hit);
      }
      // The lines cross at x0 but the base segment ends 1e-5 m before it (far more than the
      // crossing tolerance of makeNearParallel, about 1e-6 here).
      NearParallelCase c = makeNearParallel(x0, angle, 1.3, 0.7, 2.0, -1e-5, frame);
      EXPECT_FALSE(rc::intersectSegments(c.p1, c.q1, c.p2, c.q2).hit);
      EXPECT_FALSE(rc::intersectSegments(c.p2, c.q2, c.p1, c.q1).hit);
      // Parallel, 2^-20 m apart.
      Vec2 off = mapUV(0.0, 1.0 / 1048576.0, frame) - mapUV(0.0, 0.0, frame);
      EXPECT_FALSE(rc::intersectSegments(p1, q1, p1 + off, q1 + off).hit);
    }
  }
}

TEST(SegmentIntersection, CollinearOverlappingAndDisjoint) {
  // Overlapping: the first shared point along the first segment, whichever way the second runs.
  rc::SegmentIntersection r = rc::intersectSegments({0, 0}, {4, 0}, {2, 0}, {6, 0});
  ASSERT_TRUE(r.hit);
  EXPECT_FLOAT_EQ(r.fraction, 0.5f);
  EXPECT_EQ(r.point, (Vec2{2, 0}));
  r = rc::intersectSegments({0, 0}, {4, 0}, {6, 0}, {2, 0});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.point, (Vec2{2, 0}));
  r = rc::intersectSegments({4, 0}, {0, 0}, {1, 0}, {3, 0});
  ASSERT_TRUE(r.hit);
  EXPECT_FLOAT_EQ(r.fraction, 0.25f);
  EXPECT_EQ(r.point, (Vec2{3, 0}));
  r = rc::intersectSegments({0, 0}, {3, 3}, {-1, -1}, {5, 5});  // second contains the first
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.fraction, 0.0f);
  EXPECT_EQ(r.point, (Vec2{0, 0}));
  r = rc::intersectSegments({0, 0}, {3, 3}, {1, 1}, {2, 2});  // first contains the second
  ASSERT_TRUE(r.hit);
  EXPECT_FLOAT_EQ(r.fraction, 1.0f / 3.0f);
  expectVecNear(r.point, {1, 1}, 1e-6, "point");
  // Disjoint on the same line.
  EXPECT_FALSE(rc::intersectSegments({0, 0}, {1, 0}, {2, 0}, {3, 0}).hit);
  EXPECT_FALSE(rc::intersectSegments({0, 0}, {1, 0}, {3, 0}, {2, 0}).hit);
  EXPECT_FALSE(rc::intersectSegments({2, 2}, {3, 3}, {0, 0}, {1.99f, 1.99f}).hit);
  EXPECT_FALSE(rc::intersectSegments({0, 0}, {1, 0}, {1.0f + 1.0f / 1048576.0f, 0}, {2, 0}).hit);
}

TEST(SegmentIntersection, TouchingAtEndpointsCountsAsHit) {
  // End to end on one line.
  rc::SegmentIntersection r = rc::intersectSegments({0, 0}, {1, 0}, {1, 0}, {2, 0});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.fraction, 1.0f);
  EXPECT_EQ(r.point, (Vec2{1, 0}));
  // An L, both ways round.
  r = rc::intersectSegments({0, 0}, {1, 0}, {1, 0}, {1, 1});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.fraction, 1.0f);
  r = rc::intersectSegments({1, 1}, {1, 0}, {0, 0}, {1, 0});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.fraction, 1.0f);
  EXPECT_EQ(r.point, (Vec2{1, 0}));
  // A T: an endpoint of the second on the inside of the first.
  r = rc::intersectSegments({0, 0}, {2, 0}, {1, 0}, {1, 5});
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.fraction, 0.5f);
  EXPECT_EQ(r.point, (Vec2{1, 0}));
  // Two segments ending at the same point, at coordinates of different magnitudes (so the float
  // differences carry up to ~30 significant bits and their cross products are not exact in
  // double). Found by the random loop below (case 953); kept as a fixed regression case.
  {
    const Vec2 a{0x1.ea0378p+0f, 0x1.5906cep+1f};  // (1.91411543, 2.69552016)
    const Vec2 o{0x1.aa791p+1f, 0x1.6b6d3p+2f};    // (3.33181953, 5.67853928)
    const Vec2 b{0x1.e586bcp-6f, 0x1.67734ap+2f};  // (0.029634174, 5.61641169)
    EXPECT_TRUE(rc::intersectSegments(o, a, o, b).hit);
    EXPECT_TRUE(rc::intersectSegments(a, o, b, o).hit) << "segments sharing their end point";
  }
  // Shared endpoints at arbitrary coordinates, in all four orders: the shared vertex is a hit, and
  // a segment stopping 1e-3 of its length short of it misses.
  rc::Random rng(5);
  int misses[4] = {0, 0, 0, 0}, firstMiss = -1;
  for (int i = 0; i < 1000; ++i) {
    Vec2 o = rng.inBox({-10, -10}, {10, 10});
    Vec2 a = o + rng.inBox({-3, -3}, {3, 3});
    double turn = rng.uniform(0.05f, 3.0f) * (i % 2 == 0 ? 1.0 : -1.0);
    double cs = std::cos(turn), sn = std::sin(turn);
    double dx = static_cast<double>(a.x) - o.x, dy = static_cast<double>(a.y) - o.y;
    Vec2 b{static_cast<float>(o.x + cs * dx - sn * dy),
           static_cast<float>(o.y + sn * dx + cs * dy)};
    const rc::SegmentIntersection hits[4] = {
        rc::intersectSegments(o, a, o, b), rc::intersectSegments(a, o, b, o),
        rc::intersectSegments(a, o, o, b), rc::intersectSegments(o, b, a, o)};
    for (int k = 0; k < 4; ++k) {
      if (!hits[k].hit) {
        ++misses[k];
        if (firstMiss < 0) firstMiss = i;
        continue;
      }
      EXPECT_EQ(hits[k].point, o) << "case " << i << " order " << k;
    }
    if (hits[0].hit) {
      EXPECT_EQ(hits[0].fraction, 0.0f) << i;
    }
    if (hits[1].hit) {
      EXPECT_EQ(hits[1].fraction, 1.0f) << i;
    }
    Vec2 shortEnd = rc::lerp(b, o, 0.999f);
    EXPECT_FALSE(rc::intersectSegments(o, a, b, shortEnd).hit) << i;
    EXPECT_FALSE(rc::intersectSegments(shortEnd, b, a, o).hit) << i;
  }
  EXPECT_EQ(misses[0] + misses[1] + misses[2] + misses[3], 0)
      << "shared endpoint missed: (o,a,o,b) " << misses[0] << ", (a,o,b,o) " << misses[1]
      << ", (a,o,o,b) " << misses[2] << ", (o,b,a,o) " << misses[3] << "; first case " << firstMiss;
  // A fan 1e-8 rad wide sharing its vertex: built on an axis (as in makeNearParallel) so the two
  // segments stay distinct after rounding to float.
  const double fanAngles[] = {1e-8, 1e-6, 1e-4};
  for (double angle : fanAngles) {
    for (int frame = 0; frame < 4; ++frame) {
      Vec2 o = mapUV(2.75, 0.0, frame), a = mapUV(4.25, 0.0, frame);
      Vec2 b = mapUV(2.75 + 1.5 * std::cos(angle), 1.5 * std::sin(angle), frame);
      ASSERT_NE(a, b);
      r = rc::intersectSegments(o, a, o, b);
      ASSERT_TRUE(r.hit) << angle << " " << frame;
      EXPECT_EQ(r.point, o);
      r = rc::intersectSegments(a, o, b, o);
      ASSERT_TRUE(r.hit) << angle << " " << frame;
      EXPECT_EQ(r.point, o);
      EXPECT_EQ(r.fraction, 1.0f);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// rc::trianglesOverlap against an independent brute force: two triangles overlap iff an edge of one
// meets an edge of the other or a vertex of one is inside (or on) the other.

bool pointInTriangleRef(P2 p, const P2 t[3]) {
  int o1 = orient(t[0], t[1], p), o2 = orient(t[1], t[2], p), o3 = orient(t[2], t[0], p);
  return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
}

bool trianglesOverlapRef(const Vec2 a[3], const Vec2 b[3]) {
  P2 pa[3] = {toP2(a[0]), toP2(a[1]), toP2(a[2])};
  P2 pb[3] = {toP2(b[0]), toP2(b[1]), toP2(b[2])};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segmentsIntersectRef(pa[i], pa[(i + 1) % 3], pb[j], pb[(j + 1) % 3])) return true;
    }
  }
  return pointInTriangleRef(pa[0], pb) || pointInTriangleRef(pb[0], pa);
}

bool degenerate(const Vec2 t[3]) {
  return orient(toP2(t[0]), toP2(t[1]), toP2(t[2])) == 0;
}

TEST(TrianglesOverlap, HandCases) {
  const Vec2 a[3] = {{0, 0}, {4, 0}, {0, 4}};
  const Vec2 inside[3] = {{1, 1}, {2, 1}, {1, 2}};
  const Vec2 apart[3] = {{3, 3}, {5, 3}, {3, 5}};      // beyond the hypotenuse x + y = 4
  const Vec2 touching[3] = {{2, 2}, {5, 2}, {2, 5}};   // vertex on the hypotenuse
  const Vec2 edgeShare[3] = {{4, 0}, {0, 4}, {4, 4}};  // shares the hypotenuse
  const Vec2 star[3] = {{-1, 1}, {5, 1}, {2, -2}};     // edges cross, no vertex inside
  EXPECT_TRUE(rc::trianglesOverlap(a, inside));
  EXPECT_TRUE(rc::trianglesOverlap(inside, a));
  EXPECT_FALSE(rc::trianglesOverlap(a, apart));
  EXPECT_TRUE(rc::trianglesOverlap(a, touching));
  EXPECT_TRUE(rc::trianglesOverlap(a, edgeShare));
  EXPECT_TRUE(rc::trianglesOverlap(a, star));
  EXPECT_TRUE(rc::trianglesOverlap(a, a));
}

TEST(TrianglesOverlap, MatchesBruteForceBothWindings) {
  rc::Random rng(77);
  int overlaps = 0, compared = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec2 a[3], b[3];
    if (i % 2 == 0) {
      // Small integer grid: exact coordinates, many touching vertices and shared edges.
      for (Vec2* t : {a, b}) {
        for (int k = 0; k < 3; ++k)
          t[k] = {static_cast<float>(static_cast<int>(rng.below(9)) - 4),
                  static_cast<float>(static_cast<int>(rng.below(9)) - 4)};
      }
    } else {
      Vec2 ca = rng.inBox({-2, -2}, {2, 2}), cb = rng.inBox({-2, -2}, {2, 2});
      float sa = rng.uniform(0.05f, 3.0f), sb = rng.uniform(0.05f, 3.0f);
      for (int k = 0; k < 3; ++k) {
        a[k] = ca + sa * rng.inBox({-1, -1}, {1, 1});
        b[k] = cb + sb * rng.inBox({-1, -1}, {1, 1});
      }
    }
    // Collinear vertices: the reference's point-in-triangle test is only right for triangles
    // with area. Zero-area ones are covered by the tests below.
    if (degenerate(a) || degenerate(b)) continue;
    ++compared;
    bool want = trianglesOverlapRef(a, b);
    overlaps += want ? 1 : 0;
    const Vec2 ra[3] = {a[0], a[2], a[1]}, rb[3] = {b[0], b[2], b[1]};
    EXPECT_EQ(rc::trianglesOverlap(a, b), want) << "case " << i;
    EXPECT_EQ(rc::trianglesOverlap(ra, b), want) << "case " << i;
    EXPECT_EQ(rc::trianglesOverlap(a, rb), want) << "case " << i;
    EXPECT_EQ(rc::trianglesOverlap(ra, rb), want) << "case " << i;
    EXPECT_EQ(rc::trianglesOverlap(b, a), want) << "case " << i;
    EXPECT_EQ(rc::trianglesOverlap(rb, ra), want) << "case " << i;
  }
  EXPECT_GT(compared, 18000);
  EXPECT_GT(overlaps, compared / 5);
  EXPECT_LT(overlaps, compared * 4 / 5);
}

// Zero-area triangles are the segment between their extreme vertices, or a point: the answer is
// whether that point set meets the other triangle (physics/distance.h). Every case is checked in
// both argument orders and all six vertex orders of each side.
void expectOverlap(const Vec2 a[3], const Vec2 b[3], bool want, const char* what) {
  const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (const auto& pa : perms) {
    for (const auto& pb : perms) {
      const Vec2 ta[3] = {a[pa[0]], a[pa[1]], a[pa[2]]}, tb[3] = {b[pb[0]], b[pb[1]], b[pb[2]]};
      EXPECT_EQ(rc::trianglesOverlap(ta, tb), want) << what;
      EXPECT_EQ(rc::trianglesOverlap(tb, ta), want) << what << " (swapped)";
    }
  }
}

TEST(TrianglesOverlap, CollinearHandCases) {
  const Vec2 t[3] = {{0, 0}, {4, 0}, {0, 4}};  // legs on the axes, hypotenuse x + y = 4
  auto segment = [](Vec2 p, Vec2 q, Vec2 m) { return std::array<Vec2, 3>{p, q, m}; };
  auto point = [](Vec2 p) { return std::array<Vec2, 3>{p, p, p}; };

  // A segment (three collinear vertices, the middle one listed anywhere) against a triangle.
  expectOverlap(t, segment({-2, 1}, {5, 1}, {-1, 1}).data(), true, "crosses, no vertex inside");
  expectOverlap(t, segment({-1, 1}, {6, 1}, {1, 1}).data(), true, "crosses, middle inside");
  expectOverlap(t, segment({1, 1}, {2, 1}, {1.5f, 1}).data(), true, "wholly inside");
  expectOverlap(t, segment({3, 3}, {5, 5}, {4, 4}).data(), false, "beyond the hypotenuse");
  expectOverlap(t, segment({5, 0}, {0, 5}, {2.5f, 2.5f}).data(), false, "parallel, outside");
  expectOverlap(t, segment({5, 0}, {7, 0}, {6, 0}).data(), false, "on an edge's line, beyond");
  expectOverlap(t, segment({4, 0}, {6, 0}, {5, 0}).data(), true, "touches a vertex end-on");
  expectOverlap(t, segment({1, 0}, {3, 0}, {2, 0}).data(), true, "lies along an edge");
  expectOverlap(t, segment({2, 2}, {4, 4}, {3, 3}).data(), true, "ends on the hypotenuse");
  expectOverlap(t, segment({1, 1}, {6, 6}, {1, 1}).data(), true, "two equal vertices, crosses");
  expectOverlap(t, segment({5, 5}, {6, 6}, {5, 5}).data(), false, "two equal vertices, apart");

  // A point (three equal vertices) against a triangle.
  expectOverlap(t, point({1, 1}).data(), true, "point inside");
  expectOverlap(t, point({2, 0}).data(), true, "point on an edge");
  expectOverlap(t, point({0, 4}).data(), true, "point on a vertex");
  expectOverlap(t, point({2, 2}).data(), true, "point on the hypotenuse");
  expectOverlap(t, point({3, 3}).data(), false, "point outside");
  expectOverlap(t, point({5, 0}).data(), false, "point on an edge's line, beyond the edge");

  // Two zero-area triangles on one line: overlapping, touching end to end, apart.
  const auto s = segment({0, 0}, {2, 0}, {1, 0});
  expectOverlap(s.data(), segment({1, 0}, {5, 0}, {3, 0}).data(), true, "collinear, overlap");
  expectOverlap(s.data(), segment({2, 0}, {4, 0}, {3, 0}).data(), true, "collinear, end to end");
  expectOverlap(s.data(), segment({3, 0}, {5, 0}, {4, 0}).data(), false, "collinear, apart");
  expectOverlap(s.data(), segment({-1, 0}, {3, 0}, {0, 0}).data(), true, "collinear, contains");
  const auto d = segment({0, 0}, {2, 2}, {1, 1});
  expectOverlap(d.data(), segment({3, 3}, {5, 5}, {4, 4}).data(), false, "diagonal, apart");
  expectOverlap(d.data(), segment({2, 2}, {4, 4}, {3, 3}).data(), true, "diagonal, end to end");

  // Other zero-area pairs: crossing, parallel, points.
  expectOverlap(segment({0, 0}, {2, 2}, {0, 0}).data(), segment({0, 2}, {2, 0}, {2, 0}).data(),
                true, "segments cross");
  expectOverlap(s.data(), segment({0, 1}, {2, 1}, {1, 1}).data(), false, "parallel segments");
  expectOverlap(s.data(), segment({1, -1}, {1, 1}, {1, 0}).data(), true, "T junction");
  expectOverlap(s.data(), point({1.5f, 0}).data(), true, "point on a segment");
  expectOverlap(s.data(), point({3, 0}).data(), false, "point on a segment's line, beyond");
  expectOverlap(s.data(), point({1, 0.5f}).data(), false, "point beside a segment");
  expectOverlap(point({1, 2}).data(), point({1, 2}).data(), true, "equal points");
  expectOverlap(point({1, 2}).data(), point({1, 3}).data(), false, "distinct points");

  // Non-finite coordinates span no point set.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  expectOverlap(t, point({nan, 1}).data(), false, "NaN");
  expectOverlap(t, segment({-inf, 1}, {inf, 1}, {0, 1}).data(), false, "infinite");
}

TEST(TrianglesOverlap, ExactFarFromTheOrigin) {
  // A segment from (X, e) to (-e, X) and the point (X/2, X/2), X = 2^40, e = 2^-40. By hand,
  // (p1 - p0) x (r - p0) = (-e - X)(X/2 - e) - (X - e)(-X/2) = e^2 > 0: the point is off the
  // segment's line (by 2^-80 / |p1 - p0|), so nothing touches. Projections in double round
  // X - e to X and put the point on the line; exact orientation signs do not.
  const float X = 0x1p40f, e = 0x1p-40f;
  const Vec2 segment[3] = {{X, e}, {-e, X}, {X, e}};
  const Vec2 triangle[3] = {{X, e}, {-e, X}, {X, X}};  // the segment plus a far apex
  const Vec2 point[3] = {{X / 2, X / 2}, {X / 2, X / 2}, {X / 2, X / 2}};
  const Vec2 below[3] = {{X / 2, X / 2}, {0, 0}, {0, X / 2}};  // on the origin's side
  const Vec2 endpoint[3] = {{X, e}, {X, e}, {X, e}};
  expectOverlap(segment, point, false, "segment, point e^2 off its line");
  expectOverlap(segment, below, false, "segment, triangle e^2 off its line");
  expectOverlap(triangle, point, false, "triangle, point e^2 off its edge");
  expectOverlap(triangle, below, false, "triangle, triangle e^2 off its edge");
  expectOverlap(segment, endpoint, true, "segment, its endpoint");
  expectOverlap(triangle, endpoint, true, "triangle, its vertex");
}

// Independent reference for any triangles, degenerate or not: the point sets are disjoint iff
// some axis separates their projections, and the candidate axes here are the direction of every
// pair of the six vertices and its perpendicular. That includes every axis the separating axis
// theorem needs: the edge normals of both, the direction of a zero-area triangle's segment (two
// collinear segments, a point beyond a segment's end), the line between two points. The test's
// coordinates are multiples of 2^-9 below 8 in magnitude, so every difference, product and sum
// below is a multiple of 2^-18 below 2^9 (27 significant bits at most): exact in long double
// and in double, touching included.
bool trianglesOverlapSat(const Vec2 a[3], const Vec2 b[3]) {
  const Vec2 all[6] = {a[0], a[1], a[2], b[0], b[1], b[2]};
  auto separates = [&](long double nx, long double ny) {
    long double loA = 1e30L, hiA = -1e30L, loB = 1e30L, hiB = -1e30L;
    for (int k = 0; k < 3; ++k) {
      long double pa = nx * a[k].x + ny * a[k].y, pb = nx * b[k].x + ny * b[k].y;
      loA = std::min(loA, pa);
      hiA = std::max(hiA, pa);
      loB = std::min(loB, pb);
      hiB = std::max(hiB, pb);
    }
    return hiA < loB || hiB < loA;
  };
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      long double dx = static_cast<long double>(all[j].x) - all[i].x;
      long double dy = static_cast<long double>(all[j].y) - all[i].y;
      if (separates(dx, dy) || separates(-dy, dx)) return false;
    }
  }
  return true;
}

TEST(TrianglesOverlap, DegenerateMatchesSeparatingAxes) {
  rc::Random rng(78);
  int zeroArea = 0, zeroAreaOverlaps = 0, points = 0, overlaps = 0;
  constexpr int kCases = 20000;
  for (int i = 0; i < kCases; ++i) {
    // Grid step 1 (many shared vertices, collinear triples, touching) or 1/256 (general
    // position), coordinates within +-4.
    const float step = i % 2 == 0 ? 1.0f : 1.0f / 256.0f;
    const int span = static_cast<int>(4.0f / step);
    auto coordinate = [&] {
      return step * static_cast<float>(static_cast<int>(rng.below(2 * span + 1)) - span);
    };
    auto draw = [&](Vec2 t[3]) {
      switch (rng.below(5)) {
        case 0:
        case 1:  // three free vertices (zero area only by chance)
          for (int k = 0; k < 3; ++k)
            t[k] = {coordinate(), coordinate()};
          break;
        case 2:
        case 3: {  // collinear: p + k d, k in [-2, 2], some k equal
          Vec2 p{coordinate() / 2, coordinate() / 2};
          Vec2 dir{static_cast<float>(static_cast<int>(rng.below(5)) - 2) * step,
                   static_cast<float>(static_cast<int>(rng.below(5)) - 2) * step};
          if (step < 1.0f) dir = 16.0f * dir;
          for (int k = 0; k < 3; ++k)
            t[k] = p + static_cast<float>(static_cast<int>(rng.below(5)) - 2) * dir;
          break;
        }
        default:  // a point
          t[0] = t[1] = t[2] = Vec2{coordinate(), coordinate()};
          break;
      }
    };
    Vec2 a[3], b[3];
    draw(a);
    draw(b);
    bool want = trianglesOverlapSat(a, b);
    bool flat = degenerate(a) || degenerate(b);
    zeroArea += flat ? 1 : 0;
    zeroAreaOverlaps += flat && want ? 1 : 0;
    points += (a[0] == a[1] && a[1] == a[2]) || (b[0] == b[1] && b[1] == b[2]) ? 1 : 0;
    overlaps += want ? 1 : 0;
    const Vec2 ra[3] = {a[2], a[0], a[1]}, rb[3] = {b[1], b[0], b[2]};
    ASSERT_EQ(rc::trianglesOverlap(a, b), want) << "case " << i;
    ASSERT_EQ(rc::trianglesOverlap(b, a), want) << "case " << i;
    ASSERT_EQ(rc::trianglesOverlap(ra, rb), want) << "case " << i;
    ASSERT_EQ(rc::trianglesOverlap(rb, ra), want) << "case " << i;
  }
  // The mix is worth testing: plenty of zero-area triangles and points, overlapping or not.
  EXPECT_GT(zeroArea, kCases / 2);
  EXPECT_GT(points, kCases / 5);
  EXPECT_GT(zeroAreaOverlaps, zeroArea / 10);
  EXPECT_LT(zeroAreaOverlaps, zeroArea * 9 / 10);
  RecordProperty("zero_area_cases", zeroArea);
  RecordProperty("zero_area_overlapping", zeroAreaOverlaps);
  RecordProperty("overlapping", overlaps);
}

// ---------------------------------------------------------------------------------------------
// The seed chapters' plane tests: the line dot(n, x) + d = 0 with n unit.

TEST(PlaneTests, CirclePlaneSeparation) {
  // Line y = 2 (n = (0, 1), d = -2).
  EXPECT_FLOAT_EQ(rc::circlePlaneSeparation({0, 5}, 1, {0, 1}, -2), 2.0f);
  EXPECT_FLOAT_EQ(rc::circlePlaneSeparation({7, 2.5f}, 1, {0, 1}, -2), -0.5f);  // overlaps
  EXPECT_FLOAT_EQ(rc::circlePlaneSeparation({0, 3}, 1, {0, 1}, -2), 0.0f);      // touches
  EXPECT_FLOAT_EQ(rc::circlePlaneSeparation({0, -3}, 1, {0, 1}, -2), -6.0f);    // behind
  // n = (0.6, 0.8), d = 1: centre (3, 4) is 1.8 + 3.2 + 1 = 6 from the line, minus r = 2.
  EXPECT_NEAR(rc::circlePlaneSeparation({3, 4}, 2, {0.6f, 0.8f}, 1), 4.0f, 1e-6f);
}

TEST(PlaneTests, SegmentLineIntersectionSeedFormula) {
  float t = -1.0f;
  // Line y = 2; R0 = (1, 0), v = (0, 4): t = -(0 - 2) / 4.
  ASSERT_TRUE(rc::segmentLineIntersection({1, 0}, {0, 4}, {0, 1}, -2, &t));
  EXPECT_FLOAT_EQ(t, 0.5f);
  // Line 0.6 x + 0.8 y = 5; R0 = 0, v = (10, 0): t = 5 / 6.
  ASSERT_TRUE(rc::segmentLineIntersection({0, 0}, {10, 0}, {0.6f, 0.8f}, -5, &t));
  EXPECT_NEAR(t, 5.0 / 6.0, 1e-6);
  // Endpoints of [0, 1] count.
  ASSERT_TRUE(rc::segmentLineIntersection({0, 2}, {0, 1}, {0, 1}, -2, &t));
  EXPECT_EQ(t, 0.0f);
  ASSERT_TRUE(rc::segmentLineIntersection({0, 1}, {0, 1}, {0, 1}, -2, &t));
  EXPECT_EQ(t, 1.0f);
  // Random lines and segments against the formula in double, away from the ends of [0, 1].
  rc::Random rng(9);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    float angle = rng.uniform(-rc::kPi, rc::kPi);
    rc::SinCos sc = rc::sincos(angle);
    Vec2 n{sc.cosine, sc.sine};
    float d = rng.uniform(-3, 3);
    Vec2 r0 = rng.inBox({-4, -4}, {4, 4}), v = rng.inBox({-6, -6}, {6, 6});
    double vn = static_cast<double>(v.x) * n.x + static_cast<double>(v.y) * n.y;
    double r0n = static_cast<double>(r0.x) * n.x + static_cast<double>(r0.y) * n.y;
    double want = -(r0n + d) / vn;
    if (std::fabs(vn) < 1e-3 || std::fabs(want) < 1e-4 || std::fabs(want - 1) < 1e-4) continue;
    float got = -1.0f;
    bool hit = rc::segmentLineIntersection(r0, v, n, d, &got);
    ASSERT_EQ(hit, want >= 0 && want <= 1) << i;
    if (hit) {
      ++hits;
      EXPECT_NEAR(got, want, 1e-5 * (1 + std::fabs(want)) / std::min(1.0, std::fabs(vn))) << i;
      // The point it names is on the line.
      Vec2 x = rc::mulAdd(r0, got, v);
      EXPECT_NEAR(rc::dot(n, x) + d, 0.0, 1e-5 * (1 + rc::length(v))) << i;
    }
  }
  EXPECT_GT(hits, 500);
}

TEST(PlaneTests, SegmentLineParallelAndOutOfRange) {
  float t = 42.0f;
  // Parallel to y = 2: never crosses, also when it lies on the line.
  EXPECT_FALSE(rc::segmentLineIntersection({0, 0}, {3, 0}, {0, 1}, -2, &t));
  EXPECT_FALSE(rc::segmentLineIntersection({0, 2}, {3, 0}, {0, 1}, -2, &t));
  EXPECT_FALSE(rc::segmentLineIntersection({0, 0}, {0, 0}, {0, 1}, -2, &t));
  // t = 2 and t = -1.
  EXPECT_FALSE(rc::segmentLineIntersection({0, 0}, {0, 1}, {0, 1}, -2, &t));
  EXPECT_FALSE(rc::segmentLineIntersection({0, 3}, {0, 1}, {0, 1}, -2, &t));
  // Just beyond either end.
  EXPECT_FALSE(rc::segmentLineIntersection({0, 0}, {0, 1.999f}, {0, 1}, -2, &t));
  EXPECT_FALSE(rc::segmentLineIntersection({0, 2.001f}, {0, 1}, {0, 1}, -2, &t));
}

// ---------------------------------------------------------------------------------------------
// Properties on random shape pairs of every solid kind, plus segments.

enum Kind { kCircle, kBox, kPolygon, kRoundedPolygon, kCapsule, kSegment, kKindCount };

rc::Shape randomShape(rc::Random& rng, int kind) {
  for (;;) {
    Vec2 c = rng.inBox({-0.5f, -0.5f}, {0.5f, 0.5f});
    try {
      switch (kind) {
        case kCircle:
          return rc::makeCircle(c, rng.uniform(0.05f, 1.2f));
        case kBox:
          return rc::makeBox(rng.uniform(0.05f, 1.2f), rng.uniform(0.05f, 1.2f), c);
        case kPolygon:
        case kRoundedPolygon: {
          int n = 3 + static_cast<int>(rng.below(6));
          float size = rng.uniform(0.1f, 1.5f);
          Vec2 pts[8];
          for (int k = 0; k < n; ++k)
            pts[k] = c + size * rng.inBox({-1, -1}, {1, 1});
          float radius = kind == kRoundedPolygon ? rng.uniform(0.02f, 0.5f) : 0.0f;
          return rc::makePolygon(std::span<const Vec2>(pts, static_cast<size_t>(n)), radius);
        }
        case kCapsule:
          return rc::makeCapsule(c, c + rng.inBox({-1.5f, -1.5f}, {1.5f, 1.5f}),
                                 rng.uniform(0.05f, 0.8f));
        default:
          return rc::makeSegment(c, c + rng.inBox({-2, -2}, {2, 2}));
      }
    } catch (const rc::InvalidShape&) {
      // Degenerate cloud or too-short axis: draw again.
    }
  }
}

// Positions on the 2^-10 grid, so that adding 10000 (the far-from-origin test) is exact in float.
rc::Transform randomTransform(rc::Random& rng, float extent) {
  Vec2 p = rng.inBox({-extent, -extent}, {extent, extent});
  p = {std::round(p.x * 1024.0f) / 1024.0f, std::round(p.y * 1024.0f) / 1024.0f};
  return {p, rc::Rot::fromAngle(rng.uniform(-rc::kPi, rc::kPi))};
}

struct RandomPair {
  rc::Shape a;
  rc::Transform xfA;
  rc::Shape b;
  rc::Transform xfB;
};

std::vector<RandomPair> randomPairs(std::uint64_t seed, int n) {
  rc::Random rng(seed);
  std::vector<RandomPair> pairs;
  pairs.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    rc::Shape a = randomShape(rng, static_cast<int>(rng.below(kKindCount)));
    rc::Shape b = randomShape(rng, static_cast<int>(rng.below(kKindCount)));
    rc::Transform xfA = randomTransform(rng, 1.0f), xfB = randomTransform(rng, 3.0f);
    pairs.push_back({a, xfA, b, xfB});
  }
  return pairs;
}

constexpr int kPropertyPairs = 20000;

std::string describe(const RandomPair& p, int i) {
  return std::string("case ") + std::to_string(i) + " " + rc::shapeTypeName(p.a.type) + " / " +
         rc::shapeTypeName(p.b.type);
}

TEST(DistanceProperties, MatchesVertexEdgeReferenceAndNeverNaN) {
  std::vector<RandomPair> pairs = randomPairs(31, kPropertyPairs);
  int overlapping = 0;
  double worst = 0.0;
  for (int i = 0; i < kPropertyPairs; ++i) {
    const RandomPair& p = pairs[static_cast<size_t>(i)];
    rc::DistanceOutput o = rc::shapeDistance(p.a, p.xfA, p.b, p.xfB);
    ASSERT_TRUE(allFinite(o)) << describe(p, i);
    ASSERT_GE(o.distance, 0.0f) << describe(p, i);
    Core ca = worldCore(p.a, p.xfA), cb = worldCore(p.b, p.xfB);
    double want = referenceDistance(ca, cb);
    worst = std::max(worst, std::fabs(o.distance - want));
    EXPECT_NEAR(o.distance, want, 2e-5) << describe(p, i);
    EXPECT_TRUE(isClosestPair(o, ca, cb, 2e-5)) << describe(p, i);
    if (o.distance > 0.0f) {
      EXPECT_NEAR(rc::length(o.normal), 1.0f, 1e-5f) << describe(p, i);
      Vec2 along = o.pointA + o.distance * o.normal;
      expectVecNear(along, o.pointB, 2e-5, describe(p, i).c_str());
    } else {
      ++overlapping;
    }
  }
  EXPECT_GT(overlapping, kPropertyPairs / 10);
  EXPECT_LT(overlapping, kPropertyPairs * 9 / 10);
  RecordProperty("worst_distance_error", std::to_string(worst));
}

TEST(DistanceProperties, Symmetric) {
  std::vector<RandomPair> pairs = randomPairs(32, kPropertyPairs);
  int differentPoints = 0;
  for (int i = 0; i < kPropertyPairs; ++i) {
    const RandomPair& p = pairs[static_cast<size_t>(i)];
    rc::DistanceOutput ab = rc::shapeDistance(p.a, p.xfA, p.b, p.xfB);
    rc::DistanceOutput ba = rc::shapeDistance(p.b, p.xfB, p.a, p.xfA);
    ASSERT_TRUE(allFinite(ab) && allFinite(ba)) << describe(p, i);
    EXPECT_NEAR(ab.distance, ba.distance, 1e-5) << describe(p, i);
    EXPECT_EQ(ab.distance == 0.0f, ba.distance == 0.0f) << describe(p, i);
    // Points swapped and normal negated. Different points are allowed only where the closest
    // feature is not unique (separated shapes: both answers must then pass isClosestPair) or the
    // cores overlap (normal zero: any common point will do). When only the roundings overlap, the
    // point midway between the surfaces is the same from both sides.
    bool samePoints =
        rc::distance(ab.pointA, ba.pointB) <= 1e-4f && rc::distance(ab.pointB, ba.pointA) <= 1e-4f;
    if (!samePoints) {
      ++differentPoints;
      if (ab.distance > 0.0f) {
        Core ca = worldCore(p.a, p.xfA), cb = worldCore(p.b, p.xfB);
        EXPECT_TRUE(isClosestPair(ab, ca, cb, 2e-5) && isClosestPair(ba, cb, ca, 2e-5))
            << describe(p, i);
      } else {
        EXPECT_TRUE(ab.normal == Vec2{} || ba.normal == Vec2{}) << describe(p, i);
      }
    }
    if (ab.distance > 1e-2f) expectVecNear(ab.normal, -ba.normal, 1e-3, describe(p, i).c_str());
  }
  EXPECT_LT(differentPoints, kPropertyPairs / 100);
}

TEST(DistanceProperties, InvariantUnderCommonRigidMotion) {
  std::vector<RandomPair> pairs = randomPairs(33, kPropertyPairs);
  rc::Random rng(34);
  for (int i = 0; i < kPropertyPairs; ++i) {
    const RandomPair& p = pairs[static_cast<size_t>(i)];
    rc::Transform t{rng.inBox({-10, -10}, {10, 10}), rc::Rot::fromAngle(rng.uniform(-4, 4))};
    rc::Transform xfA = rc::mul(t, p.xfA), xfB = rc::mul(t, p.xfB);
    rc::DistanceOutput o = rc::shapeDistance(p.a, p.xfA, p.b, p.xfB);
    rc::DistanceOutput m = rc::shapeDistance(p.a, xfA, p.b, xfB);
    ASSERT_TRUE(allFinite(m)) << describe(p, i);
    EXPECT_NEAR(o.distance, m.distance, 2e-4) << describe(p, i);
    Vec2 wantA = rc::apply(t, o.pointA), wantB = rc::apply(t, o.pointB);
    if (rc::distance(wantA, m.pointA) > 2e-4f || rc::distance(wantB, m.pointB) > 2e-4f) {
      // Not unique: the moved answer must still be a closest pair of the moved shapes.
      EXPECT_TRUE(isClosestPair(m, worldCore(p.a, xfA), worldCore(p.b, xfB), 2e-4))
          << describe(p, i);
    }
    if (o.distance > 1e-2f) {
      expectVecNear(m.normal, rc::rotate(t.q, o.normal), 1e-3, describe(p, i).c_str());
    }
  }
}

TEST(DistanceProperties, SameAnswerFarFromOrigin) {
  // Both bodies moved by the same exact offset (see randomTransform): 1e4 m away, where a float
  // position has only 2^-10 m resolution. GJK works in A's frame, so only the final conversion of
  // the points to the world frame may differ (half an ulp of 1e4 per coordinate).
  std::vector<RandomPair> pairs = randomPairs(35, kPropertyPairs);
  const Vec2 far{10000.0f, -10000.0f};
  for (int i = 0; i < kPropertyPairs; ++i) {
    const RandomPair& p = pairs[static_cast<size_t>(i)];
    rc::Transform xfA{p.xfA.p + far, p.xfA.q}, xfB{p.xfB.p + far, p.xfB.q};
    ASSERT_EQ(xfA.p - far, p.xfA.p);  // the offset is exact
    ASSERT_EQ(xfB.p - far, p.xfB.p);
    rc::DistanceOutput o = rc::shapeDistance(p.a, p.xfA, p.b, p.xfB);
    rc::DistanceOutput f = rc::shapeDistance(p.a, xfA, p.b, xfB);
    ASSERT_TRUE(allFinite(f)) << describe(p, i);
    EXPECT_NEAR(f.distance, o.distance, 1e-3) << describe(p, i);
    expectVecNear(f.pointA - far, o.pointA, 1e-3, describe(p, i).c_str());
    expectVecNear(f.pointB - far, o.pointB, 1e-3, describe(p, i).c_str());
    expectVecNear(f.normal, o.normal, 1e-5, describe(p, i).c_str());
  }
}

TEST(DistanceProperties, WarmStartMatchesColdStart) {
  // A cache from the previous frame (B moved a little since) gives the same distance.
  std::vector<RandomPair> pairs = randomPairs(36, 5000);
  rc::Random rng(37);
  for (int i = 0; i < 5000; ++i) {
    const RandomPair& p = pairs[static_cast<size_t>(i)];
    rc::ShapeProxy a = rc::makeProxy(p.a), b = rc::makeProxy(p.b);
    rc::SimplexCache cache;
    (void)rc::shapeDistance(a, p.xfA, b, p.xfB, &cache);
    ASSERT_LE(cache.count, 3) << describe(p, i);
    rc::Transform moved{p.xfB.p + rng.inBox({-0.2f, -0.2f}, {0.2f, 0.2f}),
                        rc::mul(p.xfB.q, rc::Rot::fromAngle(rng.uniform(-0.2f, 0.2f)))};
    rc::DistanceOutput warm = rc::shapeDistance(a, p.xfA, b, moved, &cache);
    rc::DistanceOutput cold = rc::shapeDistance(a, p.xfA, b, moved, nullptr);
    ASSERT_TRUE(allFinite(warm)) << describe(p, i);
    EXPECT_NEAR(warm.distance, cold.distance, 1e-5) << describe(p, i);
  }
}

}  // namespace distance_test
