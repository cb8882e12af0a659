#include "physics/toi.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace rc {

CastOutput sweptCircles(Vec2 centerA, float radiusA, Vec2 moveA, Vec2 centerB, float radiusB,
                        Vec2 moveB) {
  // Relative motion of B seen from A: |d + t v| = R with d = cB - cA, v = moveB - moveA.
  // As a quadratic a t^2 + 2 b t + c = 0: a = v.v, b = d.v, c = d.d - R^2. Three rewrites keep
  // every digit when the circles start far apart (|d| up to 1e6 R):
  //  - c = (|d| - R)(|d| + R): no subtraction of two huge squares;
  //  - the discriminant b^2 - a c equals a R^2 - (d x v)^2 (Lagrange's identity), computed from
  //    the cross product instead of the difference of two nearly equal huge products;
  //  - the smaller root is c / (-b + sqrt(disc)) (the "citardauq" form): -b > 0 when
  //    approaching, so no cancellation between -b and sqrt(disc).
  CastOutput out;
  Vec2 d = centerB - centerA;
  Vec2 v = moveB - moveA;
  float radius = radiusA + radiusB;
  float dist = length(d);
  float c = (dist - radius) * (dist + radius);
  if (c <= 0.0f) {  // already touching
    out.hit = true;
    out.fraction = 0.0f;
    out.normal = dist > 0.0f ? (1.0f / dist) * d : Vec2{1.0f, 0.0f};
    out.point = mulAdd(centerA, radiusA, out.normal);
    return out;
  }
  float a = dot(v, v);
  float b = dot(d, v);
  if (a == 0.0f || b >= 0.0f) return out;  // not moving, or moving apart
  float cr = cross(d, v);
  float disc = a * radius * radius - cr * cr;
  if (disc < 0.0f) return out;  // the paths pass each other
  float t = c / (-b + std::sqrt(disc));
  if (t > 1.0f) return out;
  Vec2 pa = mulAdd(centerA, t, moveA), pb = mulAdd(centerB, t, moveB);
  out.hit = true;
  out.fraction = t;
  out.normal = normalize(pb - pa);
  out.point = mulAdd(pa, radiusA, out.normal);
  return out;
}

CastOutput shapeCast(const ShapeProxy& a, const Transform& xfA, Vec2 translation,
                     const ShapeProxy& b, const Transform& xfB, float target) {
  // Conservative advancement (Mirtich 1996) with linear motion. With n the unit normal of the
  // closest features (A -> B), the separation along n is a lower bound of the distance and falls
  // at exactly dot(translation, n) per unit t, so stepping by gap / that speed never passes
  // contact. Each step aims at the target itself, except that the cores are kept half a tolerance
  // apart: sharp shapes cast with target 0 would otherwise stop with their cores exactly
  // touching, where GJK has no normal to give. The tolerance is the oracle's (Box2D: 0.25 *
  // b2_linearSlop).
  // The cores are measured, not the surfaces: a negative target (an overlap of the rounded
  // surfaces, as a contact solver's slop asks for) is then a positive core distance, where the
  // surface distance would stay 0 and never tell how deep.
  constexpr float kTolerance = 0.25f * kLinearSlop;
  constexpr int kMaxIterations = 40;
  const float coreTarget = std::max(0.0f, target + a.radius + b.radius);
  const float aim = std::max(0.0f, 0.5f * kTolerance - coreTarget);
  ShapeProxy coreA = a, coreB = b;
  coreA.radius = coreB.radius = 0.0f;
  CastOutput out;
  SimplexCache cache;
  float t = 0.0f;
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    Transform at{mulAdd(xfA.p, t, translation), xfA.q};
    DistanceOutput dist = shapeDistance(coreA, at, coreB, xfB, &cache);
    out.iterations = iter + 1;
    float gap = dist.distance - coreTarget;
    if (gap < kTolerance) {
      out.hit = true;
      out.fraction = t;
      out.point = mulSub(dist.pointB, b.radius, dist.normal);  // on B's rounded surface
      // B's surface normal, towards A. Only a cast that starts in contact can have touching
      // cores (no normal): any direction out of B will do there, the reverse of the motion is
      // the natural one.
      if (lengthSquared(dist.normal) > 0.0f) {
        out.normal = -dist.normal;
      } else {
        out.normal = -normalize(translation);
        if (lengthSquared(out.normal) == 0.0f) out.normal = {0.0f, 1.0f};
      }
      return out;
    }
    float approach = dot(translation, dist.normal);
    if (approach <= 0.0f) return out;  // moving away or sliding past
    t += (gap - aim) / approach;
    if (t > 1.0f) return out;
  }
  return out;  // out of iterations: only reached while the gap is still open, so no hit
}

Transform sweepTransform(const Sweep& s, float t) {
  Vec2 c = lerp(s.c1, s.c2, t);
  // A sweep that does not turn from angle +0 (the world sweeps round bodies so) takes no sine
  // and cosine: Rot{} is sincos(+0)'s result, bit for bit.
  const float angle = s.a1 + t * (s.a2 - s.a1);
  const Rot q = std::bit_cast<std::uint32_t>(angle) == 0u ? Rot{} : Rot::fromAngle(angle);
  return {c - rotate(q, s.localCenter), q};
}

ToiOutput timeOfImpact(const ShapeProxy& a, const Sweep& sweepA, const ShapeProxy& b,
                       const Sweep& sweepB, float tMax, float target) {
  // Conservative advancement with rotation: any point of a body moves at most
  // |dc| + |da| * R per unit t, R the farthest core point from the centre of mass. Work on the
  // cores (radii folded into the target) so the bound holds for rounded shapes too. Steps aim at
  // the target, or half a tolerance above the cores touching when the target is closer than
  // that (see shapeCast).
  constexpr float kTolerance = 0.25f * kLinearSlop;
  constexpr int kMaxIterations = 64;
  ShapeProxy coreA = a, coreB = b;
  coreA.radius = coreB.radius = 0.0f;
  float coreTarget = target + a.radius + b.radius;
  const float aim = std::max(0.0f, 0.5f * kTolerance - coreTarget);
  auto farthest = [](const ShapeProxy& p, Vec2 center) {
    float r = 0.0f;
    for (int i = 0; i < p.count; ++i)
      r = std::max(r, distance(p.points[i], center));
    return r;
  };
  float rA = farthest(a, sweepA.localCenter), rB = farthest(b, sweepB.localCenter);
  Vec2 dcA = sweepA.c2 - sweepA.c1, dcB = sweepB.c2 - sweepB.c1;
  float angular = std::fabs(sweepA.a2 - sweepA.a1) * rA + std::fabs(sweepB.a2 - sweepB.a1) * rB;

  ToiOutput out;
  SimplexCache cache;
  float t = 0.0f;
  for (int iter = 0; iter < kMaxIterations; ++iter) {
    Transform xfA = sweepTransform(sweepA, t), xfB = sweepTransform(sweepB, t);
    DistanceOutput dist = shapeDistance(coreA, xfA, coreB, xfB, &cache);
    out.iterations = iter + 1;
    float gap = dist.distance - coreTarget;
    if (gap < kTolerance) {
      if (iter == 0 && gap < -kTolerance) {
        out.state = ToiState::overlapped;
        out.fraction = 0.0f;
      } else {
        out.state = ToiState::hit;
        out.fraction = t;
      }
      out.normal = dist.normal;
      // Contact point midway between the rounded surfaces.
      out.point = 0.5f * (mulAdd(dist.pointA, a.radius, dist.normal) +
                          mulSub(dist.pointB, b.radius, dist.normal));
      return out;
    }
    // Upper bound on how fast the gap can close along the current normal.
    float bound = dot(dcA - dcB, dist.normal) + angular;
    if (bound <= 0.0f) {
      out.state = ToiState::separated;
      out.fraction = tMax;
      return out;
    }
    t += (gap - aim) / bound;
    if (t >= tMax) {
      out.state = ToiState::separated;
      out.fraction = tMax;
      return out;
    }
  }
  out.state = ToiState::failed;
  out.fraction = t;
  return out;
}

}  // namespace rc
