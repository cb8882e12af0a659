#include "physics/collide.h"

#include <algorithm>
#include <array>
#include <string>

#include "physics/distance.h"

namespace rc {
namespace {

using detail::ManifoldFn;
using detail::OverlapFn;

constexpr int index(ShapeType t) {
  return static_cast<int>(t);
}

Manifold circles(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                 float margin) {
  return collideCircles(a.circle, xa, b.circle, xb, margin);
}
Manifold capsuleCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       float margin) {
  return collideCapsuleAndCircle(a.capsule, xa, b.circle, xb, margin);
}
Manifold boxCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                   float margin) {
  return collideBoxAndCircle(a.box, xa, b.circle, xb, margin);
}
Manifold polygonCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       float margin) {
  return collidePolygonAndCircle(a.polygon, xa, b.circle, xb, margin);
}
Manifold segmentCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
                       float margin) {
  return collideSegmentAndCircle(a.segment, xa, b.circle, xb, margin);
}
Manifold boxes(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
               float margin) {
  return collideBoxes(a.box, xa, b.box, xb, margin);
}
Manifold chain(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb,
               float margin) {
  return collideChainSegment(a.chainSegment, xa, b, xb, margin);
}

bool overlapCircles(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  float r = a.circle.radius + b.circle.radius;
  return distanceSquared(apply(xa, a.circle.center), apply(xb, b.circle.center)) <= r * r;
}
bool overlapBoxCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  Vec2 p = invApply(xa, apply(xb, b.circle.center)) - a.box.center;
  Vec2 h = a.box.halfExtents;
  Vec2 q{std::clamp(p.x, -h.x, h.x), std::clamp(p.y, -h.y, h.y)};
  return distanceSquared(p, q) <= b.circle.radius * b.circle.radius;
}
bool overlapCapsuleCircle(const Shape& a, const Transform& xa, const Shape& b,
                          const Transform& xb) {
  Vec2 c = invApply(xa, apply(xb, b.circle.center));
  Vec2 p = a.capsule.center1, e = a.capsule.center2 - p;
  float u = std::clamp(dot(c - p, e) / lengthSquared(e), 0.0f, 1.0f);
  float r = a.capsule.radius + b.circle.radius;
  return distanceSquared(c, mulAdd(p, u, e)) <= r * r;
}
// No bounding-circle test first: on pairs whose AABBs overlap (what the broadphase hands on)
// the circles rejected 0-4% and cost 10-24% of the query (geometry_bench, overlap-prefilter
// rows); the AABB is the cheap bound of this hierarchy.
bool overlapGjk(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return shapeDistance(a, xa, b, xb).distance <= 0.0f;
}
// Sharp convex polygons (boxes and polygons without rounding): the separating axis test on the
// face normals of both, stopping at the first axis that separates. Cheaper than GJK here and
// exact (the face normals are the only candidate axes for two convex polygons with area).
struct SharpCore {
  Vec2 v[kMaxPolygonVertices];
  Vec2 n[kMaxPolygonVertices];
  int count;
};
void sharpCore(const Shape& s, const Transform& xf, SharpCore* out) {
  if (s.type == ShapeType::box) {
    Vec2 c = s.box.center, e = s.box.halfExtents;
    Vec2 ax = rotate(xf.q, {1.0f, 0.0f}), ay = rotate(xf.q, {0.0f, 1.0f});
    Vec2 wc = apply(xf, c), ex = e.x * ax, ey = e.y * ay;
    out->count = 4;
    out->v[0] = wc - ex - ey;
    out->v[1] = wc + ex - ey;
    out->v[2] = wc + ex + ey;
    out->v[3] = wc - ex + ey;
    out->n[0] = -ay;
    out->n[1] = ax;
    out->n[2] = ay;
    out->n[3] = -ax;
    return;
  }
  if (s.type == ShapeType::segment) {
    // A segment is a two-sided face; with a partner that has area, its normal and the
    // partner's face normals are every candidate axis.
    out->count = 2;
    out->v[0] = apply(xf, s.segment.point1);
    out->v[1] = apply(xf, s.segment.point2);
    out->n[0] = normalize(rightPerp(out->v[1] - out->v[0]));
    out->n[1] = -out->n[0];
    return;
  }
  const Polygon& p = s.polygon;
  out->count = p.count;
  for (int i = 0; i < p.count; ++i) {
    out->v[i] = apply(xf, p.vertices[i]);
    out->n[i] = rotate(xf.q, p.normals[i]);
  }
}
bool separatedByFaces(const SharpCore& a, const SharpCore& b) {
  for (int i = 0; i < a.count; ++i) {
    float best = 1e30f;
    for (int j = 0; j < b.count; ++j)
      best = std::min(best, dot(a.n[i], b.v[j] - a.v[i]));
    if (best > 0.0f) return true;
  }
  return false;
}
bool overlapSharpPolygons(const Shape& a, const Transform& xa, const Shape& b,
                          const Transform& xb) {
  bool roundedA = a.type == ShapeType::polygon && a.polygon.radius > 0.0f;
  bool roundedB = b.type == ShapeType::polygon && b.polygon.radius > 0.0f;
  if (roundedA || roundedB) return shapeDistance(a, xa, b, xb).distance <= 0.0f;
  SharpCore ca, cb;
  sharpCore(a, Transform{}, &ca);
  sharpCore(b, invMul(xa, xb), &cb);
  return !separatedByFaces(ca, cb) && !separatedByFaces(cb, ca);
}

bool overlapPolygonCircle(const Shape& a, const Transform& xa, const Shape& b,
                          const Transform& xb) {
  // Distance from the centre to the core: the face of largest separation, or the vertex at
  // either end of it when the centre projects past that face (exact for convex polygons).
  const Polygon& p = a.polygon;
  Vec2 c = invApply(xa, apply(xb, b.circle.center));
  float r = p.radius + b.circle.radius;
  int best = 0;
  float maxSep = -1e30f;
  for (int i = 0; i < p.count; ++i) {
    float sep = dot(p.normals[i], c - p.vertices[i]);
    if (sep > r) return false;
    if (sep > maxSep) {
      maxSep = sep;
      best = i;
    }
  }
  if (maxSep <= 0.0f) return true;
  Vec2 v1 = p.vertices[best], v2 = p.vertices[nextIndex(best, p.count)];
  Vec2 e = v2 - v1;
  float u = dot(c - v1, e);
  if (u <= 0.0f) return distanceSquared(c, v1) <= r * r;
  if (u >= lengthSquared(e)) return distanceSquared(c, v2) <= r * r;
  return true;  // beside the face, and maxSep <= r
}
// A segment or a chain link (overlap ignores sidedness, as Box2D's b2TestOverlap does).
bool overlapSegmentCircle(const Shape& a, const Transform& xa, const Shape& b,
                          const Transform& xb) {
  const Segment& g = a.type == ShapeType::segment ? a.segment : a.chainSegment.segment;
  Vec2 c = invApply(xa, apply(xb, b.circle.center));
  Vec2 p = g.point1, e = g.point2 - p;
  float u = std::clamp(dot(c - p, e) / lengthSquared(e), 0.0f, 1.0f);
  return distanceSquared(c, mulAdd(p, u, e)) <= b.circle.radius * b.circle.radius;
}

bool overlapBoxes(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  Transform rel = invMul(xa, xb);
  if (!rel.q.isIdentity()) {
    // Oriented boxes: separating axis test on the four face normals.
    Vec2 d = rotate(rel.q, b.box.center) + rel.p - a.box.center;
    Vec2 hA = a.box.halfExtents, hB = b.box.halfExtents;
    float c = std::fabs(rel.q.c), s = std::fabs(rel.q.s);
    if (std::fabs(d.x) > hA.x + c * hB.x + s * hB.y) return false;
    if (std::fabs(d.y) > hA.y + s * hB.x + c * hB.y) return false;
    Vec2 dl = invRotate(rel.q, d);
    if (std::fabs(dl.x) > hB.x + c * hA.x + s * hA.y) return false;
    if (std::fabs(dl.y) > hB.y + s * hA.x + c * hA.y) return false;
    return true;
  }
  Vec2 d = abs(rel.p + b.box.center - a.box.center);
  return d.x <= a.box.halfExtents.x + b.box.halfExtents.x &&
         d.y <= a.box.halfExtents.y + b.box.halfExtents.y;
}
bool overlapSegments(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  const Segment& sa = a.type == ShapeType::segment ? a.segment : a.chainSegment.segment;
  const Segment& sb = b.type == ShapeType::segment ? b.segment : b.chainSegment.segment;
  return intersectSegments(apply(xa, sa.point1), apply(xa, sa.point2), apply(xb, sb.point1),
                           apply(xb, sb.point2))
      .hit;
}

struct Table : detail::PairTable {
  constexpr void add(ShapeType a, ShapeType b, ManifoldFn m, OverlapFn o) {
    e[index(a)][index(b)] = {m, o, false};
    if (a != b) e[index(b)][index(a)] = {m, o, true};
  }

  constexpr Table() {
    constexpr ShapeType solids[] = {ShapeType::circle, ShapeType::box, ShapeType::polygon,
                                    ShapeType::capsule};
    // The general path first; specialised pairs overwrite it below.
    for (ShapeType x : solids) {
      for (ShapeType y : solids)
        add(x, y, collideHulls, overlapGjk);
      add(x, ShapeType::segment, collideHulls, overlapGjk);
      add(ShapeType::chainSegment, x, chain, overlapGjk);
    }
    add(ShapeType::circle, ShapeType::circle, circles, overlapCircles);
    add(ShapeType::capsule, ShapeType::circle, capsuleCircle, overlapCapsuleCircle);
    add(ShapeType::box, ShapeType::circle, boxCircle, overlapBoxCircle);
    add(ShapeType::polygon, ShapeType::circle, polygonCircle, overlapPolygonCircle);
    add(ShapeType::segment, ShapeType::circle, segmentCircle, overlapSegmentCircle);
    add(ShapeType::chainSegment, ShapeType::circle, collideChainSegmentAndCircleShapes,
        overlapSegmentCircle);
    add(ShapeType::box, ShapeType::polygon, collideHulls, overlapSharpPolygons);
    add(ShapeType::segment, ShapeType::polygon, collideHulls, overlapSharpPolygons);
    add(ShapeType::segment, ShapeType::box, collideHulls, overlapSharpPolygons);
    add(ShapeType::polygon, ShapeType::polygon, collideHulls, overlapSharpPolygons);
    add(ShapeType::box, ShapeType::box, boxes, overlapBoxes);
    // Zero-area pairs: overlap only (static geometry never needs a manifold with itself).
    add(ShapeType::segment, ShapeType::segment, nullptr, overlapSegments);
    add(ShapeType::segment, ShapeType::chainSegment, nullptr, overlapSegments);
    add(ShapeType::chainSegment, ShapeType::chainSegment, nullptr, overlapSegments);
  }
};

}  // namespace

// Built at compile time (constinit): no initialisation guard on the per-pair path.
constinit const detail::PairTable detail::kPairTable = Table{};

void detail::unsupportedPair(const char* what, ShapeType a, ShapeType b) {
  throw UnsupportedPair(std::string(what) + ": no function registered for " + shapeTypeName(a) +
                        " vs " + shapeTypeName(b));
}

Manifold detail::flipped(Manifold m) {
  m.normal = -m.normal;
  for (int i = 0; i < m.pointCount; ++i)
    std::swap(m.points[i].anchorA, m.points[i].anchorB);
  return m;
}

bool hasManifold(ShapeType a, ShapeType b) {
  return detail::kPairTable.e[index(a)][index(b)].manifold != nullptr;
}

}  // namespace rc
