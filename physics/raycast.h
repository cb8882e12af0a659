// Ricochet physics: ray and segment casts against every shape.
//
// A ray is origin + t * translation for t in [0, maxFraction]; translation's length is the
// ray's length, so a fraction times that length is the distance travelled.
//
// A ray that starts inside a solid shape (boundary included) hits it at fraction 0, at the
// origin, with the normal pointing against the ray's direction: a shot fired from inside a wall
// stops at once instead of passing out through the far side. (Box2D 2.4.1 reports no hit there.)
// Segments and chain links have no inside. A ray running exactly along a segment does not hit it.
// A one-sided chain link is hit only by rays coming from its right side. A zero-length ray hits
// only what contains its origin. No NaN is ever produced from finite input.
#pragma once

#include "physics/shapes.h"

namespace rc {

struct RayCastInput {
  Vec2 origin{};
  Vec2 translation{};
  float maxFraction = 1.0f;
};

struct CastOutput {
  Vec2 normal{};  // unit surface normal at the hit, pointing out of the shape
  Vec2 point{};   // hit point, world frame
  float fraction = 0.0f;
  int iterations = 0;
  bool hit = false;
};

// Casts in the shape's local frame.
CastOutput rayCast(const Circle& s, const RayCastInput& in);
CastOutput rayCast(const Box& s, const RayCastInput& in);
CastOutput rayCast(const Polygon& s, const RayCastInput& in);
CastOutput rayCast(const Capsule& s, const RayCastInput& in);
CastOutput rayCast(const Segment& s, const RayCastInput& in, bool oneSided = false);
CastOutput rayCast(const ChainSegment& s, const RayCastInput& in);

// World-frame cast against a placed shape.
CastOutput rayCast(const Shape& s, const Transform& xf, const RayCastInput& in);

}  // namespace rc
