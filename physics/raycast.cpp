#include "physics/raycast.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {
namespace {

// Results are returned as prvalues built in place: a local filled field by field and then
// copied out costs a store-forwarding stall on the copy (~1/3 of a circle cast).
constexpr CastOutput hitAt(Vec2 normal, Vec2 point, float fraction) {
  return {normal, point, fraction, 0, true};
}

// The normal against the ray. A translation whose squared length overflows (a polygon's cast
// takes such rays unscaled) is shortened by an exact power of two first.
CastOutput startsInside(const RayCastInput& in) {
  Vec2 d = in.translation;
  if (!std::isfinite(lengthSquared(d))) d = 0x1p-70f * d;
  return hitAt(-normalize(d), in.origin, 0.0f);
}

// Ray against a circle, stable for rays far longer than the radius: project the centre on the
// ray and take the half chord from the perpendicular distance (no b^2 - 4ac cancellation).
CastOutput castCircle(Vec2 center, float radius, const RayCastInput& in, float length, Vec2 dir) {
  CastOutput out;
  Vec2 s = center - in.origin;
  float tc = dot(s, dir);
  Vec2 perp = mulSub(s, tc, dir);
  float h2 = radius * radius - lengthSquared(perp);
  if (h2 < 0.0f) return out;
  float t = tc - std::sqrt(h2);
  if (t < 0.0f || t > in.maxFraction * length) return out;
  out.fraction = t / length;
  out.point = mulAdd(in.origin, t, dir);
  out.normal = normalize(out.point - center);
  out.hit = true;
  return out;
}

void keepCloser(CastOutput& best, const CastOutput& c) {
  if (c.hit && (!best.hit || c.fraction < best.fraction)) best = c;
}

// Ray against a disc on the unscaled translation d: project the centre on the ray and take the
// half chord from the perpendicular distance (the stable form of castCircle, without the ray's
// length).
[[gnu::always_inline]] inline CastOutput castDisc(Vec2 center, float r, const RayCastInput& in) {
  const Vec2 s = center - in.origin, d = in.translation;
  const float inv = 1.0f / lengthSquared(d);
  const float tc = dot(s, d) * inv;
  const Vec2 perp = mulSub(s, tc, d);
  const float h2 = (r * r - lengthSquared(perp)) * inv;
  if (!(h2 >= 0.0f)) return {};
  const float t = tc - std::sqrt(h2);
  if (t < 0.0f || t > in.maxFraction) return {};
  const Vec2 p = mulAdd(in.origin, t, d);
  return hitAt(normalize(p - center), p, t);
}

// Ray against the capsule a-b swept by r, in the capsule's own axes: u along a -> b, the
// perpendicular coordinate of the origin qp and its rate dp. From outside the band |qp| <= r the
// ray can only enter through the side facing it, at t = (+-r - qp) / dp; if that point lies
// beyond an end, or the origin is already within the band beyond an end, the first hit can only
// be that end's disc (the disc fills the band's cross-section at the end). One division, at most
// one disc: a third of casting both discs and both sides. With insideCheck, an origin inside
// reports fraction 0 against the ray (raycast.h).
CastOutput castCapsule(Vec2 a, Vec2 b, float r, const RayCastInput& in, bool insideCheck) {
  const Vec2 e = b - a;
  const float len2 = lengthSquared(e);
  if (len2 == 0.0f) {
    if (insideCheck && distanceSquared(in.origin, a) <= r * r) return startsInside(in);
    return castDisc(a, r, in);
  }
  const float len = std::sqrt(len2);
  const Vec2 u = (1.0f / len) * e;
  const Vec2 q = in.origin - a, d = in.translation;
  const float qa = dot(q, u), qp = cross(u, q);
  if (std::fabs(qp) <= r) {
    if (qa >= 0.0f && qa <= len) return insideCheck ? startsInside(in) : CastOutput{};
    const Vec2 end = qa < 0.0f ? a : b;
    if (insideCheck && distanceSquared(in.origin, end) <= r * r) return startsInside(in);
    return castDisc(end, r, in);
  }
  const float side = qp > 0.0f ? r : -r;
  const float dp = cross(u, d);
  if (!(dp * side < 0.0f)) return {};  // parallel to the band or moving away from it
  const float t = (side - qp) / dp;
  if (t > in.maxFraction) return {};
  const float s = qa + t * dot(d, u);
  if (s < 0.0f) return castDisc(a, r, in);
  if (s > len) return castDisc(b, r, in);
  const Vec2 n = qp > 0.0f ? leftPerp(u) : rightPerp(u);
  return hitAt(n, mulAdd(in.origin, t, d), t);
}

// Runs cast on the ray, shortened by an exact power of two (and the fraction scaled back) when
// the translation's squared length overflows: the same ray, the same point. Checked once per
// cast, not once per piece of a shape.
template <class Cast>
CastOutput castFiniteLength(const RayCastInput& in, Cast cast) {
  if (std::isfinite(lengthSquared(in.translation))) return cast(in);
  CastOutput out = cast({in.origin, 0x1p-70f * in.translation, 0x1p70f * in.maxFraction});
  out.fraction *= 0x1p-70f;
  return out;
}

}  // namespace

CastOutput rayCast(const Circle& s, const RayCastInput& in) {
  if (distanceSquared(in.origin, s.center) <= s.radius * s.radius) return startsInside(in);
  float length = rc::length(in.translation);
  if (length == 0.0f) return {};
  return castCircle(s.center, s.radius, in, length, (1.0f / length) * in.translation);
}

// The sharp casts, inlined into the world-frame dispatcher (a call and a returned CastOutput
// per cast cost a fifth of an oriented box's ray cast) and wrapped for the public functions.
namespace {
[[gnu::always_inline]] inline CastOutput castBox(const Box& s, const RayCastInput& in);
[[gnu::always_inline]] inline CastOutput castPolygon(const Polygon& s, const RayCastInput& in);
}  // namespace

CastOutput rayCast(const Box& s, const RayCastInput& in) {
  return castBox(s, in);
}

CastOutput rayCast(const Polygon& s, const RayCastInput& in) {
  return castPolygon(s, in);
}

namespace {

CastOutput castBox(const Box& s, const RayCastInput& in) {
  Vec2 lo = s.center - s.halfExtents, hi = s.center + s.halfExtents;
  if (AABB{lo, hi}.contains(in.origin)) return startsInside(in);
  // Slab test (Kay and Kajiya): the latest entry and the earliest exit over both axes.
  float tEnter = 0.0f, tExit = in.maxFraction;
  Vec2 normal{};
  const float o[2] = {in.origin.x, in.origin.y};
  const float d[2] = {in.translation.x, in.translation.y};
  const float l[2] = {lo.x, lo.y}, h[2] = {hi.x, hi.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0f) {
      if (o[axis] < l[axis] || o[axis] > h[axis]) return {};
      continue;
    }
    float inv = 1.0f / d[axis];
    float t1 = (l[axis] - o[axis]) * inv, t2 = (h[axis] - o[axis]) * inv;
    float sign = -1.0f;
    if (t1 > t2) {
      std::swap(t1, t2);
      sign = 1.0f;
    }
    if (t1 > tEnter) {
      tEnter = t1;
      normal = axis == 0 ? Vec2{sign, 0.0f} : Vec2{0.0f, sign};
    }
    tExit = std::min(tExit, t2);
    if (tEnter > tExit) return {};
  }
  if (normal == Vec2{}) return {};  // never entered a slab within range
  return hitAt(normal, mulAdd(in.origin, tEnter, in.translation), tEnter);
}

// A rounded polygon is its core plus a capsule on every edge. Out of line: inside the sharp
// cast its registers and stack cost every polygon cast.
[[gnu::noinline]] CastOutput castRoundedPolygon(const Polygon& s, const RayCastInput& in) {
  if (containsPoint(Shape(s), Transform{}, in.origin)) return startsInside(in);
  if (lengthSquared(in.translation) == 0.0f) return {};
  CastOutput best = castFiniteLength(in, [&](const RayCastInput& ray) {
    CastOutput closest;
    for (int i = 0; i < s.count; ++i)
      keepCloser(closest, castCapsule(s.vertices[i], s.vertices[nextIndex(i, s.count)], s.radius,
                                      ray, false));
    return closest;
  });
  if (!best.hit) return best;
  // The normal from the hit's closest feature of the core, not from the capsule that won: where
  // a flat side meets a corner's arc the two entries are within a rounding of each other, and
  // the arc's normal, if it wins, is off by sqrt(2 rounding / r) (1e-3 rad; ray oracle). By
  // regions, not by comparing distances (equal there to float precision): a point in front of
  // an edge and within its extent is nearest that edge (the core lies behind the edge's line);
  // only outside every such region is it nearest a vertex.
  float nearestFace = std::numeric_limits<float>::infinity();
  float nearestCorner = std::numeric_limits<float>::infinity();
  Vec2 cornerNormal{};
  for (int i = 0; i < s.count; ++i) {
    const Vec2 v1 = s.vertices[i], e = s.vertices[nextIndex(i, s.count)] - v1;
    const float u = dot(best.point - v1, e), ee = lengthSquared(e);
    const float d = dot(best.point - v1, s.normals[i]);
    if (u >= 0.0f && u <= ee && d >= 0.0f) {
      if (d < nearestFace) {
        nearestFace = d;
        best.normal = s.normals[i];
      }
    } else if (nearestFace == std::numeric_limits<float>::infinity()) {
      const Vec2 corner = u < 0.0f ? v1 : v1 + e;
      const float d2 = distanceSquared(best.point, corner);
      if (d2 < nearestCorner) {
        nearestCorner = d2;
        cornerNormal = best.point - corner;
      }
    }
  }
  if (nearestFace == std::numeric_limits<float>::infinity()) best.normal = normalize(cornerNormal);
  return best;
}

CastOutput castPolygon(const Polygon& s, const RayCastInput& in) {
  if (s.radius > 0.0f) return castRoundedPolygon(s, in);
  // Cyrus-Beck clipping of the ray against every edge's half-plane.
  float lower = 0.0f, upper = in.maxFraction;
  int index = -1;
  for (int i = 0; i < s.count; ++i) {
    float num = dot(s.normals[i], s.vertices[i] - in.origin);
    float den = dot(s.normals[i], in.translation);
    // Tested in the order of the common cases (an equality test first costs every edge a
    // parity and an equality branch).
    if (den < 0.0f) {
      if (num < lower * den) {
        lower = num / den;  // entering this half-plane later
        index = i;
      }
    } else if (den > 0.0f) {
      if (num < upper * den) upper = num / den;  // leaving this half-plane earlier
    } else if (num < 0.0f) {
      return {};  // parallel to this edge and outside it (or NaN input)
    }
    if (upper < lower) return {};
  }
  if (index < 0) {
    // Never entered: the origin is inside every half-plane, or the ray has zero length.
    bool inside = true;
    for (int i = 0; i < s.count; ++i)
      inside = inside && dot(s.normals[i], in.origin - s.vertices[i]) <= 0.0f;
    return inside ? startsInside(in) : CastOutput{};
  }
  return hitAt(s.normals[index], mulAdd(in.origin, lower, in.translation), lower);
}

}  // namespace

CastOutput rayCast(const Capsule& s, const RayCastInput& in) {
  return castFiniteLength(in, [&](const RayCastInput& ray) {
    return castCapsule(s.center1, s.center2, s.radius, ray, true);
  });
}

CastOutput rayCast(const Segment& s, const RayCastInput& in, bool oneSided) {
  // One pass: the face the ray can hit is the one whose normal opposes it.
  Vec2 e = s.point2 - s.point1;
  Vec2 n = normalize(rightPerp(e));
  float denom = dot(n, in.translation);
  if (denom == 0.0f) return {};  // parallel
  if (denom > 0.0f) {
    if (oneSided) return {};  // from behind a one-sided link
    n = -n;
    denom = -denom;
  }
  float num = dot(n, s.point1 - in.origin);
  if (num > 0.0f) return {};  // starts behind the face
  float t = num / denom;
  if (t > in.maxFraction) return {};
  Vec2 p = mulAdd(in.origin, t, in.translation);
  float u = dot(p - s.point1, e);
  if (u < 0.0f || u > lengthSquared(e)) return {};
  return hitAt(n, p, t);
}

CastOutput rayCast(const ChainSegment& s, const RayCastInput& in) {
  return rayCast(s.segment, in, s.oneSided);
}

namespace {

// A circle cast without the round trip through the shape's frame. The centre is taken relative
// to the ray origin as (p - origin) + R c, which stays exact when both are 1e4 m out. With the
// translation d and the centre s, the entry is t = (s.d - sqrt(r^2 d.d - (s x d)^2))
// / d.d, the discriminant written with the cross product (Lagrange's identity) so that it never
// cancels two huge products on long rays or far circles. 1 / d.d is computed beside the square
// root, off the critical path.
[[gnu::always_inline]] inline CastOutput rayCastCircleWorld(const Circle& c, const Transform& xf,
                                                            const RayCastInput& in) {
  Vec2 s = (xf.p - in.origin) + rotate(xf.q, c.center);
  float r2 = c.radius * c.radius;
  if (lengthSquared(s) <= r2) return startsInside(in);
  float dd = lengthSquared(in.translation);
  float sd = dot(s, in.translation);
  float invDd = 1.0f / dd;
  float cr = cross(s, in.translation);
  float disc = r2 * dd - cr * cr;
  // One test turns every miss away: a line that misses the circle (disc < 0: the root is NaN),
  // a circle behind the origin (sd <= 0, the origin being outside: t < 0), a ray of zero length
  // (0 * inf = NaN), a circle beyond the ray's reach.
  float t = (sd - std::sqrt(disc)) * invDd;
  if (!(t >= 0.0f && t <= in.maxFraction)) return {};
  // hit - centre = t d - s, over the radius (1 / r is computed off the critical path). Far out,
  // t d - s carries the rounding of s and its length drifts from r: normalised then instead.
  Vec2 n = (1.0f / c.radius) * mulSub(-1.0f * s, -t, in.translation);
  float n2 = lengthSquared(n);
  if (n2 < 0.99999f || n2 > 1.00001f) n = normalize(n);
  return hitAt(n, mulAdd(in.origin, t, in.translation), t);
}

// A segment cast in the world frame, with the endpoints taken relative to the ray origin
// ((p - origin) + R v stays exact far from the world origin).
[[gnu::always_inline]] inline CastOutput rayCastSegmentWorld(const Segment& g, bool oneSided,
                                                             const Transform& xf,
                                                             const RayCastInput& in) {
  Vec2 v1 = (xf.p - in.origin) + rotate(xf.q, g.point1);
  Vec2 e = rotate(xf.q, g.point2 - g.point1);
  Vec2 n = normalize(rightPerp(e));
  float denom = dot(n, in.translation);
  if (denom == 0.0f) return {};
  if (denom > 0.0f) {
    if (oneSided) return {};
    n = -n;
    denom = -denom;
  }
  float num = dot(n, v1);
  if (num > 0.0f) return {};
  float t = num / denom;
  if (t > in.maxFraction) return {};
  float u = dot(mulSub(t * in.translation, 1.0f, v1), e);
  if (u < 0.0f || u > lengthSquared(e)) return {};
  return hitAt(n, mulAdd(in.origin, t, in.translation), t);
}

// A cast in the shape's frame, the result brought back to the world. The result is
// initialised from the per-type cast's prvalue and is the only thing returned, so no copy of
// it is made (see hitAt).
template <class Cast>
[[gnu::always_inline]] inline CastOutput castInShapeFrame(const Transform& xf,
                                                          const RayCastInput& in, Cast&& cast) {
  const RayCastInput local{invApply(xf, in.origin), invRotate(xf.q, in.translation),
                           in.maxFraction};
  CastOutput out = cast(local);
  if (out.hit) {
    // The point from the world ray, not the local one, so far-off shapes keep their precision.
    out.point = mulAdd(in.origin, out.fraction, in.translation);
    out.normal = rotate(xf.q, out.normal);
  }
  return out;
}

// An oriented box (makeOrientedBox's rectangle) crossed as two slabs in the world frame (Kay and
// Kajiya, on the box's own axes): no round trip through the shape's frame and no vertex loads.
// With c the box centre from the ray origin, u an axis, h the half extent along it and
// d = dot(u, translation), the ray is within that slab for t * d in [dot(u, c) - h,
// dot(u, c) + h]; it enters through the face that d approaches. Every NaN or infinity from
// unguarded input (an offset that overflows, a translation of infinities) makes an entry or its
// slab's exit NaN, or an entry of +inf or an exit of -inf, and each of those fails the final
// test: such a cast misses, as the guarded path would decide.
[[gnu::always_inline]] inline CastOutput rayCastOrientedBoxWorld(const Polygon& p,
                                                                 const Transform& xf,
                                                                 const RayCastInput& in) {
  const Vec2 c = (xf.p - in.origin) + rotate(xf.q, p.centroid);
  const Vec2 u = rotate(xf.q, p.normals[1]);  // the box's x axis; its y axis is leftPerp(u)
  const Vec2 v = leftPerp(u);
  const float cu = dot(u, c), cv = dot(v, c);
  const float hu = p.boxHalfExtents.x, hv = p.boxHalfExtents.y;
  // Inside, boundary included, as for every solid shape (raycast.h).
  if (std::abs(cu) <= hu && std::abs(cv) <= hv) return startsInside(in);
  const float du = dot(u, in.translation), dv = dot(v, in.translation);
  // A ray parallel to a slab is either always within it or never; the division would give
  // 0/0 on the slab's boundary, so the case is taken apart (rare and well predicted). The two
  // slabs are written out on purpose: with them in one inline helper, the general polygon cast
  // (geometry_bench raycast/polygon) measured 34-36 ns instead of 17, also with this function
  // out of line: code layout, not instructions (the assembler's
  // -mbranches-within-32B-boundaries gave 22.7 ns).
  float enterU = -std::numeric_limits<float>::infinity(), exitU = -enterU;
  float enterV = enterU, exitV = exitU;
  if (du != 0.0f) {
    const float s = std::copysign(hu, du);
    enterU = (cu - s) / du;
    exitU = (cu + s) / du;
  } else if (!(std::abs(cu) <= hu)) {
    return {};
  }
  if (dv != 0.0f) {
    const float s = std::copysign(hv, dv);
    enterV = (cv - s) / dv;
    exitV = (cv + s) / dv;
  } else if (!(std::abs(cv) <= hv)) {
    return {};
  }
  // The later entry; the face entered is the one the ray approaches (its normal against d).
  const bool throughU = enterU >= enterV;
  const float t = throughU ? enterU : enterV;
  if (!(t >= 0.0f && t <= exitU && t <= exitV && t <= in.maxFraction)) return {};
  const Vec2 axis = throughU ? u : v;
  const float along = throughU ? du : dv;
  return hitAt(along > 0.0f ? -axis : axis, mulAdd(in.origin, t, in.translation), t);
}

// A polygon cast on its own (the commonest solid after circles and boxes), without the other
// shapes' code around it: in the shared function below the register spills of every other case
// cost an oriented box's cast a tenth of its time.
[[gnu::noinline]] CastOutput rayCastPolygonWorld(const Polygon& p, const Transform& xf,
                                                 const RayCastInput& in) {
  if (p.boxHalfExtents.x > 0.0f && p.radius == 0.0f) return rayCastOrientedBoxWorld(p, xf, in);
  return castInShapeFrame(xf, in, [&](const RayCastInput& local) { return castPolygon(p, local); });
}

CastOutput rayCastLocal(const Shape& s, const Transform& xf, const RayCastInput& in) {
  return castInShapeFrame(xf, in, [&](const RayCastInput& local) -> CastOutput {
    switch (s.type) {
      case ShapeType::circle:
        return rayCast(s.circle, local);
      case ShapeType::box:
        return castBox(s.box, local);
      case ShapeType::polygon:
        return castPolygon(s.polygon, local);
      case ShapeType::capsule:
        return rayCast(s.capsule, local);
      case ShapeType::segment:
        return rayCast(s.segment, local);
      case ShapeType::chainSegment:
        return rayCast(s.chainSegment, local);
    }
    return {};
  });
}

}  // namespace

CastOutput rayCast(const Shape& s, const Transform& xf, const RayCastInput& in) {
  // A sharp polygon's clipping squares nothing and divides only by an edge's own approach, so it
  // needs no guard: an offset that overflows makes every edge's numerator infinite or NaN, which
  // no comparison lets in, and the cast misses as the careful path below would decide. Taken
  // first, polygons (oriented boxes above all) skip the guard's cost.
  if (s.type == ShapeType::polygon && s.polygon.radius == 0.0f)
    return rayCastPolygonWorld(s.polygon, xf, in);
  // One test lets ordinary input through: the offset's components and the translation's
  // squared length summed are finite (anything infinite or NaN, or a sum that overflows, takes
  // the careful path below, which decides exactly as if there were no shortcut).
  const Vec2 offset = xf.p - in.origin;
  if (std::isfinite(offset.x + offset.y + lengthSquared(in.translation))) [[likely]] {
    if (s.type == ShapeType::circle) return rayCastCircleWorld(s.circle, xf, in);
    if (s.type == ShapeType::segment) return rayCastSegmentWorld(s.segment, false, xf, in);
    if (s.type == ShapeType::chainSegment)
      return rayCastSegmentWorld(s.chainSegment.segment, s.chainSegment.oneSided, xf, in);
    if (s.type == ShapeType::polygon) return rayCastPolygonWorld(s.polygon, xf, in);
    return rayCastLocal(s, xf, in);
  }
  // Inputs near the float range: a shape whose offset from the ray origin overflows is farther
  // than any representable ray reaches; a translation whose squared length overflows is cast
  // scaled by an exact power of two and its fraction scaled back.
  if (!isFinite(offset)) return {};
  if (!std::isfinite(lengthSquared(in.translation)) && isFinite(in.translation)) {
    constexpr float kScale = 0x1p-70f;
    RayCastInput scaled{in.origin, kScale * in.translation, in.maxFraction / kScale};
    CastOutput out = rayCast(s, xf, scaled);
    if (out.hit) {
      out.fraction *= kScale;
      out.point = mulAdd(in.origin, out.fraction, in.translation);
    }
    return out;
  }
  if (s.type == ShapeType::circle) return rayCastCircleWorld(s.circle, xf, in);
  if (s.type == ShapeType::segment) return rayCastSegmentWorld(s.segment, false, xf, in);
  if (s.type == ShapeType::chainSegment)
    return rayCastSegmentWorld(s.chainSegment.segment, s.chainSegment.oneSided, xf, in);
  return rayCastLocal(s, xf, in);
}

}  // namespace rc
