// Ricochet physics: pair dispatch. One table indexed by the two shape types holds the manifold
// and overlap function of every pair; each pair is registered once and its mirror is derived by
// swapping the arguments and flipping the result. A pair that has no function (two zero-area
// shapes: segment and chain links among themselves have no manifold) throws UnsupportedPair
// rather than silently reporting no contact.
#pragma once

#include <array>
#include <stdexcept>

#include "physics/manifold.h"

namespace rc {

class UnsupportedPair : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
using ManifoldFn = Manifold (*)(const Shape&, const Transform&, const Shape&, const Transform&,
                                float margin);
using OverlapFn = bool (*)(const Shape&, const Transform&, const Shape&, const Transform&);
struct PairEntry {
  ManifoldFn manifold = nullptr;
  OverlapFn overlap = nullptr;
  bool flip = false;  // registered for (b, a): call with the arguments swapped
};
struct PairTable {
  std::array<std::array<PairEntry, kShapeTypeCount>, kShapeTypeCount> e{};
};
// Built at compile time in collide.cpp. The lookup is inline so that a call site makes one
// indirect call, not two (a tenth of a chain-circle manifold).
extern const PairTable kPairTable;
[[noreturn]] void unsupportedPair(const char* what, ShapeType a, ShapeType b);
Manifold flipped(Manifold m);
}  // namespace detail

// Contact manifold of any supported pair; normal from A to B. Points are reported while the
// shapes are within `margin` (see manifold.h).
inline Manifold collide(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                        float margin = kSpeculativeDistance) {
  const detail::PairEntry& e =
      detail::kPairTable.e[static_cast<int>(a.type)][static_cast<int>(b.type)];
  if (e.manifold == nullptr) detail::unsupportedPair("collide", a.type, b.type);
  if (!e.flip) return e.manifold(a, xfA, b, xfB, margin);
  return detail::flipped(e.manifold(b, xfB, a, xfA, margin));
}

// Do the shapes overlap (touching counts)? Closed forms for circles, the separating axis test
// for sharp polygons, GJK for the rest. No bounding-circle test first: callers come through the
// broadphase, whose AABB test is the cheap bound, and after it the circles cost more than they
// saved (geometry_bench, overlap-prefilter rows: tests/bench/README.md).
inline bool testOverlap(const Shape& a, const Transform& xfA, const Shape& b,
                        const Transform& xfB) {
  const detail::PairEntry& e =
      detail::kPairTable.e[static_cast<int>(a.type)][static_cast<int>(b.type)];
  if (e.overlap == nullptr) detail::unsupportedPair("testOverlap", a.type, b.type);
  return e.flip ? e.overlap(b, xfB, a, xfA) : e.overlap(a, xfA, b, xfB);
}

// True when collide() has a function for the pair.
bool hasManifold(ShapeType a, ShapeType b);

}  // namespace rc
