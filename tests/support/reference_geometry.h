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

// Signed distance between two rounded convex shapes (cores and radii): the gap between the
// surfaces when positive, minus the penetration depth (the shortest translation that separates
// them) when negative. Written from the definitions, independently of physics/ (no GJK, no
// clipping), as the arbiter of the overlap oracle.
//
// Candidate axes: the edge normals of both cores; for a 2-point core also its direction; for a
// 1-point core the direction to the other core's centroid. Two disjoint convex cores are
// separated along one of them (the separating axis theorem gives the edge normals for cores with
// area; two disjoint segments on one line need the direction; two points the line through
// them). The distance between disjoint convex sets is then the minimum over edge pairs of the
// segment-segment distance, which is the minimum over every vertex of one core and every edge of
// the other of the point-to-segment distance (a closest pair always includes a vertex; a 1-point
// core is a degenerate edge); that is what is computed, without repeating pairs. When no axis
// separates, the cores intersect and the depth is the minimum over the same axes of the
// projection overlap: exact, because the faces of the Minkowski difference A - B have the edge
// normals of both cores, and any other axis only gives a larger overlap (an upper bound).
inline double signedDistance(const Core& a, const Core& b) {
  double ux[2 * kMaxPolygonVertices], uy[2 * kMaxPolygonVertices];  // unit axes
  int axisCount = 0;
  auto addAxis = [&](double x, double y) {
    double len = std::sqrt(x * x + y * y);  // metres, no overflow: hypot's care is not needed
    if (len > 0.0) {
      ux[axisCount] = x / len;
      uy[axisCount++] = y / len;
    }
  };
  auto addAxesOf = [&](const Core& c, const Core& other) {
    if (c.count == 1) {
      P2 m{};
      for (int i = 0; i < other.count; ++i) {
        m.x += other.pts[i].x / other.count;
        m.y += other.pts[i].y / other.count;
      }
      addAxis(m.x - c.pts[0].x, m.y - c.pts[0].y);
      return;
    }
    for (int i = 0; i < edgeCount(c); ++i) {
      P2 s = edgeStart(c, i), e = edgeEnd(c, i);
      addAxis(s.y - e.y, e.x - s.x);                    // normal
      if (c.count == 2) addAxis(e.x - s.x, e.y - s.y);  // direction
    }
  };
  addAxesOf(a, b);
  addAxesOf(b, a);

  // The projection of both cores on each axis: separated when the intervals are apart, else
  // overlapping by min(maxA - minB, maxB - minA), the translation along the axis that parts them.
  double depth = std::numeric_limits<double>::infinity();
  for (int k = 0; k < axisCount; ++k) {
    auto interval = [&](const Core& c, double* lo, double* hi) {
      *lo = std::numeric_limits<double>::infinity();
      *hi = -*lo;
      for (int i = 0; i < c.count; ++i) {
        double p = c.pts[i].x * ux[k] + c.pts[i].y * uy[k];
        *lo = std::min(*lo, p);
        *hi = std::max(*hi, p);
      }
    };
    double loA, hiA, loB, hiB;
    interval(a, &loA, &hiA);
    interval(b, &loB, &hiB);
    const double gap = std::max(loB - hiA, loA - hiB);
    if (gap > 0.0) {
      // Squared distances from the vertices of `v` to the edges of `c` (pointSegmentDistance
      // without the square root, one reciprocal per edge: the oracle runs this millions of times).
      auto vertexEdge = [](const Core& v, const Core& c) {
        double best = std::numeric_limits<double>::infinity();
        for (int j = 0; j < edgeCount(c); ++j) {
          const P2 s = edgeStart(c, j), e = edgeEnd(c, j);
          const double ex = e.x - s.x, ey = e.y - s.y, ee = ex * ex + ey * ey;
          const double inv = ee > 0.0 ? 1.0 / ee : 0.0;
          for (int i = 0; i < v.count; ++i) {
            const double px = v.pts[i].x - s.x, py = v.pts[i].y - s.y;
            const double t = std::min(std::max((px * ex + py * ey) * inv, 0.0), 1.0);
            const double dx = px - t * ex, dy = py - t * ey;
            best = std::min(best, dx * dx + dy * dy);
          }
        }
        return best;
      };
      return std::sqrt(std::min(vertexEdge(a, b), vertexEdge(b, a))) - a.radius - b.radius;
    }
    depth = std::min(depth, -gap);
  }
  // No axis at all only for two 1-point cores at the same point: touching cores, depth 0.
  if (axisCount == 0) depth = 0.0;
  return -depth - a.radius - b.radius;
}

// A convex polygon in long double, counter-clockwise: the exact shape a test means, before its
// vertices are rounded to float for the factory.
struct ExactPolygon {
  long double x[kMaxPolygonVertices] = {};
  long double y[kMaxPolygonVertices] = {};
  int count = 0;
};

// Area, centroid and polar moment about the centroid, by the shoelace sums in long double about
// the first vertex (so a small polygon far from the origin keeps its digits).
struct ExactMass {
  long double area = 0, cx = 0, cy = 0, inertia = 0;
};
inline ExactMass exactMass(const ExactPolygon& p) {
  const long double ox = p.x[0], oy = p.y[0];
  long double a2 = 0, sx = 0, sy = 0, j = 0;  // twice the area, 6 x first moments, 12 x polar
  for (int k = 0; k < p.count; ++k) {
    const int l = (k + 1) % p.count;
    const long double px = p.x[k] - ox, py = p.y[k] - oy, qx = p.x[l] - ox, qy = p.y[l] - oy;
    const long double c = px * qy - qx * py;
    a2 += c;
    sx += c * (px + qx);
    sy += c * (py + qy);
    j += c * (px * px + px * qx + qx * qx + py * py + py * qy + qy * qy);
  }
  ExactMass m;
  m.area = a2 / 2;
  const long double x = sx / (3 * a2), y = sy / (3 * a2);
  m.inertia = j / 12 - m.area * (x * x + y * y);
  m.cx = ox + x;
  m.cy = oy + y;
  return m;
}

inline long double perimeter(const ExactPolygon& p) {
  long double sum = 0;
  for (int k = 0; k < p.count; ++k) {
    const int l = (k + 1) % p.count;
    sum += std::hypot(p.x[l] - p.x[k], p.y[l] - p.y[k]);
  }
  return sum;
}

// Where the ray o + t d, t in [0, tMax], enters the polygon (origin outside): the latest entry
// over the edges' half-planes (Cyrus-Beck) in long double, and the edge entered there.
struct ExactEntry {
  bool hit = false;
  long double t = 0;
  int edge = -1;
};
inline ExactEntry exactEntry(const ExactPolygon& p, long double ox, long double oy, long double dx,
                             long double dy, long double tMax) {
  long double lower = 0, upper = tMax;
  int edge = -1;
  for (int k = 0; k < p.count; ++k) {
    const int l = (k + 1) % p.count;
    const long double nx = p.y[l] - p.y[k], ny = p.x[k] - p.x[l];  // outward, not unit
    const long double num = nx * (p.x[k] - ox) + ny * (p.y[k] - oy), den = nx * dx + ny * dy;
    if (den == 0) {
      if (num < 0) return {};
    } else if (den < 0) {
      if (num / den > lower) {
        lower = num / den;
        edge = k;
      }
    } else {
      upper = std::min(upper, num / den);
    }
    if (upper < lower) return {};
  }
  if (edge < 0) return {};
  return {true, lower, edge};
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
