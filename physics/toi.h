// Ricochet physics: swept shapes and time of impact.
//
//   sweptCircles      two moving circles, solved in closed form with a quadratic written so
//                     that no step cancels catastrophically (see toi.cpp);
//   shapeCast         a shape translated along a path against another, by conservative
//                     advancement on GJK distances (any convex pair: circle vs segment, polygon,
//                     capsule, ... );
//   timeOfImpact      two shapes both translating and rotating over a step, by conservative
//                     advancement with a bound on the rotational speed of the farthest point.
// Each returns the fraction of the motion at first contact and the contact point and normal
// there. Fractions are in [0, 1] of the given motion.
#pragma once

#include "physics/distance.h"
#include "physics/raycast.h"

namespace rc {

// Moving circles: centres cA + t * moveA and cB + t * moveB. Hit at the first t in [0, 1]
// where the discs touch; normal from A to B, point on the contact. Circles overlapping at t = 0
// hit at fraction 0.
CastOutput sweptCircles(Vec2 centerA, float radiusA, Vec2 moveA, Vec2 centerB, float radiusB,
                        Vec2 moveB);

// Shape A moved by translation (world frame) against fixed shape B. Stops when the surfaces are
// within `target` of each other (default: touching within the 0.25 * slop tolerance); a
// negative target asks for that much overlap of the rounded surfaces (at most rA + rB: the
// cores touching).
// The normal points from B towards A at the hit (the surface normal of B the mover hits). The
// hit is reported up to 0.25 * slop before touching (never after), so the cores are apart and
// the normal is that of the closest features. A cast that starts in contact hits at fraction 0;
// if the cores already overlap there, the normal is the reverse of the motion.
CastOutput shapeCast(const ShapeProxy& a, const Transform& xfA, Vec2 translation,
                     const ShapeProxy& b, const Transform& xfB, float target = 0.0f);

// Motion of a body over a step: centre of mass moves c1 -> c2 and angle a1 -> a2, both
// linearly in t; localCenter is the centre of mass in the body frame.
struct Sweep {
  Vec2 localCenter{};
  Vec2 c1{}, c2{};
  float a1 = 0.0f, a2 = 0.0f;
};
Transform sweepTransform(const Sweep& s, float t);

enum class ToiState { hit, separated, overlapped, failed };
struct ToiOutput {
  ToiState state = ToiState::separated;
  float fraction = 1.0f;
  Vec2 point{};   // contact point at the time of impact, world frame
  Vec2 normal{};  // from A to B
  int iterations = 0;
};

// First t in [0, tMax] at which the surfaces come within `target` (tolerance 0.25 * slop).
// overlapped: closer than target at t = 0. failed: the iteration budget ran out (fraction is a
// safe time before contact).
ToiOutput timeOfImpact(const ShapeProxy& a, const Sweep& sweepA, const ShapeProxy& b,
                       const Sweep& sweepB, float tMax = 1.0f, float target = kLinearSlop);

}  // namespace rc
