// The outlines of the solid cells of a tile grid: what merges a wall of tiles into chain loops
// with no seams between tiles (a box sliding along a wall of separate tile boxes catches on
// their corners, and a ray along it can stop at a joint; one chain link per straight run
// cannot).
//
// Contour tracing on the grid's corners: every side of a solid cell that faces an empty cell
// (or the grid's edge) is a unit edge; edges chain end to start into closed loops, and straight
// runs merge into one edge, so a 40x40 block is one loop of 4 corners and a block with a hole
// two loops. Where two solid cells touch only at a corner, each keeps its own loop. Loops run
// with the solid on their left as drawn (on screen with y down, and in the world with y up
// alike): counter-clockwise around solid regions, clockwise around holes. A one-sided chain
// through the corners (rc::makeChain) then collides on the empty side only.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace game {

struct GridCorner {
  int x = 0, y = 0;  // corner (x, y) is the top-left of cell (x, y); y down
  friend bool operator==(GridCorner, GridCorner) = default;
};

// `solid` holds width * height cells, row by row from the top, non-zero for solid. Loops come
// in the order of their first corner scanning rows from the top, each starting at that
// corner.
std::vector<std::vector<GridCorner>> traceOutlines(int width, int height,
                                                   std::span<const std::uint8_t> solid);

// How many corners traceOutlines would return in all, without tracing (a corner of the grid
// with one or three solid cells around it is one corner, with two diagonal ones two): what a
// caller checks before asking for millions of chain links.
std::size_t countOutlineCorners(int width, int height, std::span<const std::uint8_t> solid);

}  // namespace game
