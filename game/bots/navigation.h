// Navigation: where an actor can walk on a level, and the way from one place to another.
//
// The grid: square cells over the level's bounds, half a tile wide, their centres on the tiles'
// centres and corners (so a one-tile corridor has a line of free centres down its middle). A
// cell is blocked where a disc of the actor's radius plus kNavMargin at its centre would overlap
// static geometry (walls, tiles, static props) or where its centre is inside merged tiles (a
// chain loop has no inside for an overlap test: a scanline says what the loops enclose), and a
// hazard where a disc kNavSpan + 1 cells wider would reach a kill trigger (a crowd can push a bot
// walking past); both are impassable. A passable cell is costly where the disc kNavSpan cells
// wider would reach a hurt trigger (so a walk from centre to centre of cells that are not costly
// never takes the actor into one): a bot may cross a hurt zone, but a step costs twice its
// plain cost more for each costly end (kCostlyFactor), so a cell's worth of walk inside one
// costs five outside, and a route goes round the zone unless the way round is about four times
// as long. A cell inside tiles and farther than its half diagonal from
// their edges is opaque: any point nearer its centre than any other's is inside the wall. A
// passable cell is roomy when the wider disc meets no static geometry either: an actor anywhere in
// it is clear of walls (and of hurt zones). Moving props are not obstacles (actors push them). The
// grid is built once per match from the level's static bodies: derived data (the same level gives
// the same grid), so it is neither hashed nor saved.
//
// Paths: A* over the 8-connected grid with no corner cutting (a diagonal step needs both of its
// straight neighbours passable). Steps cost 70 straight and 99 diagonally (99/70 = 1.41429,
// sqrt 2 to 1e-5), more into and out of costly cells (stepCost: the same both ways, so a
// distance field from a point is the cost to it), integers so that costs compare exactly; the
// heuristic is the octile distance in the same units, the cost of the path with no obstacle or
// hurt zone, raised where a landmark knows better
// (ALT: Goldberg and Harrelson 2005): for the patrol points' distance fields L (below),
// |L(goal) - L(n)| is at most the cost from n to the goal, and the search takes the four that
// bound the start best. Each bound and the octile distance is admissible and consistent, so is
// their maximum: paths stay optimal, and the searches through this project's corridors and mazes
// expand a fraction of the cells the octile distance alone does. The open list breaks ties by the
// lower f, then the lower h (nearer the goal), then the lower cell index: the same query always
// gives the same path (every field is worked out before the first search, so the landmarks do
// not depend on which were before). A path is then shortened by line of sight on the
// grid (string pulling): a turn is skipped while the straight walk past it stays on roomy cells,
// checked every quarter of a cell (kNavSpan covers the sample spacing and a cell's half
// diagonal). No ray is cast: smoothing costs a few thousand instructions, not a physics query
// per turn.
//
// Patrols go between fixed patrol points: the level's own places (spawns, pickups, markers, path
// points) and up to kPatrolPoints in all, the rest spread over the open cells (each the open cell
// farthest from those already chosen). The way to a patrol point needs no search: its distance
// field (Dijkstra from the point, the same steps and costs) is worked out the first time a bot
// walks there and kept, and a walk descends it, an optimal path in as many steps as it has cells.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "game/bots/bot_state.h"
#include "game/level/level.h"
#include "game/level/level_builder.h"
#include "physics/world.h"

namespace game {

// Clearance kept from walls beyond the actor's radius (m).
inline constexpr float kNavMargin = 0.05f;
// How much wider than the blocking disc the roomy and hazard discs are, in cells: half a cell's
// diagonal plus half the sample spacing of a straight walk (a quarter cell).
inline constexpr float kNavSpan = 0.70711f + 0.125f;
// Step costs (see above).
inline constexpr std::int32_t kStraightCost = 70, kDiagonalCost = 99;
// What each costly end adds to a step, in multiples of its plain cost.
inline constexpr std::int32_t kCostlyFactor = 2;
inline constexpr std::size_t kPatrolPoints = 24;
// A cell no path reaches, in a distance field.
inline constexpr std::int32_t kUnreached = 0x7FFFFFFF;

struct NavGrid {
  static constexpr std::uint8_t kBlocked = 1, kHazard = 2, kRoomy = 4, kOpaque = 8, kCostly = 16;
  int width = 0, height = 0;
  float cell = 0.5f;                 // m
  rc::Vec2 origin{};                 // the centre of cell 0 (x 0, y 0); cell index y * width + x
  float radius = 0.0f;               // the actor's radius it was built for (m)
  std::vector<std::uint8_t> flags;   // per cell: kBlocked, kHazard, kRoomy, kOpaque, kCostly
  std::vector<std::int32_t> region;  // per cell: its connected region of passable cells, or -1
  std::vector<std::int32_t> open;    // the passable cells, in index order
  std::vector<std::uint8_t>
      moves;  // per cell: bit k set when step k (E W N S NE NW SE SW) is legal
  std::vector<std::int32_t> patrol;  // the patrol points' cells (see above)
  std::uint64_t signature = 0;       // FNV-1a of the size, flags and patrol points

  int size() const { return width * height; }
  bool passable(int c) const {
    return (flags[static_cast<std::size_t>(c)] & (kBlocked | kHazard)) == 0;
  }
  bool costly(int c) const { return (flags[static_cast<std::size_t>(c)] & kCostly) != 0; }
  int x(int c) const { return c % width; }
  int y(int c) const { return c / width; }
  rc::Vec2 center(int c) const {
    return origin + rc::Vec2{static_cast<float>(x(c)) * cell, static_cast<float>(y(c)) * cell};
  }
  // The cell whose centre is nearest the point (clamped to the grid); -1 for an empty grid.
  int cellAt(rc::Vec2 p) const;
};

// A grid from per-cell flags (regions and the open list worked out; patrol points spread over
// the open cells from `places`): tests and tools.
NavGrid makeNavGrid(int width, int height, float cell, rc::Vec2 origin,
                    std::vector<std::uint8_t> flags, const std::vector<rc::Vec2>& places = {});

// The level's grid for actors of `radius` (its bounds, tile size, static bodies and kill
// triggers). An empty grid (size 0) for a level without bounds.
NavGrid buildNavGrid(const Level& level, const BuiltLevel& built, const rc::World& world,
                     float radius);

// The search's work arrays, reused from one search to the next (stamped, never cleared), and the
// patrol points' distance fields, each worked out on first use. Neither is part of the match's
// state: the arrays hold nothing from one call to the next, and a field is the same whenever it
// is worked out (it depends on the grid alone).
struct PathSearch {
  std::vector<std::vector<std::int32_t>> fields;  // per patrol point; empty until first used
  std::uint64_t fieldsOf = 0;                     // the signature of the grid they are of
  std::vector<std::int32_t> cost, parent;
  std::vector<std::uint32_t> reached, closed;  // == stamp: set in this search
  std::uint32_t stamp = 0;
  struct Node {
    std::int32_t f, h, cell;
  };
  std::vector<Node> heap;
  std::vector<int> path, cells;  // for callers: a path's cells, a search's reach
};

// The cost of a step between neighbouring cells a and b: kStraightCost or kDiagonalCost, and
// kCostlyFactor times that again for each of them that is costly.
inline std::int32_t stepCost(const NavGrid& grid, int a, int b, bool diagonal) {
  const std::int32_t base = diagonal ? kDiagonalCost : kStraightCost;
  return base * (1 + kCostlyFactor * (int{grid.costly(a)} + int{grid.costly(b)}));
}

// The octile distance between two cells, in step costs.
std::int32_t octileDistance(const NavGrid& grid, int a, int b);

// The cheapest path from cell `start` to cell `goal`, both included, into `out`; false (and
// `out` empty) when there is none. Both cells must be passable. The first search on a grid works
// out every patrol point's field (the landmarks).
bool findPath(const NavGrid& grid, int start, int goal, PathSearch& search, std::vector<int>& out);

// The cost of the cheapest path from every cell to `goal` (kUnreached where there is none).
void distanceField(const NavGrid& grid, int goal, std::vector<std::int32_t>& out);

// The cheapest path from `start` to the field's goal, both included: from each cell the first
// step (in the order east, west, north, south, then the diagonals) to a neighbour whose field is
// lower by exactly the step's cost. False (and `out` empty) when the field does not reach
// `start`.
bool descendField(const NavGrid& grid, const std::vector<std::int32_t>& field, int start,
                  std::vector<int>& out);

// The way from `start` to patrol point `point` (an index in NavGrid::patrol), down its field
// (worked out now if it is the first time).
bool pathToPatrolPoint(const NavGrid& grid, int start, std::size_t point, PathSearch& search,
                       std::vector<int>& out);

// The cost of a path of adjacent cells (stepCost per step).
std::int32_t pathCost(const NavGrid& grid, const std::vector<int>& cells);

// The passable cell nearest the point (by its centre; ties to the lower index) within `reach`
// cells of the cell under it, in `region` unless that is -1; -1 if there is none.
int nearestPassable(const NavGrid& grid, rc::Vec2 p, int region = -1, int reach = 8);

// The point itself if its cell is not costly (or the grid is empty), else the centre of the
// nearest passable cell that is not, within `reach` cells (the point itself if there is none):
// where to stand to look into a hurt zone rather than in it.
rc::Vec2 clearOfHurt(const NavGrid& grid, rc::Vec2 p, int reach = 8);

// The passable cells reachable from `start` in at most `steps` straight steps, in the order a
// breadth-first search meets them (neighbours east, west, north, south).
void reachableCells(const NavGrid& grid, int start, int steps, PathSearch& search,
                    std::vector<int>& out);

// Whether a straight walk from a to b keeps to roomy cells (checked every quarter cell): an actor
// walking it meets no static body and enters no hazard or hurt zone.
bool walkable(const NavGrid& grid, rc::Vec2 a, rc::Vec2 b);

// The path of cells as waypoints for a walk from `from`: its turns, then those skipped that a
// straight walk can cut (walkable), at most `maxPoints` of them (the first ones).
std::vector<rc::Vec2> smoothPath(const NavGrid& grid, rc::Vec2 from, const std::vector<int>& cells,
                                 std::size_t maxPoints);

// A point of the segment from a to b (its ends excluded; checked every half cell) that is inside
// a wall for sure (nearest an opaque cell's centre), if the grid knows one: a ray from a to b
// meets that wall before it gets there. Sight uses it to skip the ray casts the grid can answer.
std::optional<rc::Vec2> pointInsideWall(const NavGrid& grid, rc::Vec2 a, rc::Vec2 b);

// The filter of static solid bodies (walls, tiles, static props; never sensors).
rc::QueryFilter staticSolids(const rc::World& world);

}  // namespace game
