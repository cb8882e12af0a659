// What broadphase_bench and scaling_bench drive both engines' broadphases with: circles of
// radius 0.5 m moving at 5 m/s, stepped at 60 Hz, as AABBs in both engines' types.
#pragma once

#include <box2d/b2_collision.h>

#include "physics/broadphase.h"

namespace rc::bench {

inline constexpr float kRadius = 0.5f, kSpeed = 5.0f, kDt = 1.0f / 60.0f;

inline AABB circleBox(Vec2 c) {
  return {{c.x - kRadius, c.y - kRadius}, {c.x + kRadius, c.y + kRadius}};
}
inline b2AABB toB2(const AABB& box) {
  b2AABB b;
  b.lowerBound.Set(box.lower.x, box.lower.y);
  b.upperBound.Set(box.upper.x, box.upper.y);
  return b;
}

}  // namespace rc::bench
