// Reference geometry for the tests, in double (long double for orientation signs), computed
// independently of physics/ except where said: points, point-segment distance, orientation, and
// convex cores (1 to 8 points, counter-clockwise when 3 or more) with a rounding radius.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/distance.h"
#include "physics/math.h"
#include "physics/shapes.h"

namespace rc::testing {

struct P2 {
  double x = 0.0;
  double y = 0.0;
};
inline P2 toP2(Vec2 v) {
  return {v.x, v.y};
}
inline double dist(P2 a, P2 b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}

inline double pointSegmentDistance(P2 p, P2 a, P2 b) {
  double ex = b.x - a.x, ey = b.y - a.y;
  double ee = ex * ex + ey * ey;
  double t = ee > 0.0 ? std::clamp(((p.x - a.x) * ex + (p.y - a.y) * ey) / ee, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - (a.x + t * ex), p.y - (a.y + t * ey));
}

// Sign of the orientation of (a, b, c) in long double (exact or nearly so for float inputs).
inline int orient(P2 a, P2 b, P2 c) {
  long double v = (static_cast<long double>(b.x) - a.x) * (static_cast<long double>(c.y) - a.y) -
                  (static_cast<long double>(b.y) - a.y) * (static_cast<long double>(c.x) - a.x);
  return (v > 0) - (v < 0);
}

// A shape's core in world coordinates and its radius.
struct Core {
  P2 pts[kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;
};

// The core from local points placed by xf, transformed in double.
inline Core worldCore(const Vec2* local, int count, double radius, const Transform& xf) {
  Core c;
  c.count = count;
  c.radius = radius;
  double qc = xf.q.c, qs = xf.q.s;
  for (int i = 0; i < count; ++i) {
    double x = local[i].x, y = local[i].y;
    c.pts[i] = {qc * x - qs * y + xf.p.x, qs * x + qc * y + xf.p.y};
  }
  return c;
}

// Edges of a core: all of them for a polygon, the one segment for 1 or 2 points.
inline int edgeCount(const Core& c) {
  return c.count >= 3 ? c.count : 1;
}
inline P2 edgeStart(const Core& c, int i) {
  return c.pts[i];
}
inline P2 edgeEnd(const Core& c, int i) {
  return c.count >= 3 ? c.pts[(i + 1) % c.count] : c.pts[c.count - 1];
}

inline bool coreContains(const Core& c, P2 p) {
  if (c.count < 3) return false;
  for (int i = 0; i < c.count; ++i)
    if (orient(edgeStart(c, i), edgeEnd(c, i), p) < 0) return false;
  return true;
}

// Signed distance from p to the rounded shape's surface: negative inside.
inline double signedSurfaceDistance(const Core& c, P2 p) {
  double edge = std::numeric_limits<double>::infinity();
  for (int i = 0; i < edgeCount(c); ++i)
    edge = std::min(edge, pointSegmentDistance(p, edgeStart(c, i), edgeEnd(c, i)));
  return (coreContains(c, p) ? -edge : edge) - c.radius;
}

// Support of a placed shape along direction n: max over its core points (rc::makeProxy) of p.n,
// plus the radius.
inline float support(const Shape& s, const Transform& xf, Vec2 n) {
  ShapeProxy p = makeProxy(s);
  float best = -1e30f;
  for (int i = 0; i < p.count; ++i)
    best = std::max(best, dot(apply(xf, p.points[i]), n));
  return best + p.radius;
}

}  // namespace rc::testing
