// Splitting a simple polygon into convex pieces the engine can take (rc::Polygon holds at most
// kMaxPolygonVertices vertices).
//
// Ear clipping triangulates the polygon; then Hertel and Mehlhorn's pass removes each
// triangulation diagonal whose two sides merge into a convex piece small enough (Hertel &
// Mehlhorn 1983: at most four times the fewest convex pieces, in linear time after the
// triangulation). The predicates run in double on the float input. Deterministic: the same
// points give the same pieces in the same order.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

#include "physics/math.h"

namespace game {

// Why a polygon cannot be split: a message without the object's name ("crosses itself: edges 2
// and 5 meet"), which the caller puts in context.
class DecompositionError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Polygons with more vertices than this are refused (ear clipping is quadratic or worse).
inline constexpr std::size_t kMaxDecomposedVertices = 256;

// The polygon's own shoelace area: positive when counter-clockwise.
double signedArea(std::span<const rc::Vec2> polygon);

// Convex pieces, each counter-clockwise, with no three consecutive vertices collinear and at
// most `maxVertices` (3 or more) vertices, whose union is the polygon. The polygon may be
// either orientation; consecutive duplicate and collinear points are dropped first. Throws
// DecompositionError when it is not simple (crosses or touches itself, doubles back), has no
// area, has fewer than 3 corners or more than kMaxDecomposedVertices.
std::vector<std::vector<rc::Vec2>> decomposeConvex(std::span<const rc::Vec2> polygon,
                                                   int maxVertices);

}  // namespace game
