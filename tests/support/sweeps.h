// Random sweeps and a time-of-impact reference built from the GJK distance alone, shared by the
// unit tests (tests/unit/toi_test.cpp) and the Box2D oracle (tests/oracle/toi_oracle_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "physics/distance.h"
#include "physics/random.h"
#include "physics/shapes.h"
#include "physics/toi.h"
#include "support/random_shapes.h"

namespace rc::testing {

// The four solid shape types of the TOI tests; polygons are sharp or rounded at random.
inline constexpr Kind kSolidKinds[4] = {Kind::circle, Kind::box, Kind::polygon, Kind::capsule};

inline Shape solidShape(Random& rng, Kind kind) {
  if (kind == Kind::polygon && rng.below(2) == 1) return randomShape(rng, Kind::roundedPolygon);
  return randomShape(rng, kind);
}

inline float farthestCorePoint(const ShapeProxy& p, Vec2 center) {
  float r = 0;
  for (int i = 0; i < p.count; ++i)
    r = std::max(r, distance(p.points[i], center));
  return r;
}

// Upper bound on the distance any point of the shape (rounding included) travels per unit t:
// the centre moves |c2 - c1| and a point at r from it turns through |a2 - a1| r.
inline float motionBound(const ShapeProxy& p, const Sweep& s) {
  return length(s.c2 - s.c1) +
         std::fabs(s.a2 - s.a1) * (farthestCorePoint(p, s.localCenter) + p.radius);
}

struct SweepCase {
  ShapeProxy a, b;
  Sweep sa, sb;
  // Bound on how fast any point of one shape moves relative to the other, per unit t.
  float motion() const { return motionBound(a, sa) + motionBound(b, sb); }
  // Distance between the rounded surfaces at t (0 when they overlap).
  float distanceAt(float t) const {
    return shapeDistance(a, sweepTransform(sa, t), b, sweepTransform(sb, t)).distance;
  }
  // Distance between the cores (radii left out): what Box2D's targets are stated in.
  float coreDistanceAt(float t) const {
    ShapeProxy ca = a, cb = b;
    ca.radius = cb.radius = 0;
    return shapeDistance(ca, sweepTransform(sa, t), cb, sweepTransform(sb, t)).distance;
  }
};

// B near the origin drifting up to 0.5 m and turning up to 0.5 rad; A starting 1.5 to 5 m away,
// heading for a point near B (overshooting or falling short) while turning up to 1 rad.
inline SweepCase randomSweep(Random& rng, Kind ka, Kind kb) {
  SweepCase c;
  Shape sa = solidShape(rng, ka), sb = solidShape(rng, kb);
  c.a = makeProxy(sa);
  c.b = makeProxy(sb);
  c.sb.localCenter = computeMass(sb, 1.0f).center;
  c.sb.c1 = rng.inBox({-0.5f, -0.5f}, {0.5f, 0.5f});
  c.sb.c2 = c.sb.c1 + rng.inBox({-0.5f, -0.5f}, {0.5f, 0.5f});
  c.sb.a1 = rng.uniform(-kPi, kPi);
  c.sb.a2 = c.sb.a1 + rng.uniform(-0.5f, 0.5f);
  Rot dir = Rot::fromAngle(rng.uniform(-kPi, kPi));
  c.sa.localCenter = computeMass(sa, 1.0f).center;
  c.sa.c1 = c.sb.c1 + rng.uniform(1.5f, 5.0f) * Vec2{dir.c, dir.s};
  Vec2 aim = c.sb.c2 + rng.inBox({-1, -1}, {1, 1});
  c.sa.c2 = c.sa.c1 + rng.uniform(0.3f, 1.5f) * (aim - c.sa.c1);
  c.sa.a1 = rng.uniform(-kPi, kPi);
  c.sa.a2 = c.sa.a1 + rng.uniform(-1.0f, 1.0f);
  return c;
}

// First t in [0, 1] at which distance(t) drops below `level` (2: never), by the steps the motion
// bound allows: no point moves faster than m = c.motion() per unit t relative to the other shape,
// so after a sample at distance d the distance cannot drop below `level` for (d - level) / m. A
// floor of `minStep` of motion per step keeps grazing sweeps finite: the first sample below is
// then at most minStep / m after the true crossing, never before it.
template <class Distance>
float firstBelowLipschitz(const SweepCase& c, Distance distance, float level, float minStep) {
  float m = std::max(c.motion(), 1e-6f);
  float t = 0;
  for (;;) {
    float d = distance(t);
    if (d < level) return t;
    if (t >= 1.0f) return 2.0f;
    t = std::min(1.0f, t + std::max(d - level, minStep) / m);
  }
}

}  // namespace rc::testing
