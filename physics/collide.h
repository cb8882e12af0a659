// Ricochet physics: pair dispatch. One table indexed by the two shape types holds the manifold
// and overlap function of every pair; each pair is registered once and its mirror is derived by
// swapping the arguments and flipping the result. A pair that has no function (two zero-area
// shapes: segment and chain links among themselves have no manifold) throws UnsupportedPair
// rather than silently reporting no contact.
#pragma once

#include <stdexcept>

#include "physics/manifold.h"

namespace rc {

class UnsupportedPair : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// Contact manifold of any supported pair; normal from A to B. Points are reported while the
// shapes are within `margin` (see manifold.h).
Manifold collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                 float margin = kSpeculativeDistance);

// Do the shapes overlap (touching counts)? Closed forms for circles, the separating axis test
// for sharp polygons, GJK for the rest. No bounding-circle test first: callers come through the
// broadphase, whose AABB test is the cheap bound, and after it the circles cost more than they
// saved (geometry_bench, overlap-prefilter rows: README, Performance).
bool testOverlap(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB);

// True when collide() has a function for the pair.
bool hasManifold(ShapeType a, ShapeType b);

}  // namespace rc
