#include "physics/collide.h"

#include <algorithm>
#include <array>
#include <string>

#include "physics/distance.h"

namespace rc {
namespace {

using ManifoldFn = Manifold (*)(const Shape&, const Transform&, const Shape&, const Transform&);
using OverlapFn = bool (*)(const Shape&, const Transform&, const Shape&, const Transform&);

struct Entry {
  ManifoldFn manifold = nullptr;
  OverlapFn overlap = nullptr;
  bool flip = false;  // registered for (b, a): call with the arguments swapped
};

constexpr int index(ShapeType t) {
  return static_cast<int>(t);
}

Manifold circles(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideCircles(a.circle, xa, b.circle, xb);
}
Manifold capsuleCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideCapsuleAndCircle(a.capsule, xa, b.circle, xb);
}
Manifold boxCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideBoxAndCircle(a.box, xa, b.circle, xb);
}
Manifold polygonCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collidePolygonAndCircle(a.polygon, xa, b.circle, xb);
}
Manifold segmentCircle(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideSegmentAndCircle(a.segment, xa, b.circle, xb);
}
Manifold boxes(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideBoxes(a.box, xa, b.box, xb);
}
Manifold chain(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  return collideChainSegment(a.chainSegment, xa, b, xb);
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
bool overlapGjk(const Shape& a, const Transform& xa, const Shape& b, const Transform& xb) {
  BoundingCircle ba = computeBoundingCircle(a), bb = computeBoundingCircle(b);
  float r = ba.radius + bb.radius;
  if (distanceSquared(apply(xa, ba.center), apply(xb, bb.center)) > r * r) return false;
  return shapeDistance(a, xa, b, xb).distance <= 0.0f;
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

struct Table {
  std::array<std::array<Entry, kShapeTypeCount>, kShapeTypeCount> e{};

  void add(ShapeType a, ShapeType b, ManifoldFn m, OverlapFn o) {
    e[index(a)][index(b)] = {m, o, false};
    if (a != b) e[index(b)][index(a)] = {m, o, true};
  }

  Table() {
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
    add(ShapeType::polygon, ShapeType::circle, polygonCircle, overlapGjk);
    add(ShapeType::segment, ShapeType::circle, segmentCircle, overlapGjk);
    add(ShapeType::box, ShapeType::box, boxes, overlapBoxes);
    // Zero-area pairs: overlap only (static geometry never needs a manifold with itself).
    add(ShapeType::segment, ShapeType::segment, nullptr, overlapSegments);
    add(ShapeType::segment, ShapeType::chainSegment, nullptr, overlapSegments);
    add(ShapeType::chainSegment, ShapeType::chainSegment, nullptr, overlapSegments);
  }
};

const Table& table() {
  static const Table t;
  return t;
}

[[noreturn]] void unsupported(const char* what, ShapeType a, ShapeType b) {
  throw UnsupportedPair(std::string(what) + ": no function registered for " + shapeTypeName(a) +
                        " vs " + shapeTypeName(b));
}

}  // namespace

Manifold collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
  const Entry& e = table().e[index(a.type)][index(b.type)];
  if (e.manifold == nullptr) unsupported("collide", a.type, b.type);
  if (!e.flip) return e.manifold(a, xfA, b, xfB);
  Manifold m = e.manifold(b, xfB, a, xfA);
  m.normal = -m.normal;
  for (int i = 0; i < m.pointCount; ++i)
    std::swap(m.points[i].anchorA, m.points[i].anchorB);
  return m;
}

bool testOverlap(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB) {
  const Entry& e = table().e[index(a.type)][index(b.type)];
  if (e.overlap == nullptr) unsupported("testOverlap", a.type, b.type);
  return e.flip ? e.overlap(b, xfB, a, xfA) : e.overlap(a, xfA, b, xfB);
}

bool hasManifold(ShapeType a, ShapeType b) {
  return table().e[index(a)][index(b)].manifold != nullptr;
}

}  // namespace rc
