// Ricochet physics: contact manifolds.
//
// A manifold describes how two shapes touch: one normal (from A to B) and up to two points, each
// with its separation along the normal (negative when penetrating) and a feature id that stays
// the same while the same features touch, so the solver can warm start from last step's
// impulses. Points are reported while the shapes are within `margin` (kSpeculativeDistance by
// default; a world passes more for bodies that approach faster), so a solver can stop an
// approaching body before it penetrates.
//
// How each pair is solved (collide.cpp registers them in a table):
//   circle-circle, circle-capsule: closest points in closed form;
//   circle-box, box-box (same rotation): axis-aligned fast paths, no trigonometry, no loops;
//   everything else: both shapes as rounded hulls (1 to 8 core points and a radius; a capsule or
//   segment is a two-point hull). The separating axis test finds the reference face; the incident
//   edge is clipped to the reference face's side planes (Sutherland-Hodgman on one edge). When
//   the cores are apart and the closest features are two vertices, the face normal is wrong, so
//   GJK's closest points give the normal and a single point instead.
//   chain links: as a segment seen from its collision side (never its back face), then the normal
//   must be one the link allows: its own face normal, or towards a convex joint the fan between
//   its normal and the neighbour's, or anything towards an open end. A contact from closest
//   points whose normal points into the neighbour's region is dropped (the neighbour reports
//   it, unless the shape has crossed to the neighbour's back); a face of the shape crossing the
//   link is clamped to the nearest allowed normal, keeping whichever separates more. This removes
//   ghost collisions at the joints of flat, convex and concave walls.
#pragma once

#include <cstdint>

#include "physics/shapes.h"

namespace rc {

// Only points[0, pointCount) are set; the rest is left uninitialised (this runs for every
// contact pair every step, so nothing is written that is not read).
struct ManifoldPoint {
  Vec2 point;    // world point midway between the two surfaces
  Vec2 anchorA;  // point relative to A's origin (world orientation)
  Vec2 anchorB;  // point relative to B's origin (world orientation)
  float separation;
  std::uint16_t id;
};

struct Manifold {
  Vec2 normal{};  // unit, from A to B
  ManifoldPoint points[2];
  int pointCount = 0;
};

Manifold collideCircles(const Circle& a, const Transform& xfA, const Circle& b,
                        const Transform& xfB, float margin = kSpeculativeDistance);
Manifold collideCapsuleAndCircle(const Capsule& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin = kSpeculativeDistance);
Manifold collidePolygonAndCircle(const Polygon& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin = kSpeculativeDistance);
Manifold collideSegmentAndCircle(const Segment& a, const Transform& xfA, const Circle& b,
                                 const Transform& xfB, float margin = kSpeculativeDistance);
Manifold collideBoxAndCircle(const Box& a, const Transform& xfA, const Circle& b,
                             const Transform& xfB, float margin = kSpeculativeDistance);
// Aligned boxes in closed form; turned ones by the hull path specialised to two boxes (the
// same manifold as collideHulls, to the bit).
Manifold collideBoxes(const Box& a, const Transform& xfA, const Box& b, const Transform& xfB,
                      float margin = kSpeculativeDistance);
// General path: any two solid or segment shapes as rounded hulls.
Manifold collideHulls(const Shape& a, const Transform& xfA, const Shape& b, const Transform& xfB,
                      float margin = kSpeculativeDistance);
// A chain link against a circle, the same rules as collideChainSegment on a faster path.
Manifold collideChainSegmentAndCircle(const ChainSegment& a, const Transform& xfA, const Circle& b,
                                      const Transform& xfB, float margin = kSpeculativeDistance);
// The same with the dispatch table's signature (collide.cpp): one call instead of two on the
// path a bullet against a wall of links takes.
Manifold collideChainSegmentAndCircleShapes(const Shape& a, const Transform& xfA, const Shape& b,
                                            const Transform& xfB, float margin);
// A chain link against any solid shape, ghost-free.
Manifold collideChainSegment(const ChainSegment& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB, float margin = kSpeculativeDistance);

}  // namespace rc
