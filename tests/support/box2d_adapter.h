// Our shapes and transforms as Box2D 2.4.1 objects, for the oracle tests and the benchmarks.
//
// Skin: Box2D 2.4.1 gives every polygon and edge a radius of b2_polygonRadius (0.01 m). The
// adapter sets m_radius = 0 on sharp polygons and edges after building them, so both engines
// describe the same sharp shapes and do the same work. A rounded polygon becomes a
// b2PolygonShape with m_radius = our radius: Box2D's distance, overlap and manifold routines
// round polygons by m_radius (its manifolds by face normals only, see manifold_oracle_test.cpp),
// but its RayCast and ComputeMass ignore it.
//
// A chain link becomes the b2EdgeShape that b2ChainShape::GetChildEdge makes: one-sided with its
// ghost vertices (SetOneSided(ghost1, point1, point2, ghost2)), or two-sided without them.
#pragma once

#include <box2d/b2_distance.h>
#include <box2d/box2d.h>

#include "physics/distance.h"
#include "physics/shapes.h"
#include "physics/toi.h"

namespace rc::testing {

inline b2Transform toB2(const Transform& xf) {
  b2Transform t;
  t.p.Set(xf.p.x, xf.p.y);
  t.q.c = xf.q.c;  // the same rotation bits on both sides
  t.q.s = xf.q.s;
  return t;
}

struct Box2DShape {
  b2CircleShape circle;
  b2PolygonShape polygon;
  b2EdgeShape edge;
  b2Shape::Type type = b2Shape::e_circle;

  const b2Shape* get() const {
    switch (type) {
      case b2Shape::e_circle:
        return &circle;
      case b2Shape::e_polygon:
        return &polygon;
      default:
        return &edge;
    }
  }
};

// True when b2PolygonShape::Set would weld two of these vertices (closer than half of
// b2_linearSlop): Box2D would build another polygon or, left with fewer than 3 points, assert.
// Our hull welds polygons under 25 cm at 1% of their size instead (shapes.cpp, weldRadius).
inline bool box2dWouldWeld(const Vec2* v, int count) {
  constexpr float kWeld = 0.5f * b2_linearSlop;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j)
      if (distanceSquared(v[i], v[j]) < kWeld * kWeld) return true;
  return false;
}

// Returns false for shapes Box2D 2.4.1 has no type for (capsules), for a polygon whose hull
// Box2D builds with a different vertex count (nearly collinear points), and for slivers of less
// than 1e-5 m^2.
inline bool toB2(const Shape& s, Box2DShape* o) {
  switch (s.type) {
    case ShapeType::circle:
      o->type = b2Shape::e_circle;
      o->circle.m_p.Set(s.circle.center.x, s.circle.center.y);
      o->circle.m_radius = s.circle.radius;
      return true;
    case ShapeType::box:
      o->type = b2Shape::e_polygon;
      o->polygon.SetAsBox(s.box.halfExtents.x, s.box.halfExtents.y,
                          {s.box.center.x, s.box.center.y}, 0.0f);
      o->polygon.m_radius = 0.0f;
      return true;
    case ShapeType::polygon: {
      // Box2D 2.4.1 asserts (b2PolygonShape::Set, ComputeCentroid: area > b2_epsilon) on
      // slivers that our hull accepts: leave those to the caller to draw again.
      float twiceArea = 0.0f;
      for (int i = 0; i < s.polygon.count; ++i)
        twiceArea +=
            cross(s.polygon.vertices[i], s.polygon.vertices[nextIndex(i, s.polygon.count)]);
      if (twiceArea < 2e-5f || box2dWouldWeld(s.polygon.vertices, s.polygon.count)) return false;
      o->type = b2Shape::e_polygon;
      b2Vec2 v[b2_maxPolygonVertices];
      for (int i = 0; i < s.polygon.count; ++i)
        v[i].Set(s.polygon.vertices[i].x, s.polygon.vertices[i].y);
      o->polygon.Set(v, s.polygon.count);
      o->polygon.m_radius = s.polygon.radius;
      return o->polygon.m_count == s.polygon.count;  // Box2D's hull agreed with ours
    }
    case ShapeType::segment:
      o->type = b2Shape::e_edge;
      o->edge.SetTwoSided({s.segment.point1.x, s.segment.point1.y},
                          {s.segment.point2.x, s.segment.point2.y});
      o->edge.m_radius = 0.0f;
      return true;
    case ShapeType::chainSegment: {
      const ChainSegment& c = s.chainSegment;
      auto v = [](Vec2 p) { return b2Vec2(p.x, p.y); };
      o->type = b2Shape::e_edge;
      if (c.oneSided)
        o->edge.SetOneSided(v(c.ghost1), v(c.segment.point1), v(c.segment.point2), v(c.ghost2));
      else
        o->edge.SetTwoSided(v(c.segment.point1), v(c.segment.point2));
      o->edge.m_radius = 0.0f;
      return true;
    }
    default:
      return false;
  }
}

// A b2DistanceProxy over our core points and radius (no skin), for b2Distance and
// b2TimeOfImpact. The proxy points into `points`: fill it in place and do not copy it.
struct Box2DProxy {
  b2Vec2 points[b2_maxPolygonVertices];
  b2DistanceProxy proxy;

  void set(const ShapeProxy& p) {
    static_assert(kMaxPolygonVertices <= b2_maxPolygonVertices);
    for (int i = 0; i < p.count; ++i)
      points[i].Set(p.points[i].x, p.points[i].y);
    proxy.m_vertices = points;
    proxy.m_count = p.count;
    proxy.m_radius = p.radius;
  }
};

// b2Distance between two Box2D proxies with a cold simplex cache: the oracles' independent
// distance.
inline b2DistanceOutput box2dDistance(const b2DistanceProxy& a, const b2Transform& xfA,
                                      const b2DistanceProxy& b, const b2Transform& xfB,
                                      bool useRadii) {
  b2DistanceInput input;
  input.proxyA = a;
  input.proxyB = b;
  input.transformA = xfA;
  input.transformB = xfB;
  input.useRadii = useRadii;
  b2SimplexCache cache;
  cache.count = 0;
  cache.metric = 0.0f;
  b2DistanceOutput out;
  b2Distance(&out, &cache, &input);
  return out;
}

// The same between our proxies (the same core points and radii).
inline b2DistanceOutput box2dDistance(const ShapeProxy& a, const b2Transform& xfA,
                                      const ShapeProxy& b, const b2Transform& xfB, bool useRadii) {
  Box2DProxy qa, qb;  // the b2DistanceProxy objects point into these
  qa.set(a);
  qb.set(b);
  return box2dDistance(qa.proxy, xfA, qb.proxy, xfB, useRadii);
}

// The same motion: both engines interpolate centre and angle linearly in t (Box2D builds the
// rotation with the C library's sinf/cosf, ours with rc::sincos; they differ by ~1e-7).
inline b2Sweep toB2(const Sweep& s) {
  b2Sweep w;
  w.localCenter.Set(s.localCenter.x, s.localCenter.y);
  w.c0.Set(s.c1.x, s.c1.y);
  w.c.Set(s.c2.x, s.c2.y);
  w.a0 = s.a1;
  w.a = s.a2;
  w.alpha0 = 0.0f;
  return w;
}

}  // namespace rc::testing
