// Ricochet physics: distance between convex shapes (GJK), segment closest points, and the
// segment/line and plane tests of the seed chapters.
//
// Every solid shape is a convex point set (1 to 8 points) swept by a radius: a circle is one point
// and a radius, a capsule two points and a radius, a box or polygon its vertices and its rounding.
// GJK works on those cores and the radii are applied at the end. It runs in shape A's frame, so
// two shapes 1e4 m from the origin are as accurate as two at the origin.
#pragma once

#include <cstdint>

#include "physics/shapes.h"

namespace rc {

struct ShapeProxy {
  Vec2 points[kMaxPolygonVertices]{};
  int count = 0;
  float radius = 0.0f;
};

ShapeProxy makeProxy(const Shape& s);
ShapeProxy makeProxy(const Vec2* points, int count, float radius);

// Kept between calls for the same pair to start GJK from last time's simplex (warm start).
struct SimplexCache {
  std::uint8_t count = 0;
  std::uint8_t indexA[3]{};
  std::uint8_t indexB[3]{};
};

struct DistanceOutput {
  Vec2 pointA{};          // closest point on A (on its rounded surface), world frame
  Vec2 pointB{};          // closest point on B, world frame
  Vec2 normal{};          // unit vector from A to B; zero when the cores overlap
  float distance = 0.0f;  // surface distance, 0 when the shapes overlap
  int iterations = 0;
  int simplexCount = 0;
};

// Distance between the rounded shapes. When they overlap the distance is 0 and both points are
// the same point between the cores.
DistanceOutput shapeDistance(const ShapeProxy& a, const Transform& xfA, const ShapeProxy& b,
                             const Transform& xfB, SimplexCache* cache = nullptr);
DistanceOutput shapeDistance(const Shape& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB);

struct SegmentDistanceResult {
  Vec2 closest1{};  // on segment p1 + s (q1 - p1)
  Vec2 closest2{};  // on segment p2 + t (q2 - p2)
  float fraction1 = 0.0f;
  float fraction2 = 0.0f;
  float distanceSquared = 0.0f;
};
// Closest points of two segments; exact for parallel and degenerate (point) segments.
SegmentDistanceResult segmentDistance(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2);

// Proper intersection of segments [p1, q1] and [p2, q2] (touching counts). On a hit, fraction
// along the first segment. Collinear overlapping segments report the first shared point.
struct SegmentIntersection {
  bool hit = false;
  float fraction = 0.0f;
  Vec2 point{};
};
SegmentIntersection intersectSegments(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2);

// Whether the closed triangles share a point (boundaries touching count), in either winding.
// A zero-area triangle is not rejected: it is the point set it spans, the segment between its
// two extreme vertices (a point when all three coincide), and the answer is whether that set
// meets the other triangle, itself possibly degenerate. The answer is exact for every finite
// input (exact orientation signs, no tolerance). A non-finite coordinate (NaN, infinity) spans
// no point set: the answer is false.
bool trianglesOverlap(const Vec2 a[3], const Vec2 b[3]);

// The seed chapters' plane tests. A line (plane) is the points x with dot(n, x) + d = 0, n unit.
// Signed distance of a circle to the half-plane dot(n, x) + d <= 0: negative means overlap.
float circlePlaneSeparation(Vec2 center, float radius, Vec2 n, float d);
// Where segment R0 + t v crosses the line: t = -(dot(R0, n) + d) / dot(v, n), reported only for
// t in [0, 1]. A segment parallel to the line never crosses it (returns false).
bool segmentLineIntersection(Vec2 r0, Vec2 v, Vec2 n, float d, float* t);

}  // namespace rc
