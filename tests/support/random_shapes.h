// Seeded random shapes and transforms shared by the property, brute-force and oracle tests.
#pragma once

#include <vector>

#include "physics/random.h"
#include "physics/shapes.h"

namespace rc::testing {

enum class Kind { circle, box, polygon, roundedPolygon, orientedBox, capsule, segment };
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
  }
  return "?";
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
  }
  return makeCircle({}, 1.0f);
}

inline Transform randomTransform(Random& rng, Vec2 around, float spread, bool rotate = true) {
  return {around + rng.inBox({-spread, -spread}, {spread, spread}),
          rotate ? Rot::fromAngle(rng.uniform(-3.14f, 3.14f)) : Rot{}};
}

}  // namespace rc::testing
