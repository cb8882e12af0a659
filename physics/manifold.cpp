#include "physics/manifold.h"

#include <algorithm>
#include <cmath>

#include "physics/distance.h"
#include "physics/simd.h"

namespace rc {
namespace {

using simd::F;

// A shape as a rounded convex hull: 1 to 8 core points, outward edge normals, and a radius.
// A two-point hull (capsule, segment) has two edges: p0 -> p1 and back, with opposite normals.
// The points are kept as x and y lanes, four to a vector, for the separating axis test (see
// maxSeparation); lanes past the last point repeat point 0 up to the end of its group of four.
// They are written whole: a vector load of points written one by one cannot be forwarded from
// the stores and stalls until they retire (that stall made the first four-wide test slower than
// the scalar loop).
struct Hull {
  F x[2], y[2];
  Vec2 n[kMaxPolygonVertices];
  Vec2 centroid;
  int count;
  float radius;

  Vec2 v(int i) const { return {x[i >> 2][i & 3], y[i >> 2][i & 3]}; }
};

// Fills only the first group of lanes and the two normals: a Hull is 144 bytes, and building
// one aside and copying it over was a fifth of a segment-box manifold.
void setTwoPointHull(Hull* out, Vec2 a, Vec2 b, float radius) {
  Hull& h = *out;
  h.count = 2;
  h.radius = radius;
  h.x[0] = F{a.x, b.x, a.x, b.x};
  h.y[0] = F{a.y, b.y, a.y, b.y};
  h.n[0] = normalize(rightPerp(b - a));
  h.n[1] = -h.n[0];
  h.centroid = 0.5f * (a + b);
}

// A polygon's points into the hull's lanes, placed by q and p when `placed` (the same
// arithmetic as apply(): c x - s y + p.x, s x + c y + p.y, lane by lane). Lanes past the last
// point take point 0.
template <bool placed>
[[gnu::always_inline]] inline void setPolygonPoints(Hull& h, const Polygon& g, Rot q, Vec2 p) {
  const int groups = g.count > simd::kLanes ? 2 : 1;
  float x0 = 0.0f, y0 = 0.0f;
  for (int k = 0; k < groups; ++k) {
    F x, y;
    simd::deinterleave(g.vertices + simd::kLanes * k, &x, &y);
    if constexpr (placed) {
      const F c = simd::splat(q.c), sn = simd::splat(q.s);
      const F rx = c * x - sn * y, ry = sn * x + c * y;
      x = rx + simd::splat(p.x);
      y = ry + simd::splat(p.y);
    }
    if (k == 0) {
      x0 = x[0];
      y0 = y[0];
    }
    const simd::M live = simd::M{0, 1, 2, 3} + simd::kLanes * k < g.count;
    h.x[k] = live ? x : simd::splat(x0);
    h.y[k] = live ? y : simd::splat(y0);
  }
}

// The shape as a hull placed by xf (B is built directly in A's frame: one pass, no copy).
void makeHull(const Shape& s, const Transform& xf, Hull* out) {
  Hull& h = *out;
  switch (s.type) {
    case ShapeType::circle:
      h.count = 1;
      h.centroid = apply(xf, s.circle.center);
      h.x[0] = simd::splat(h.centroid.x);
      h.y[0] = simd::splat(h.centroid.y);
      h.radius = s.circle.radius;
      return;
    case ShapeType::box: {
      Vec2 c = s.box.center, e = s.box.halfExtents;
      Vec2 ax = rotate(xf.q, {1.0f, 0.0f}), ay = rotate(xf.q, {0.0f, 1.0f});
      Vec2 wc = apply(xf, c), ex = e.x * ax, ey = e.y * ay;
      h.count = 4;
      h.radius = 0.0f;
      // Corners wc - ex - ey, wc + ex - ey, wc + ex + ey, wc - ex + ey, lane by lane.
      const F sx{-1.0f, 1.0f, 1.0f, -1.0f}, sy{-1.0f, -1.0f, 1.0f, 1.0f};
      h.x[0] = (simd::splat(wc.x) + sx * ex.x) + sy * ey.x;
      h.y[0] = (simd::splat(wc.y) + sx * ex.y) + sy * ey.y;
      h.n[0] = -ay;
      h.n[1] = ax;
      h.n[2] = ay;
      h.n[3] = -ax;
      h.centroid = wc;
      return;
    }
    case ShapeType::polygon:
      h.count = s.polygon.count;
      h.radius = s.polygon.radius;
      setPolygonPoints<true>(h, s.polygon, xf.q, xf.p);
      for (int i = 0; i < h.count; ++i)
        h.n[i] = rotate(xf.q, s.polygon.normals[i]);
      h.centroid = apply(xf, s.polygon.centroid);
      return;
    case ShapeType::capsule:
      setTwoPointHull(&h, apply(xf, s.capsule.center1), apply(xf, s.capsule.center2),
                      s.capsule.radius);
      return;
    case ShapeType::segment:
      setTwoPointHull(&h, apply(xf, s.segment.point1), apply(xf, s.segment.point2), 0.0f);
      return;
    case ShapeType::chainSegment:
      setTwoPointHull(&h, apply(xf, s.chainSegment.segment.point1),
                      apply(xf, s.chainSegment.segment.point2), 0.0f);
      return;
  }
}

// The shape as a hull in its own frame: makeHull with the identity, without the arithmetic
// (x * 1 - y * 0 is not folded away under strict IEEE rules, so the identity transform cost
// 8 multiplies and 6 additions a vertex and normal).
void makeLocalHull(const Shape& s, Hull* out) {
  Hull& h = *out;
  switch (s.type) {
    case ShapeType::circle:
      h.count = 1;
      h.centroid = s.circle.center;
      h.x[0] = simd::splat(h.centroid.x);
      h.y[0] = simd::splat(h.centroid.y);
      h.radius = s.circle.radius;
      return;
    case ShapeType::box: {
      const Vec2 c = s.box.center, e = s.box.halfExtents;
      h.count = 4;
      h.radius = 0.0f;
      h.x[0] = F{c.x - e.x, c.x + e.x, c.x + e.x, c.x - e.x};
      h.y[0] = F{c.y - e.y, c.y - e.y, c.y + e.y, c.y + e.y};
      h.n[0] = {0.0f, -1.0f};
      h.n[1] = {1.0f, 0.0f};
      h.n[2] = {0.0f, 1.0f};
      h.n[3] = {-1.0f, 0.0f};
      h.centroid = c;
      return;
    }
    case ShapeType::polygon:
      h.count = s.polygon.count;
      h.radius = s.polygon.radius;
      setPolygonPoints<false>(h, s.polygon, {}, {});
      // All the slots, a fixed size: a few vector moves instead of a call to memcpy.
      std::copy_n(s.polygon.normals, kMaxPolygonVertices, h.n);
      h.centroid = s.polygon.centroid;
      return;
    case ShapeType::capsule:
      setTwoPointHull(&h, s.capsule.center1, s.capsule.center2, s.capsule.radius);
      return;
    case ShapeType::segment:
      setTwoPointHull(&h, s.segment.point1, s.segment.point2, 0.0f);
      return;
    case ShapeType::chainSegment:
      setTwoPointHull(&h, s.chainSegment.segment.point1, s.chainSegment.segment.point2, 0.0f);
      return;
  }
}

// An empty manifold. Not Manifold{}: that value-initialises both points (64 bytes of zeros
// on every pair that does not touch, most pairs); only pointCount is read.
[[gnu::always_inline]] inline Manifold noContact() {
  Manifold m;
  return m;
}

// A manifold in A's frame before it is placed in the world.
// Only the first `count` points are set; nothing else is zero-filled (this runs per contact
// pair per step, and the fill showed in the profile).
struct Local {
  Vec2 normal{};
  Vec2 point[2];
  float separation[2];
  std::uint16_t id[2];
  int count = 0;

  void add(Vec2 p, float sep, std::uint16_t featureId) {
    point[count] = p;
    separation[count] = sep;
    id[count] = featureId;
    ++count;
  }
};

Manifold toWorld(const Local& m, const Transform& xfA, const Transform& xfB) {
  Manifold out;
  out.normal = rotate(xfA.q, m.normal);
  out.pointCount = m.count;
  Vec2 offset = xfA.p - xfB.p;
  for (int i = 0; i < m.count; ++i) {
    ManifoldPoint& mp = out.points[i];
    mp.anchorA = rotate(xfA.q, m.point[i]);
    mp.anchorB = mp.anchorA + offset;
    mp.point = mp.anchorA + xfA.p;
    mp.separation = m.separation[i];
    mp.id = m.id[i];
  }
  return out;
}

// Point c with radius rc against the convex core (v, n, count) rounded by radius (same frame).
// Normal from the hull towards the point. One point at most: returned as a small value the
// callers turn into their own form (no manifold-sized temporary on the circle paths).
struct PointContact {
  Vec2 normal, point;
  float separation;
  std::uint16_t id;
  bool hit;
};

[[gnu::always_inline]] inline PointContact pointContact(const Vec2* v, const Vec2* n, int count,
                                                        float radius, Vec2 c, float rc,
                                                        float margin) {
  Vec2 normal;
  float dist;
  std::uint16_t id = 0;
  if (count == 1) {
    Vec2 d = c - v[0];
    dist = length(d);
    normal = dist > 0.0f ? (1.0f / dist) * d : Vec2{0.0f, 1.0f};
  } else {
    int best = 0;
    float maxSep = -1e30f;
    const float reach = radius + rc + margin;
#pragma GCC unroll 1  // see support() in distance.cpp: GCC -O3 peeling costs more than it saves
    for (int i = 0; i < count; ++i) {
      float s = dot(n[i], c - v[i]);
      if (s > reach) return {{}, {}, 0.0f, 0, false};  // a face farther than any contact reaches
      if (s > maxSep) {
        maxSep = s;
        best = i;
      }
    }
    normal = n[best];
    dist = maxSep;
    id = static_cast<std::uint16_t>(best);
    if (maxSep > 0.0f) {
      // Outside the core: the face's Voronoi region, or the vertex at either end of it.
      Vec2 v1 = v[best], v2 = v[nextIndex(best, count)];
      Vec2 e = v2 - v1;
      float u = dot(c - v1, e);
      Vec2 corner{};
      bool vertex = false;
      if (u <= 0.0f) {
        corner = v1;
        vertex = true;
        id = static_cast<std::uint16_t>(0x100 | best);
      } else if (u >= lengthSquared(e)) {
        corner = v2;
        vertex = true;
        id = static_cast<std::uint16_t>(0x100 | nextIndex(best, count));
      }
      if (vertex) {
        Vec2 d = c - corner;
        dist = length(d);
        if (dist > 0.0f) normal = (1.0f / dist) * d;
      }
    }
  }
  const float sep = dist - radius - rc;
  if (sep > margin) return {{}, {}, 0.0f, 0, false};
  return {normal, mulSub(c, 0.5f * (rc + dist - radius), normal), sep, id, true};
}

// The hull's core points one after another (the form GJK and the point test take).
ShapeProxy hullProxy(const Hull& h) {
  ShapeProxy p;
  p.count = h.count;
  for (int i = 0; i < h.count; ++i)
    p.points[i] = h.v(i);
  return p;
}

void hullVsPoint(const Hull& h, Vec2 c, float rc, float margin, Local& m) {
  const PointContact pc = pointContact(hullProxy(h).points, h.n, h.count, h.radius, c, rc, margin);
  if (!pc.hit) return;
  m.normal = pc.normal;
  m.add(pc.point, pc.separation, pc.id);
}

// Largest separation of b from a over a's edge normals, and the edge that gives it. Stops at
// the first face farther than `enough`: the shapes are then too far apart for a contact.
// b's points are taken four at a time (its padding repeats real points, which leaves each
// minimum unchanged); each lane computes n.x (x - v.x) + n.y (y - v.y) exactly as dot(n, p - v)
// does, so the result is the scalar loop's to the bit.
float maxSeparation(const Hull& a, const Hull& b, float enough, int* edge) {
  const F bx0 = b.x[0], by0 = b.y[0];
  const bool wide = b.count > simd::kLanes;
  int best = 0;
  float bestSep = -1e30f;
  for (int i = 0; i < a.count; ++i) {
    const F nx = simd::splat(a.n[i].x), ny = simd::splat(a.n[i].y);
    const Vec2 ai = a.v(i);
    const F vx = simd::splat(ai.x), vy = simd::splat(ai.y);
    F d = nx * (bx0 - vx) + ny * (by0 - vy);
    if (wide) d = simd::vmin(d, nx * (b.x[1] - vx) + ny * (b.y[1] - vy));
    const float s = simd::hmin(d);
    if (s > bestSep) {
      bestSep = s;
      best = i;
      if (s > enough) break;
    }
  }
  *edge = best;
  return bestSep;
}

// The edge of `inc` most against the normal n: the incident edge.
[[gnu::always_inline]] inline int incidentEdge(const Hull& inc, Vec2 n) {
  int best = 0;
  float minDot = 1e30f;
  for (int j = 0; j < inc.count; ++j) {
    float dd = dot(n, inc.n[j]);
    if (dd < minDot) {
      minDot = dd;
      best = j;
    }
  }
  return best;
}

// The edge w[0] -> w[1], whose ends lie at u0 and u1 along a face, clipped to the face's
// extent [lo, hi] along it (each end moved to the bound it passed).
[[gnu::always_inline]] inline void clipEdge(const Vec2 (&w)[2], float u0, float u1, float lo,
                                            float hi, Vec2 (&out)[2]) {
  out[0] = w[0];
  out[1] = w[1];
  if (u0 == u1) return;
  auto at = [&](float u) { return lerp(w[0], w[1], (u - u0) / (u1 - u0)); };
  if (u0 < lo) out[0] = at(lo);
  if (u0 > hi) out[0] = at(hi);
  if (u1 < lo) out[1] = at(lo);
  if (u1 > hi) out[1] = at(hi);
}

// Reference face `edge` of `ref` (v1 -> v2, normal n): clips the incident edge of `inc` to the
// slab between the face's side planes and adds the clipped points within `margin` to m, with
// the normal from A to B (flip: the reference is B's face). Returns false, adding nothing, when
// the incident edge lies wholly past an end of the face.
[[gnu::always_inline]] inline bool clipToFace(const Hull& ref, int edge, const Hull& inc, bool flip,
                                              float margin, Local& m) {
  const int i1 = edge, i2 = nextIndex(edge, ref.count);
  const Vec2 v1 = ref.v(i1), v2 = ref.v(i2), n = ref.n[edge];
  const int incEdge = incidentEdge(inc, n);
  Vec2 w[2] = {inc.v(incEdge), inc.v(nextIndex(incEdge, inc.count))};
  int wid[2] = {incEdge, nextIndex(incEdge, inc.count)};

  Vec2 t = normalize(v2 - v1);
  float lo = 0.0f, hi = dot(v2 - v1, t);
  float u0 = dot(w[0] - v1, t), u1 = dot(w[1] - v1, t);
  if ((u0 < lo && u1 < lo) || (u0 > hi && u1 > hi)) return false;
  Vec2 c[2];
  clipEdge(w, u0, u1, lo, hi, c);
  const float refR = ref.radius, incR = inc.radius, radii = refR + incR;
  for (int k = 0; k < 2; ++k) {
    float core = dot(c[k] - v1, n);
    float s = core - radii;
    if (s > margin) continue;
    Vec2 p = mulAdd(c[k], 0.5f * (refR - incR - core), n);
    std::uint16_t id =
        static_cast<std::uint16_t>((flip ? 0x8000 : 0) | (i1 << 8) | (wid[k] << 4) | k);
    m.add(p, s, id);
  }
  if (m.count == 2 && distanceSquared(m.point[0], m.point[1]) < 1e-12f) {
    // A degenerate incident edge (parallel to the normal) clipped to one point.
    if (m.separation[1] < m.separation[0]) {
      m.point[0] = m.point[1];
      m.separation[0] = m.separation[1];
      m.id[0] = m.id[1];
    }
    m.count = 1;
  }
  m.normal = flip ? -n : n;
  return true;
}

// Both hulls in the same frame; normal from a to b. The manifold is written into m (empty on
// entry), which the caller reads field by field: returned by value, a Local written in pieces
// and then copied out whole stalled on store forwarding (a seventh of a segment-box manifold).
void collideLocal(const Hull& a, const Hull& b, float margin, Local& m) {
  if (b.count == 1) return hullVsPoint(a, b.v(0), b.radius, margin, m);
  if (a.count == 1) {
    hullVsPoint(b, a.v(0), a.radius, margin, m);
    m.normal = -m.normal;
    return;
  }
  const float radii = a.radius + b.radius;
  int edgeA, edgeB;
  const float reach = margin + radii;
  float sepA = maxSeparation(a, b, reach, &edgeA);
  if (sepA > reach) return;
  float sepB = maxSeparation(b, a, reach, &edgeB);
  if (sepB > reach) return;

  // Prefer A's face unless B's is clearly better, so the reference face does not flicker
  // between two nearly equal choices from one step to the next.
  const bool flip = sepB > sepA + 0.1f * kLinearSlop;
  const Hull& ref = flip ? b : a;
  const Hull& inc = flip ? a : b;
  const int edge = flip ? edgeB : edgeA;
  const float sep = flip ? sepB : sepA;

  // When the cores are apart, the face separation equals the true distance unless the closest
  // features are two vertices; GJK tells which (its simplex ends as one point pair). Then the
  // normal is the direction between those vertices: the face normal would be off by up to the
  // corner's angle even where its separation is within micrometres of the distance, which for
  // rounded shapes (overlapping surfaces, apart cores) is a real contact. Below half a
  // millimetre of core distance the face normal is kept: the corner normal turns fast there and
  // the separation differs by less than that. The face normals of both shapes are all the
  // separating axes there are (they are the edge normals of the Minkowski difference) unless
  // both are two-point hulls: two parallel segments apart along their common line have a
  // degenerate difference whose end direction is no face normal. Check those always.
  SimplexCache cache;
  DistanceOutput gjk{};
  bool haveGjk = false;
  auto coreDistance = [&]() -> const DistanceOutput& {
    if (!haveGjk) {
      ShapeProxy pa = hullProxy(a), pb = hullProxy(b);
      gjk = shapeDistance(pa, Transform{}, pb, Transform{}, &cache);
      haveGjk = true;
    }
    return gjk;
  };
  auto vertexContact = [&]() {
    const DistanceOutput& d = coreDistance();
    float s = d.distance - radii;
    if (s > margin) return;
    m.normal = d.normal;
    std::uint16_t id =
        static_cast<std::uint16_t>(0x4000 | (cache.indexA[0] << 4) | cache.indexB[0]);
    m.add(mulAdd(d.pointA, a.radius + 0.5f * s, d.normal), s, id);
  };
  // GJK is needed only when the incident shape's deepest vertex along the normal projects past
  // the reference face: otherwise that vertex and its foot on the face realise the separating
  // axis's separation, which is then the distance (the face-vertex case, most contacts).
  bool faceVertex = false;
  if (sep > 0.1f * kLinearSlop && (a.count > 2 || b.count > 2)) {
    const Vec2 v1 = ref.v(edge), e = ref.v(nextIndex(edge, ref.count)) - v1, n = ref.n[edge];
    int k = 0;
    float lowest = dot(n, inc.v(0));
    for (int j = 1; j < inc.count; ++j) {
      const float h = dot(n, inc.v(j));
      if (h < lowest) {
        lowest = h;
        k = j;
      }
    }
    const float u = dot(inc.v(k) - v1, e);
    faceVertex = u >= 0.0f && u <= lengthSquared(e);
  }
  if (!faceVertex && (sep > 0.1f * kLinearSlop || (a.count == 2 && b.count == 2))) {
    const DistanceOutput& d = coreDistance();
    if (d.distance > 0.1f * kLinearSlop &&
        (d.simplexCount == 1 || d.distance > sep + 0.01f * kLinearSlop))
      return vertexContact();
  }

  if (clipToFace(ref, edge, inc, flip, margin, m)) return;
  // The incident edge lies past an end of the reference face: the closest features are that
  // end's vertex and an incident vertex (a case the GJK threshold above can miss by a hair).
  if (coreDistance().distance > 0.1f * kLinearSlop) return vertexContact();
  // Cores overlapping in an odd configuration: keep the deeper incident vertex unclipped.
  const Vec2 v1 = ref.v(edge), n = ref.n[edge];
  const int j = incidentEdge(inc, n);
  const int wid[2] = {j, nextIndex(j, inc.count)};
  const int k = dot(inc.v(wid[0]) - v1, n) <= dot(inc.v(wid[1]) - v1, n) ? 0 : 1;
  const Vec2 w = inc.v(wid[k]);
  const float core = dot(w - v1, n);
  m.normal = flip ? -n : n;
  m.add(mulAdd(w, 0.5f * (ref.radius - inc.radius - core), n), core - radii,
        static_cast<std::uint16_t>((flip ? 0x8000 : 0) | (edge << 8) | (wid[k] << 4) | k));
}

}  // namespace

Manifold collideCircles(const Circle& a, const Transform& xfA, const Circle& b,
                        const Transform& xfB, float margin) {
  // In the world frame: two point transforms, no relative transform to build.
  Vec2 offsetA = rotate(xfA.q, a.center), offsetB = rotate(xfB.q, b.center);
  Vec2 d = (xfB.p - xfA.p) + (offsetB - offsetA);
  float dist2 = lengthSquared(d);
  float reach = a.radius + b.radius + margin;
  if (dist2 > reach * reach) return noContact();
  float dist = std::sqrt(dist2);
  float sep = dist - a.radius - b.radius;
  Manifold m;
  m.normal = dist > 0.0f ? (1.0f / dist) * d : Vec2{0.0f, 1.0f};
  m.pointCount = 1;
  ManifoldPoint& mp = m.points[0];
  mp.anchorA = mulAdd(offsetA, a.radius + 0.5f * sep, m.normal);
  mp.anchorB = mp.anchorA + (xfA.p - xfB.p);
  mp.point = mp.anchorA + xfA.p;
  mp.separation = sep;
  mp.id = 0;
  return m;
}

Manifold collidePolygonAndCircle(const Polygon& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin) {
  const PointContact pc = pointContact(a.vertices, a.normals, a.count, a.radius,
                                       invApply(xfA, apply(xfB, b.center)), b.radius, margin);
  if (!pc.hit) return noContact();
  // The manifold built in place from the one point (see PointContact).
  Manifold out;
  out.normal = rotate(xfA.q, pc.normal);
  out.pointCount = 1;
  ManifoldPoint& mp = out.points[0];
  mp.anchorA = rotate(xfA.q, pc.point);
  mp.anchorB = mp.anchorA + (xfA.p - xfB.p);
  mp.point = mp.anchorA + xfA.p;
  mp.separation = pc.separation;
  mp.id = pc.id;
  return out;
}

Manifold collideSegmentAndCircle(const Segment& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin) {
  return collideCapsuleAndCircle(Capsule{a.point1, a.point2, 0.0f}, xfA, b, xfB, margin);
}

Manifold collideCapsuleAndCircle(const Capsule& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin) {
  Vec2 c = invApply(xfA, apply(xfB, b.center));
  Vec2 e = a.center2 - a.center1;
  float u = dot(c - a.center1, e);
  float ee = lengthSquared(e);
  Local m;
  Vec2 closest;
  float dist;
  std::uint16_t id;
  if (u > 0.0f && u < ee) {
    // Beside the segment: the exact perpendicular, not a normalised difference that loses its
    // direction when the centre is nearly on the segment.
    Vec2 n = normalize(rightPerp(e));
    float side = dot(c - a.center1, n);
    m.normal = side >= 0.0f ? n : -n;
    dist = std::fabs(side);
    closest = mulSub(c, side, n);
    id = 0;
  } else {
    closest = u <= 0.0f ? a.center1 : a.center2;
    Vec2 d = c - closest;
    dist = length(d);
    m.normal = dist > 0.0f ? (1.0f / dist) * d : normalize(rightPerp(e));
    id = u <= 0.0f ? 1 : 2;
  }
  float sep = dist - a.radius - b.radius;
  if (sep > margin) return noContact();
  m.add(mulAdd(closest, a.radius + 0.5f * sep, m.normal), sep, id);
  return toWorld(m, xfA, xfB);
}

Manifold collideBoxAndCircle(const Box& a, const Transform& xfA, const Circle& b,
                             const Transform& xfB, float margin) {
  Vec2 p = invApply(xfA, apply(xfB, b.center)) - a.center;
  Vec2 h = a.halfExtents;
  Local m;
  Vec2 normal;
  float dist;
  std::uint16_t id;
  if (std::fabs(p.x) <= h.x && std::fabs(p.y) <= h.y) {
    // Centre inside: push out through the nearest face.
    float sx = std::fabs(p.x) - h.x, sy = std::fabs(p.y) - h.y;
    if (sx > sy) {
      normal = {p.x >= 0.0f ? 1.0f : -1.0f, 0.0f};
      dist = sx;
      id = p.x >= 0.0f ? 1 : 3;
    } else {
      normal = {0.0f, p.y >= 0.0f ? 1.0f : -1.0f};
      dist = sy;
      id = p.y >= 0.0f ? 2 : 0;
    }
  } else {
    Vec2 q{std::clamp(p.x, -h.x, h.x), std::clamp(p.y, -h.y, h.y)};
    Vec2 d = p - q;
    dist = length(d);
    normal = (1.0f / dist) * d;
    id = static_cast<std::uint16_t>(0x10 | (p.x > h.x ? 1 : (p.x < -h.x ? 2 : 0)) |
                                    (p.y > h.y ? 4 : (p.y < -h.y ? 8 : 0)));
  }
  float sep = dist - b.radius;
  if (sep > margin) return noContact();
  m.normal = normal;
  m.add(a.center + mulSub(p, 0.5f * (b.radius + dist), normal), sep, id);
  return toWorld(m, xfA, xfB);
}

namespace {

// Two boxes at a relative rotation, in closed form: the separating axis test on the two boxes'
// four axes (a box's extent along an axis is |c| hx + |s| hy), then the incident edge clipped
// to the reference face in the reference box's own frame, where that face is axis-aligned. The
// manifold is collideHulls' (same reference-face choice and hysteresis, feature ids and
// contact points, up to rounding: unit test OrientedBoxesMatchTheHullPath); the cases where
// the closest features are two corners (collideHulls asks GJK) go to collideHulls. Resting
// boxes, a pyramid's contacts, took 68 ns through collideHulls.
Manifold collideOrientedBoxes(const Box& a, const Transform& xfA, const Box& b,
                              const Transform& xfB, const Transform& rel, float margin) {
  // B's centre from A's and B's axes (c, s), (-s, c), in A's frame; A's centre in B's frame.
  const Rot q = rel.q;
  const Vec2 centreB = rel.p + rotate(q, b.center);
  const Vec2 d = centreB - a.center, dB = invRotate(q, d);
  const Vec2 hA = a.halfExtents, hB = b.halfExtents;
  const float ac = std::fabs(q.c), as = std::fabs(q.s);
  const float sepAx = std::fabs(d.x) - hA.x - (ac * hB.x + as * hB.y);
  const float sepAy = std::fabs(d.y) - hA.y - (as * hB.x + ac * hB.y);
  const float sepBx = std::fabs(dB.x) - hB.x - (ac * hA.x + as * hA.y);
  const float sepBy = std::fabs(dB.y) - hB.y - (as * hA.x + ac * hA.y);
  const float sepA = std::max(sepAx, sepAy), sepB = std::max(sepBx, sepBy);
  if (sepA > margin || sepB > margin) return noContact();
  // Prefer A's face unless B's is clearly better (collideLocal's hysteresis).
  const bool flip = sepB > sepA + 0.1f * kLinearSlop;

  // The reference box: half extents h, face normal sigma along axis k. The incident box in its
  // frame: centre p, axes u = (c, s), v = (-s, c), half extents e.
  const Vec2 h = flip ? hB : hA, e = flip ? hA : hB;
  const Vec2 p = flip ? -dB : d;
  const float c = q.c, s = flip ? -q.s : q.s;
  const float sepX = flip ? sepBx : sepAx, sepY = flip ? sepBy : sepAy;
  const int k = sepX > sepY ? 0 : 1, t = 1 - k;
  const float sep = k == 0 ? sepX : sepY;
  const float sigma = (k == 0 ? p.x : p.y) >= 0.0f ? 1.0f : -1.0f;
  // A box's faces as collideHulls numbers them: 0 -y, 1 +x, 2 +y, 3 -x; corners 0 (-,-),
  // 1 (+,-), 2 (+,+), 3 (-,+); face i runs from corner i to corner i + 1.
  const int refFace = k == 0 ? (sigma > 0.0f ? 1 : 3) : (sigma > 0.0f ? 2 : 0);
  // The incident face: the one whose normal (+-u, +-v) is most against the reference normal.
  const float uk = k == 0 ? c : s, vk = k == 0 ? -s : c;
  const int incFace =
      std::fabs(uk) > std::fabs(vk) ? (sigma * uk < 0.0f ? 1 : 3) : (sigma * vk < 0.0f ? 2 : 0);
  auto corner = [&](int i) {
    const float sx = (i == 1 || i == 2) ? e.x : -e.x, sy = i >= 2 ? e.y : -e.y;
    return Vec2{p.x + sx * c - sy * s, p.y + sx * s + sy * c};
  };
  auto along = [](Vec2 v, int axis) { return axis == 0 ? v.x : v.y; };
  const int wid[2] = {incFace, nextIndex(incFace, 4)};
  const Vec2 w[2] = {corner(wid[0]), corner(wid[1])};
  const float u0 = along(w[0], t), u1 = along(w[1], t), lo = -along(h, t), hi = along(h, t);
  // Closest features two corners (apart by more than a tenth of the slop, the deepest incident
  // corner beside the face), or the incident edge wholly past an end of the face: GJK's cases.
  const int deepest = sigma * along(w[0], k) <= sigma * along(w[1], k) ? 0 : 1;
  const float ud = along(w[deepest], t);
  if ((sep > 0.1f * kLinearSlop && (ud < lo || ud > hi)) || (u0 < lo && u1 < lo) ||
      (u0 > hi && u1 > hi))
    return collideHulls(Shape(a), xfA, Shape(b), xfB, margin);

  Vec2 clipped[2];
  clipEdge(w, u0, u1, lo, hi, clipped);
  Local m;
  const Vec2 n = k == 0 ? Vec2{sigma, 0.0f} : Vec2{0.0f, sigma};
  for (int j = 0; j < 2; ++j) {
    const float core = sigma * along(clipped[j], k) - along(h, k);
    if (core > margin) continue;
    // Halfway between the incident point and the reference face, back in A's frame.
    Vec2 point = mulAdd(clipped[j], -0.5f * core, n);
    point = flip ? centreB + rotate(q, point) : a.center + point;
    m.add(point, core,
          static_cast<std::uint16_t>((flip ? 0x8000 : 0) | (refFace << 8) | (wid[j] << 4) | j));
  }
  m.normal = flip ? -rotate(q, n) : n;
  return toWorld(m, xfA, xfB);
}

}  // namespace

Manifold collideBoxes(const Box& a, const Transform& xfA, const Box& b, const Transform& xfB,
                      float margin) {
  Transform rel = invMul(xfA, xfB);
  if (!rel.q.isIdentity()) return collideOrientedBoxes(a, xfA, b, xfB, rel, margin);
  // Aligned boxes: the separating axis is x or y, and the contact points are the ends of the
  // overlap of the two boxes' extents along the other axis.
  Vec2 cA = a.center, cB = rel.p + b.center;
  Vec2 hA = a.halfExtents, hB = b.halfExtents;
  Vec2 d = cB - cA;
  float sepX = std::fabs(d.x) - hA.x - hB.x;
  float sepY = std::fabs(d.y) - hA.y - hB.y;
  if (sepX > margin || sepY > margin) return noContact();
  if (sepX > 0.0f && sepY > 0.0f) {
    // Corner to corner: the closest features are two vertices.
    return collideHulls(Shape(a), xfA, Shape(b), xfB, margin);
  }
  Local m;
  int axis = sepX > sepY ? 0 : 1;
  float sep = axis == 0 ? sepX : sepY;
  float sign = (axis == 0 ? d.x : d.y) >= 0.0f ? 1.0f : -1.0f;
  int o = 1 - axis;
  float cAo = o == 0 ? cA.x : cA.y, cBo = o == 0 ? cB.x : cB.y;
  float hAo = o == 0 ? hA.x : hA.y, hBo = o == 0 ? hB.x : hB.y;
  float lo = std::max(cAo - hAo, cBo - hBo), hi = std::min(cAo + hAo, cBo + hBo);
  float faceA = (axis == 0 ? cA.x : cA.y) + sign * (axis == 0 ? hA.x : hA.y);
  float mid = faceA + 0.5f * sign * sep;
  m.normal = axis == 0 ? Vec2{sign, 0.0f} : Vec2{0.0f, sign};
  std::uint16_t base = static_cast<std::uint16_t>(0x2000 | (axis << 2) | (sign > 0.0f ? 2 : 0));
  for (int k = 0; k < 2; ++k) {
    float u = k == 0 ? lo : hi;
    Vec2 p = axis == 0 ? Vec2{mid, u} : Vec2{u, mid};
    m.add(p, sep, static_cast<std::uint16_t>(base | k));
    if (hi - lo <= 0.0f) break;
  }
  return toWorld(m, xfA, xfB);
}

Manifold collideHulls(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                      float margin) {
  Hull ha, hb;
  makeLocalHull(a, &ha);
  makeHull(b, invMul(xfA, xfB), &hb);
  Local m;
  collideLocal(ha, hb, margin, m);
  return toWorld(m, xfA, xfB);
}

namespace {
// A one-point manifold in the world frame, built in place (a single return: no copy).
// Normal and point are in A's frame.
[[gnu::always_inline]] inline Manifold onePoint(Vec2 normal, Vec2 point, float separation,
                                                std::uint16_t id, const Transform& xfA,
                                                const Transform& xfB) {
  Manifold out;
  out.normal = rotate(xfA.q, normal);
  out.pointCount = 1;
  ManifoldPoint& mp = out.points[0];
  mp.anchorA = rotate(xfA.q, point);
  mp.point = mp.anchorA + xfA.p;
  mp.anchorB = mp.anchorA + (xfA.p - xfB.p);
  mp.separation = separation;
  mp.id = id;
  return out;
}

[[gnu::always_inline]] inline Manifold chainSegmentAndCircle(const ChainSegment& a,
                                                             const Transform& xfA, const Circle& b,
                                                             const Transform& xfB, float margin) {
  // The rules of collideChainSegment below, for a point, in the link's frame: a face contact
  // never leans, so only the end regions meet the joints (2.5x faster than the general path,
  // which builds two hulls).
  const Vec2 c = invApply(xfA, apply(xfB, b.center));
  Vec2 p1 = a.segment.point1, p2 = a.segment.point2;
  bool reversed = false;
  if (dot(c - p1, rightPerp(p2 - p1)) < 0.0f) {
    if (a.oneSided) return noContact();
    std::swap(p1, p2);
    reversed = true;
  }
  const Vec2 e = p2 - p1;
  const float u = dot(c - p1, e), ee = lengthSquared(e);
  const float reach = b.radius + margin;  // squared tests first: most pairs are out of reach
  if (u > 0.0f && u < ee) {
    const float side = dot(c - p1, rightPerp(e));  // distance times |e|, >= 0
    if (side * side > reach * reach * ee) return noContact();
    const float inv = 1.0f / std::sqrt(ee);
    const Vec2 n = inv * rightPerp(e);
    const float dist = side * inv;
    const float sep = dist - b.radius;
    if (sep > margin) return noContact();
    return onePoint(n, mulSub(c, 0.5f * (b.radius + dist), n), sep, 0, xfA, xfB);
  }
  const bool atStart = u <= 0.0f;
  const Vec2 joint = atStart ? p1 : p2;
  const Vec2 d = c - joint;
  if (lengthSquared(d) > reach * reach) return noContact();
  const float dist = length(d);
  const float sep = dist - b.radius;
  if (sep > margin) return noContact();
  const Vec2 normal = dist > 0.0f ? (1.0f / dist) * d : normalize(rightPerp(e));
  const Vec2 point = mulSub(c, 0.5f * (b.radius + dist), normal);
  const auto id = static_cast<std::uint16_t>(0x100 | !atStart);
  const float tangential = dot(normal, e);
  if (tangential * tangential <= 1e-8f * ee) return onePoint(normal, point, sep, id, xfA, xfB);
  // The neighbour beyond the joint, in the link's direction.
  const Vec2 ghost = atStart != reversed ? a.ghost1 : a.ghost2;
  const Vec2 e0 = atStart ? p1 - ghost : e, e1 = atStart ? e : ghost - p2;
  const Vec2 neighbour = atStart ? e0 : e1;
  if (lengthSquared(neighbour) == 0.0f)  // an open end: its cap
    return onePoint(normal, point, sep, id, xfA, xfB);
  const Vec2 nN = normalize(rightPerp(neighbour));
  const bool convex = cross(e0, e1) > 0.0f;
  if (convex && (atStart ? cross(nN, normal) >= -1e-4f : cross(normal, nN) >= -1e-4f))
    return onePoint(normal, point, sep, id, xfA, xfB);
  // Past what the joint allows: the neighbour's, unless it cannot see the circle. Then only a
  // convex joint's vertex can hold it (the link's face does not reach past its end).
  if (!a.oneSided || dot(d, nN) >= 0.0f || !convex) return noContact();
  const float s = dot(nN, d) - b.radius;
  if (s > margin) return noContact();
  return onePoint(nN, mulAdd(joint, 0.5f * s, nN), s, static_cast<std::uint16_t>(0x2000 | !atStart),
                  xfA, xfB);
}

}  // namespace

Manifold collideChainSegmentAndCircle(const ChainSegment& a, const Transform& xfA, const Circle& b,
                                      const Transform& xfB, float margin) {
  return chainSegmentAndCircle(a, xfA, b, xfB, margin);
}

Manifold collideChainSegmentAndCircleShapes(const Shape& a, const Transform& xfA, const Shape& b,
                                            const Transform& xfB, float margin) {
  return chainSegmentAndCircle(a.chainSegment, xfA, b.circle, xfB, margin);
}

Manifold collideChainSegment(const ChainSegment& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB, float margin) {
  const Transform rel = invMul(xfA, xfB);
  if (b.type == ShapeType::box || b.type == ShapeType::polygon) {
    // The link's line first, with the shape where it is (one rotation of the line's normal
    // instead of moving every point and normal of the shape): a shape wholly farther than the
    // margin on either side of the line touches nothing.
    const Vec2 p = a.segment.point1, e = a.segment.point2 - p, n = rightPerp(e);  // |n| = |e|
    const Vec2 nB = invRotate(rel.q, n);
    float lo, hi, radius;
    if (b.type == ShapeType::box) {
      const float mid = dot(nB, b.box.center);
      const float half =
          std::fabs(nB.x) * b.box.halfExtents.x + std::fabs(nB.y) * b.box.halfExtents.y;
      lo = mid - half;
      hi = mid + half;
      radius = 0.0f;
    } else {
      lo = hi = dot(nB, b.polygon.vertices[0]);
      for (int i = 1; i < b.polygon.count; ++i) {
        const float h = dot(nB, b.polygon.vertices[i]);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
      }
      radius = b.polygon.radius;
    }
    const float offset = dot(n, rel.p - p);
    const float reach = margin + radius;
    const float reach2 = reach * reach * lengthSquared(e);
    const float front = offset + lo, back = offset + hi;
    if ((front > 0.0f && front * front > reach2) || (back < 0.0f && back * back > reach2))
      return noContact();
  }
  Hull hb;
  makeHull(b, rel, &hb);
  Vec2 p1 = a.segment.point1, p2 = a.segment.point2, g1 = a.ghost1, g2 = a.ghost2;
  if (dot(hb.centroid - p1, rightPerp(p2 - p1)) < 0.0f) {
    if (a.oneSided) return noContact();
    // Seen from the left: reverse the link so the shape is on its right.
    std::swap(p1, p2);
    std::swap(g1, g2);
  }
  Hull ha;
  setTwoPointHull(&ha, p1, p2, 0.0f);
  Local m;
  collideLocal(ha, hb, margin, m);
  if (m.count == 0) return noContact();
  if (hb.count > 1 && (m.id[0] & 0xC700) == 0x0100) {
    // The link's back face (reference face 1 of its two-point hull; a point shape's contacts
    // have ids of their own, and never take the back face of a link they are in front of):
    // that push would drive the shape through the link to the side it is not on. The link's
    // front face decides instead.
    m.count = 0;
    if (!clipToFace(ha, 0, hb, false, margin, m) || m.count == 0) return noContact();
  }
  const Vec2 e = p2 - p1;
  // |normal . e| > 1e-4 |e|, without the square root.
  const float tangential = dot(m.normal, e);
  if (tangential * tangential > 1e-8f * lengthSquared(e)) {
    // The normal leans towards a joint. The neighbour beyond it is e0 (into the joint) and e1
    // (out of it), in the link's direction; its collision-side normal is nN.
    const bool atStart = tangential < 0.0f;
    const Vec2 e0 = atStart ? p1 - g1 : e, e1 = atStart ? e : g2 - p2;
    const Vec2 neighbour = atStart ? e0 : e1;
    if (lengthSquared(neighbour) == 0.0f) return toWorld(m, xfA, xfB);  // an open end: its cap
    const Vec2 nN = normalize(rightPerp(neighbour));
    // At a convex joint the normals fan from this link's to the neighbour's; a flat or concave
    // joint has only this link's.
    // (A normal 1e-4 rad past the neighbour's still counts: a face of the shape lying along the
    // neighbour is common and must not flicker between the two answers.)
    const bool admissible = cross(e0, e1) > 0.0f && (atStart ? cross(nN, m.normal) >= -1e-4f
                                                             : cross(m.normal, nN) >= -1e-4f);
    const Vec2 joint = atStart ? p1 : p2;
    if (!admissible) {
      // A normal from closest points (a point contact, two vertices) or from a face of the
      // shape while the cores are apart (this link's end against that face) points into the
      // neighbour's region: the neighbour is closer and reports that contact, unless it cannot
      // see the shape (one-sided, with the shape's centre behind it: the shape has crossed it).
      const bool bFace = (m.id[0] & 0xC000) == 0x8000;
      float deepest = m.separation[0];
      for (int k = 1; k < m.count; ++k)
        deepest = std::min(deepest, m.separation[k]);
      const bool neighbourSees = !a.oneSided || dot(hb.centroid - joint, nN) >= 0.0f;
      if ((!bFace || deepest + hb.radius > 0.0f) && neighbourSees) return noContact();
      // Otherwise (a face of the shape while the cores cross) the normal is clamped to the
      // nearest ones the joint allows, and the one that separates more is kept. This link's face is
      // always allowed: at a flat or concave joint it is the only choice (a shape pressed into a
      // valley is pushed out of both walls, one across a flat joint out of the floor). Past a
      // convex joint's fan the neighbour's normal is the other, at the joint's vertex (the
      // neighbour may report the same push: two points pushing one way are harmless, a ghost normal
      // is not).
      Local face;
      const bool haveFace = clipToFace(ha, 0, hb, false, margin, face) && face.count > 0;
      if (cross(e0, e1) > 0.0f) {
        float s = 1e30f;
        for (int j = 0; j < hb.count; ++j)
          s = std::min(s, dot(nN, hb.v(j) - joint));
        s -= hb.radius;
        float faceDeepest = 1e30f;
        for (int k = 0; k < face.count; ++k)
          faceDeepest = std::min(faceDeepest, face.separation[k]);
        if (s <= margin && (!haveFace || s > faceDeepest)) {
          m.count = 0;
          m.normal = nN;
          m.add(mulAdd(joint, 0.5f * s, nN), s, static_cast<std::uint16_t>(0x2000 | !atStart));
          return toWorld(m, xfA, xfB);
        }
      }
      if (!haveFace) return noContact();
      return toWorld(face, xfA, xfB);
    }
  }
  return toWorld(m, xfA, xfB);
}

}  // namespace rc
