// Seeded random shapes and transforms shared by the property, brute-force and oracle tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/random.h"
#include "physics/shapes.h"
#include "support/reference_geometry.h"

namespace rc::testing {

enum class Kind { circle, box, polygon, roundedPolygon, orientedBox, capsule, segment, chainLink };
inline const char* kindName(Kind k) {
  switch (k) {
    case Kind::circle:
      return "circle";
    case Kind::box:
      return "box";
    case Kind::polygon:
      return "polygon";
    case Kind::roundedPolygon:
      return "rounded polygon";
    case Kind::orientedBox:
      return "oriented box";
    case Kind::capsule:
      return "capsule";
    case Kind::segment:
      return "segment";
    case Kind::chainLink:
      return "chain link";
  }
  return "?";
}

// One link of a random chain, as rc::makeChain builds them: a link 0.2 to 2.5 m long about the
// origin, and neighbours 0.2 to 2 m long turned up to 1 rad either way at each joint (convex
// and concave corners), exactly straight one time in eight, and one time in eight an open end
// (the ghost is the endpoint itself). One-sided links collide with shapes on their right.
inline ChainSegment randomChainLink(Random& rng, bool oneSided) {
  Vec2 p1 = rng.inBox({-1.0f, -1.0f}, {1.0f, 1.0f});
  float angle = rng.uniform(-3.14f, 3.14f);
  Vec2 dir{std::cos(angle), std::sin(angle)};
  Vec2 p2 = p1 + rng.uniform(0.2f, 2.5f) * dir;
  auto neighbour = [&](Vec2 from, float sign) {
    std::uint32_t pick = rng.below(8);
    if (pick == 0) return from;  // open end
    float turn = pick == 1 ? 0.0f : rng.uniform(-1.0f, 1.0f);
    Vec2 d{std::cos(angle + turn), std::sin(angle + turn)};
    return from + sign * rng.uniform(0.2f, 2.0f) * d;
  };
  Vec2 ghost1 = neighbour(p1, -1.0f);
  Vec2 ghost2 = neighbour(p2, 1.0f);
  Vec2 points[4] = {ghost1, p1, p2, ghost2};
  bool open1 = ghost1 == p1, open2 = ghost2 == p2;
  std::span<const Vec2> span(points + (open1 ? 1 : 0), 4 - (open1 ? 1 : 0) - (open2 ? 1 : 0));
  // The middle link of the polyline: the one from p1 to p2.
  return makeChain(span, false, oneSided)[open1 ? 0 : 1];
}

// A shape of the given kind about the origin, sized 0.1 to ~2 m.
inline Shape randomShape(Random& rng, Kind kind) {
  switch (kind) {
    case Kind::circle:
      return makeCircle(rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}), rng.uniform(0.1f, 1.0f));
    case Kind::box:
      return makeBox(rng.uniform(0.1f, 1.0f), rng.uniform(0.1f, 1.0f),
                     rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}));
    case Kind::orientedBox:
      return makeOrientedBox(rng.uniform(0.1f, 1.0f), rng.uniform(0.1f, 1.0f),
                             rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f}), rng.uniform(-3.0f, 3.0f));
    case Kind::polygon:
    case Kind::roundedPolygon: {
      float radius = kind == Kind::roundedPolygon ? rng.uniform(0.02f, 0.3f) : 0.0f;
      for (;;) {
        int n = 3 + static_cast<int>(rng.below(6));
        std::vector<Vec2> pts;
        float size = rng.uniform(0.2f, 1.2f);
        for (int i = 0; i < n; ++i)
          pts.push_back(size * rng.inBox({-1, -1}, {1, 1}));
        try {
          return makePolygon(pts, radius);
        } catch (const InvalidShape&) {
        }
      }
    }
    case Kind::capsule: {
      Vec2 a = rng.inBox({-1, -1}, {1, 1});
      Vec2 b = a + Vec2{rng.uniform(0.1f, 1.5f), 0.0f};
      Transform spin{{}, Rot::fromAngle(rng.uniform(-3.0f, 3.0f))};
      return makeCapsule(apply(spin, a), apply(spin, b), rng.uniform(0.05f, 0.6f));
    }
    case Kind::segment: {
      Vec2 a = rng.inBox({-1.5f, -1.5f}, {1.5f, 1.5f});
      Vec2 b = rng.inBox({-1.5f, -1.5f}, {1.5f, 1.5f});
      if (distanceSquared(a, b) < 0.01f) b = a + Vec2{0.5f, 0.2f};
      return makeSegment(a, b);
    }
    case Kind::chainLink:
      return randomChainLink(rng, true);
  }
  return makeCircle({}, 1.0f);
}

// A convex polygon as the float points given to rc::makePolygon, and the exact polygon they stand
// for. Regular: n = 3..8 vertices on a circle of radius R at a random rotation. Irregular: n
// points at random angles at least 0.15 rad apart (every edge longer than the 1% weld) on an
// ellipse of semi-axes R and 0.3 R to R, turned at random: all are vertices of their hull, as
// points on a strictly convex curve. Centred within 3 R of the origin (each coordinate), so
// that rounding a vertex to float moves each coordinate by at most 2^-24 x 4 R. `interior` points
// strictly inside join the cloud, and the cloud is shuffled.
struct TestPolygon {
  ExactPolygon exact;
  std::vector<Vec2> points;  // the float vertices, then the interior points, shuffled
  long double centerX = 0, centerY = 0;
};
inline TestPolygon randomConvexPolygon(Random& rng, int n, long double radius, bool regular,
                                       int interior = 0) {
  constexpr long double kTwoPi = 6.283185307179586476925286766559L;
  std::vector<long double> angles(static_cast<size_t>(n));
  if (regular) {
    const long double turn = kTwoPi * rng.uniformDouble();
    for (int k = 0; k < n; ++k)
      angles[static_cast<size_t>(k)] = turn + kTwoPi * k / n;
  } else {
    for (;;) {
      for (long double& a : angles)
        a = kTwoPi * rng.uniformDouble();
      std::sort(angles.begin(), angles.end());
      bool apart = angles.front() + kTwoPi - angles.back() >= 0.15L;
      for (size_t k = 1; k < angles.size(); ++k)
        apart = apart && angles[k] - angles[k - 1] >= 0.15L;
      if (apart) break;
    }
  }
  const long double minor = regular ? radius : radius * (0.3L + 0.7L * rng.uniformDouble());
  const long double spin = regular ? 0.0L : kTwoPi * rng.uniformDouble();
  const long double cs = std::cos(spin), sn = std::sin(spin);
  TestPolygon t;
  t.centerX = radius * (6 * rng.uniformDouble() - 3);
  t.centerY = radius * (6 * rng.uniformDouble() - 3);
  t.exact.count = n;
  for (int k = 0; k < n; ++k) {
    const long double ex = radius * std::cos(angles[static_cast<size_t>(k)]),
                      ey = minor * std::sin(angles[static_cast<size_t>(k)]);
    t.exact.x[k] = t.centerX + cs * ex - sn * ey;
    t.exact.y[k] = t.centerY + sn * ex + cs * ey;
    t.points.push_back({static_cast<float>(t.exact.x[k]), static_cast<float>(t.exact.y[k])});
  }
  // Halfway between the vertices' mean and a random mix of them: well inside.
  for (int i = 0; i < interior; ++i) {
    long double mx = 0, my = 0, wx = 0, wy = 0, wsum = 0;
    for (int k = 0; k < n; ++k) {
      const long double w = 0.1L + rng.uniformDouble();
      mx += t.exact.x[k] / n;
      my += t.exact.y[k] / n;
      wx += w * t.exact.x[k];
      wy += w * t.exact.y[k];
      wsum += w;
    }
    t.points.push_back(
        {static_cast<float>((mx + wx / wsum) / 2), static_cast<float>((my + wy / wsum) / 2)});
  }
  for (size_t i = t.points.size(); i > 1; --i)
    std::swap(t.points[i - 1], t.points[rng.below(static_cast<std::uint32_t>(i))]);
  return t;
}

inline Transform randomTransform(Random& rng, Vec2 around, float spread, bool rotate = true) {
  return {around + rng.inBox({-spread, -spread}, {spread, spread}),
          rotate ? Rot::fromAngle(rng.uniform(-3.14f, 3.14f)) : Rot{}};
}

}  // namespace rc::testing
