#include "game/bots/navigation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <queue>

#include "physics/bytes.h"

namespace game {
namespace {

constexpr rc::ProxyFilter kEverything{0xFFFFFFFFu, 0xFFFFFFFFu};
// Grids above this many cells get coarser cells (a hostile map's bounds must not cost gigabytes).
constexpr int kMaxCells = 1 << 20;

// Neighbour steps: straight ones first, then diagonals.
constexpr int kDx[8] = {1, -1, 0, 0, 1, -1, 1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, 1, -1, -1};
// Landmarks an A* search uses at most (see findPath).
constexpr int kLandmarks = 4;

// Labels the connected regions of passable cells (4-connected: a diagonal step without corner
// cutting has both straight neighbours passable, so 8-connected reach is the same) and lists them.
void labelRegions(NavGrid& grid) {
  const int n = grid.size();
  grid.region.assign(static_cast<std::size_t>(n), -1);
  grid.open.clear();
  std::vector<int> queue;
  int regions = 0;
  for (int c = 0; c < n; ++c) {
    if (!grid.passable(c)) continue;
    grid.open.push_back(c);
    if (grid.region[static_cast<std::size_t>(c)] >= 0) continue;
    queue.assign(1, c);
    grid.region[static_cast<std::size_t>(c)] = regions;
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const int at = queue[head];
      for (int k = 0; k < 4; ++k) {
        const int x = grid.x(at) + kDx[k], y = grid.y(at) + kDy[k];
        if (x < 0 || y < 0 || x >= grid.width || y >= grid.height) continue;
        const int next = y * grid.width + x;
        if (!grid.passable(next) || grid.region[static_cast<std::size_t>(next)] >= 0) continue;
        grid.region[static_cast<std::size_t>(next)] = regions;
        queue.push_back(next);
      }
    }
    ++regions;
  }
}

// The level's places on their nearest open cells, then open cells each as far as can be from
// those chosen, up to kPatrolPoints (ties to the lower index).
void spreadPatrolPoints(NavGrid& grid, const std::vector<rc::Vec2>& places) {
  grid.patrol.clear();
  if (grid.open.empty()) return;
  auto add = [&grid](int c) {
    if (std::find(grid.patrol.begin(), grid.patrol.end(), c) == grid.patrol.end())
      grid.patrol.push_back(c);
  };
  for (const rc::Vec2 p : places) {
    if (grid.patrol.size() >= kPatrolPoints) break;
    if (const int c = nearestPassable(grid, p); c >= 0) add(c);
  }
  if (grid.patrol.empty()) grid.patrol.push_back(grid.open.front());
  std::vector<float> nearest(grid.open.size(), std::numeric_limits<float>::max());
  for (std::size_t counted = 0;;) {
    for (; counted < grid.patrol.size(); ++counted) {
      const rc::Vec2 p = grid.center(grid.patrol[counted]);
      for (std::size_t k = 0; k < grid.open.size(); ++k)
        nearest[k] = std::min(nearest[k], rc::distanceSquared(grid.center(grid.open[k]), p));
    }
    if (grid.patrol.size() >= kPatrolPoints) break;
    // Not in a hurt zone: a patrol would stand there (the level's own places may be).
    std::size_t best = grid.open.size();
    for (std::size_t k = 0; k < grid.open.size(); ++k)
      if (!grid.costly(grid.open[k]) && (best == grid.open.size() || nearest[k] > nearest[best]))
        best = k;
    // Every open cell costly, or a patrol point already.
    if (best == grid.open.size() || !(nearest[best] > 0.0f)) break;
    grid.patrol.push_back(grid.open[best]);
  }
}

// Every patrol point's field, those not yet worked out worked out now.
void ensureFields(const NavGrid& grid, PathSearch& search) {
  if (search.fieldsOf != grid.signature || search.fields.size() != grid.patrol.size()) {
    search.fields.assign(grid.patrol.size(), {});
    search.fieldsOf = grid.signature;
  }
  for (std::size_t l = 0; l < grid.patrol.size(); ++l)
    if (search.fields[l].empty()) distanceField(grid, grid.patrol[l], search.fields[l]);
}

void beginSearch(const NavGrid& grid, PathSearch& search) {
  const auto n = static_cast<std::size_t>(grid.size());
  if (search.cost.size() != n) {
    search.cost.assign(n, 0);
    search.parent.assign(n, -1);
    search.reached.assign(n, 0);
    search.closed.assign(n, 0);
    search.stamp = 0;
  }
  if (++search.stamp == 0) {  // wrapped around: old stamps could match again
    std::fill(search.reached.begin(), search.reached.end(), 0u);
    std::fill(search.closed.begin(), search.closed.end(), 0u);
    search.stamp = 1;
  }
}

// Whether the step k (of kDx, kDy) from the cell at x, y lands on a passable cell without cutting
// a corner.
inline bool canStep(const NavGrid& grid, int x, int y, int k) {
  const int nx = x + kDx[k], ny = y + kDy[k];
  if (nx < 0 || ny < 0 || nx >= grid.width || ny >= grid.height) return false;
  if (!grid.passable(ny * grid.width + nx)) return false;
  if (k >= 4) return grid.passable(y * grid.width + nx) && grid.passable(ny * grid.width + x);
  return true;
}

}  // namespace

int NavGrid::cellAt(rc::Vec2 p) const {
  if (width <= 0 || height <= 0) return -1;
  auto index = [this](float v, int count) {
    const float f = std::floor(v / cell + 0.5f);
    if (!(f >= 0.0f)) return 0;  // below, or not a number
    return f >= static_cast<float>(count - 1) ? count - 1 : static_cast<int>(f);
  };
  return index(p.y - origin.y, height) * width + index(p.x - origin.x, width);
}

NavGrid makeNavGrid(int width, int height, float cell, rc::Vec2 origin,
                    std::vector<std::uint8_t> flags, const std::vector<rc::Vec2>& places) {
  NavGrid grid;
  grid.width = width;
  grid.height = height;
  grid.cell = cell;
  grid.origin = origin;
  grid.flags = std::move(flags);
  grid.flags.resize(static_cast<std::size_t>(width * height), NavGrid::kBlocked);
  grid.moves.assign(grid.flags.size(), 0);
  for (int c = 0; c < grid.size(); ++c) {
    if (!grid.passable(c)) continue;
    std::uint8_t m = 0;
    for (int k = 0; k < 8; ++k)
      if (canStep(grid, grid.x(c), grid.y(c), k)) m = static_cast<std::uint8_t>(m | 1u << k);
    grid.moves[static_cast<std::size_t>(c)] = m;
  }
  labelRegions(grid);
  spreadPatrolPoints(grid, places);
  std::uint64_t h = rc::kFnvOffset;
  auto mix = [&h](std::uint64_t v) {
    for (int k = 0; k < 8; ++k) {
      h ^= (v >> (8 * k)) & 0xFFu;
      h *= rc::kFnvPrime;
    }
  };
  mix(static_cast<std::uint64_t>(width));
  mix(static_cast<std::uint64_t>(height));
  for (const std::uint8_t f : grid.flags)
    mix(f);
  for (const std::int32_t c : grid.patrol)
    mix(static_cast<std::uint64_t>(c));
  grid.signature = h;
  return grid;
}

namespace {

// Which cell centres merged tile loops enclose (one byte per cell): a chain has no inside for an
// overlap test, so each row of centres is crossed with the loops' links and the centres between
// the first and second crossing, the third and fourth, ... are inside (even-odd; the loops of a
// tile layer are closed).
std::vector<std::uint8_t> insideTiles(const Level& level, rc::Vec2 origin, float cell, int width,
                                      int height) {
  std::vector<std::uint8_t> inside(static_cast<std::size_t>(width * height), 0);
  std::vector<float> crossings;
  for (const LevelObject& o : level.objects) {
    if (o.kind != LevelObjectKind::tiles) continue;
    const rc::Transform xf{o.position, rc::Rot::fromAngle(o.angle)};
    std::vector<rc::Segment> links;
    for (const rc::Shape& shape : o.shapes)
      if (shape.type == rc::ShapeType::chainSegment)
        links.push_back({rc::apply(xf, shape.chainSegment.segment.point1),
                         rc::apply(xf, shape.chainSegment.segment.point2)});
    if (links.empty()) continue;
    for (int y = 0; y < height; ++y) {
      const float cy = origin.y + static_cast<float>(y) * cell;
      crossings.clear();
      for (const rc::Segment& l : links)
        if ((l.point1.y > cy) != (l.point2.y > cy))
          crossings.push_back(l.point1.x + (cy - l.point1.y) * (l.point2.x - l.point1.x) /
                                               (l.point2.y - l.point1.y));
      std::sort(crossings.begin(), crossings.end());
      for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
        const int x0 = std::max(0, static_cast<int>(std::ceil((crossings[k] - origin.x) / cell)));
        const int x1 =
            std::min(width - 1, static_cast<int>(std::floor((crossings[k + 1] - origin.x) / cell)));
        for (int x = x0; x <= x1; ++x)
          inside[static_cast<std::size_t>(y * width + x)] = 1;
      }
    }
  }
  return inside;
}

}  // namespace

rc::QueryFilter staticSolids(const rc::World& world) {
  return {kEverything, [&world](const rc::ShapeRef& r) {
            return world.type(r.body) == rc::BodyType::staticBody && !world.isSensor(r.shape);
          }};
}

NavGrid buildNavGrid(const Level& level, const BuiltLevel& built, const rc::World& world,
                     float radius) {
  const rc::AABB bounds = level.settings.bounds;
  const rc::Vec2 extent = bounds.upper - bounds.lower;
  if (!(extent.x > 0.0f && extent.y > 0.0f)) return makeNavGrid(0, 0, 0.5f, {}, {});
  // Half a tile (or a tile's even division), at most a metre: a lattice through the tiles'
  // centres.
  const float tile = level.settings.tileWidth > 0.0f ? level.settings.tileWidth : 1.0f;
  float cell = tile / (2.0f * std::max(1.0f, std::ceil(tile)));
  int width = 0, height = 0;
  for (;;) {
    const float w = std::floor(extent.x / cell) + 1.0f, h = std::floor(extent.y / cell) + 1.0f;
    if (w * h <= static_cast<float>(kMaxCells)) {
      width = static_cast<int>(w);
      height = static_cast<int>(h);
      break;
    }
    cell *= 2.0f;
  }
  std::vector<rc::BodyId> killers, hurters;
  for (const BuiltTrigger& t : built.triggers) {
    if (t.action == "kill") killers.push_back(t.body);
    if (t.action == "hurt") hurters.push_back(t.body);
  }
  const rc::QueryFilter solids = staticSolids(world);
  auto bodiesIn = [](const std::vector<rc::BodyId>& bodies) {
    return rc::QueryFilter(kEverything, [&bodies](const rc::ShapeRef& r) {
      return std::find(bodies.begin(), bodies.end(), r.body) != bodies.end();
    });
  };
  const rc::QueryFilter hazards = bodiesIn(killers), hurts = bodiesIn(hurters);
  const rc::Shape disc = rc::makeCircle({}, radius + kNavMargin);
  const rc::Shape wide = rc::makeCircle({}, radius + kNavMargin + kNavSpan * cell);
  // Kill zones get another cell of margin: a crowd can push a bot walking past.
  const rc::Shape deadly = rc::makeCircle({}, radius + kNavMargin + (kNavSpan + 1.0f) * cell);
  // Within a cell of a centre inside solid tiles, with a little to spare.
  const rc::Shape core = rc::makeCircle({}, 0.71f * cell);
  const std::vector<std::uint8_t> enclosed = insideTiles(level, bounds.lower, cell, width, height);
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(width * height), 0);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y * width + x);
      const rc::Transform at{
          bounds.lower + rc::Vec2{static_cast<float>(x) * cell, static_cast<float>(y) * cell}, {}};
      std::uint8_t f = 0;
      if (!killers.empty() && !world.overlapShape(deadly, at, hazards).empty())
        f |= NavGrid::kHazard;
      // Hurt zones: costly as far out as a wall makes a cell not roomy, so that a walk from
      // centre to centre of cells that are not costly (half a diagonal at most from one of them)
      // and a shortcut between roomy cells never take the actor into one.
      if (!hurters.empty() && !world.overlapShape(wide, at, hurts).empty()) f |= NavGrid::kCostly;
      if (enclosed[c] != 0) {
        f |= NavGrid::kBlocked;
        if (world.overlapShape(core, at, solids).empty()) f |= NavGrid::kOpaque;
      } else if (!world.overlapShape(disc, at, solids).empty()) {
        f |= NavGrid::kBlocked;
      } else if (f == 0 && world.overlapShape(wide, at, solids).empty()) {
        f |= NavGrid::kRoomy;
      }
      flags[c] = f;
    }
  }
  std::vector<rc::Vec2> places;
  for (const LevelSpawn& p : built.spawns)
    places.push_back(p.position);
  for (const LevelPickup& p : built.pickups)
    places.push_back(p.position);
  for (const LevelMarker& p : built.markers)
    places.push_back(p.position);
  for (const LevelPath& path : built.paths)
    for (const rc::Vec2 p : path.points)
      places.push_back(p);
  NavGrid grid = makeNavGrid(width, height, cell, bounds.lower, std::move(flags), places);
  grid.radius = radius;
  return grid;
}

std::int32_t octileDistance(const NavGrid& grid, int a, int b) {
  const int dx = std::abs(grid.x(a) - grid.x(b)), dy = std::abs(grid.y(a) - grid.y(b));
  const int diagonal = std::min(dx, dy), straight = std::max(dx, dy) - diagonal;
  return kDiagonalCost * diagonal + kStraightCost * straight;
}

bool findPath(const NavGrid& grid, int start, int goal, PathSearch& search, std::vector<int>& out) {
  out.clear();
  if (start < 0 || goal < 0 || !grid.passable(start) || !grid.passable(goal)) return false;
  if (grid.region[static_cast<std::size_t>(start)] != grid.region[static_cast<std::size_t>(goal)])
    return false;
  // Landmarks: the patrol points whose fields bound the start's distance best (ties to the lower
  // index). All fields are worked out first, so the choice never depends on which were before.
  ensureFields(grid, search);
  const std::int32_t* landmark[kLandmarks] = {};
  std::int32_t toGoal[kLandmarks] = {};
  int landmarks = 0;
  {
    std::int32_t bounds[kLandmarks] = {};
    for (std::size_t l = 0; l < search.fields.size(); ++l) {
      const std::vector<std::int32_t>& field = search.fields[l];
      const std::int32_t fg = field[static_cast<std::size_t>(goal)];
      if (fg == kUnreached) continue;  // another region's
      const std::int32_t bound = std::abs(fg - field[static_cast<std::size_t>(start)]);
      int at = landmarks < kLandmarks ? landmarks++ : kLandmarks;
      while (at > 0 && bounds[at - 1] < bound) {
        if (at < kLandmarks) {
          landmark[at] = landmark[at - 1];
          toGoal[at] = toGoal[at - 1];
          bounds[at] = bounds[at - 1];
        }
        --at;
      }
      if (at < kLandmarks) {
        landmark[at] = field.data();
        toGoal[at] = fg;
        bounds[at] = bound;
      }
    }
  }
  beginSearch(grid, search);
  const std::uint32_t stamp = search.stamp;
  const int width = grid.width;
  const int goalX = grid.x(goal), goalY = grid.y(goal);
  // The heuristic: the octile distance, or what the triangle inequality through a landmark says
  // if that is more (|d(L, goal) - d(L, n)| <= d(n, goal)); each is consistent, so their maximum.
  auto heuristic = [&](int x, int y, int c) {
    const int dx = std::abs(x - goalX), dy = std::abs(y - goalY);
    const int diagonal = std::min(dx, dy);
    std::int32_t h = kDiagonalCost * diagonal + kStraightCost * (std::max(dx, dy) - diagonal);
    for (int l = 0; l < landmarks; ++l)
      h = std::max(h, std::abs(toGoal[l] - landmark[l][c]));
    return h;
  };
  // A node is worse than another with a higher f, then a higher h, then a higher index: the
  // heap's top is the best.
  auto worse = [](const PathSearch::Node& a, const PathSearch::Node& b) {
    if (a.f != b.f) return a.f > b.f;
    if (a.h != b.h) return a.h > b.h;
    return a.cell > b.cell;
  };
  std::int32_t* cost = search.cost.data();
  std::int32_t* parent = search.parent.data();
  std::uint32_t* reached = search.reached.data();
  std::uint32_t* closed = search.closed.data();
  const std::uint8_t* moves = grid.moves.data();
  search.heap.clear();
  cost[start] = 0;
  parent[start] = -1;
  reached[start] = stamp;
  const std::int32_t h0 = heuristic(grid.x(start), grid.y(start), start);
  search.heap.push_back({h0, h0, start});
  while (!search.heap.empty()) {
    std::pop_heap(search.heap.begin(), search.heap.end(), worse);
    const PathSearch::Node node = search.heap.back();
    search.heap.pop_back();
    const int c = node.cell;
    const std::int32_t g = node.f - node.h;
    if (closed[c] == stamp || g != cost[c]) continue;
    closed[c] = stamp;
    if (c == goal) {
      for (int k = goal; k >= 0; k = parent[k])
        out.push_back(k);
      std::reverse(out.begin(), out.end());
      return true;
    }
    const int x = c % width, y = c / width;
    const unsigned legal = moves[c];
    for (int k = 0; k < 8; ++k) {
      if ((legal >> k & 1u) == 0) continue;
      const int nx = x + kDx[k], ny = y + kDy[k];
      const int next = ny * width + nx;
      if (closed[next] == stamp) continue;
      const std::int32_t g2 = g + stepCost(grid, c, next, k >= 4);
      if (reached[next] == stamp && g2 >= cost[next]) continue;
      reached[next] = stamp;
      cost[next] = g2;
      parent[next] = c;
      const std::int32_t h = heuristic(nx, ny, next);
      search.heap.push_back({g2 + h, h, next});
      std::push_heap(search.heap.begin(), search.heap.end(), worse);
    }
  }
  return false;  // not reached: same region, so only a broken grid gets here
}

void distanceField(const NavGrid& grid, int goal, std::vector<std::int32_t>& out) {
  out.assign(static_cast<std::size_t>(grid.size()), kUnreached);
  if (goal < 0 || !grid.passable(goal)) return;
  // Dijkstra from the goal (the steps are symmetric: this is the cost to it from anywhere) with a
  // bucket queue: costs are integers and a step costs less than kBuckets, so the cells at
  // distance d wait in bucket d % kBuckets and no two distances pending share one.
  constexpr int kBuckets = 512;
  static_assert(kDiagonalCost * (1 + 2 * kCostlyFactor) < kBuckets && kStraightCost > 0);
  std::vector<std::vector<int>> buckets(kBuckets);
  out[static_cast<std::size_t>(goal)] = 0;
  buckets[0].push_back(goal);
  std::size_t pending = 1;
  for (std::int32_t d = 0; pending > 0; ++d) {
    std::vector<int>& bucket = buckets[static_cast<std::size_t>(d % kBuckets)];
    for (std::size_t k = 0; k < bucket.size(); ++k) {
      const int c = bucket[k];
      --pending;
      if (out[static_cast<std::size_t>(c)] != d) continue;  // reached cheaper since
      const unsigned legal = grid.moves[static_cast<std::size_t>(c)];
      for (int step = 0; step < 8; ++step) {
        if ((legal >> step & 1u) == 0) continue;
        const int next = c + kDy[step] * grid.width + kDx[step];
        const std::int32_t nd = d + stepCost(grid, c, next, step >= 4);
        if (nd < out[static_cast<std::size_t>(next)]) {
          out[static_cast<std::size_t>(next)] = nd;
          buckets[static_cast<std::size_t>(nd % kBuckets)].push_back(next);
          ++pending;
        }
      }
    }
    bucket.clear();
  }
}

bool descendField(const NavGrid& grid, const std::vector<std::int32_t>& field, int start,
                  std::vector<int>& out) {
  out.clear();
  if (start < 0 || field[static_cast<std::size_t>(start)] == kUnreached) return false;
  int c = start;
  out.push_back(c);
  while (field[static_cast<std::size_t>(c)] > 0) {
    // The step on a cheapest path: the field lower by exactly the step's cost (a lower field
    // behind a costlier step is not on one).
    int best = -1;
    const std::int32_t here = field[static_cast<std::size_t>(c)];
    const int x = c % grid.width, y = c / grid.width;
    for (int k = 0; k < 8 && best < 0; ++k) {
      if (!canStep(grid, x, y, k)) continue;
      const int next = c + kDy[k] * grid.width + kDx[k];
      const std::int32_t there = field[static_cast<std::size_t>(next)];
      if (there != kUnreached && there + stepCost(grid, c, next, k >= 4) == here) best = next;
    }
    if (best < 0) {  // a field of another grid: no way down
      out.clear();
      return false;
    }
    c = best;
    out.push_back(c);
  }
  return true;
}

bool pathToPatrolPoint(const NavGrid& grid, int start, std::size_t point, PathSearch& search,
                       std::vector<int>& out) {
  ensureFields(grid, search);
  return descendField(grid, search.fields[point], start, out);
}

std::int32_t pathCost(const NavGrid& grid, const std::vector<int>& cells) {
  std::int32_t cost = 0;
  for (std::size_t k = 1; k < cells.size(); ++k) {
    const bool diagonal =
        grid.x(cells[k]) != grid.x(cells[k - 1]) && grid.y(cells[k]) != grid.y(cells[k - 1]);
    cost += stepCost(grid, cells[k - 1], cells[k], diagonal);
  }
  return cost;
}

namespace {

// The cell nearest the point (by its centre; ties to the lower index) that `fits`, within
// `reach` cells of the cell under it; -1 if there is none.
template <class Fits>
int nearestWhere(const NavGrid& grid, rc::Vec2 p, int reach, Fits fits) {
  const int under = grid.cellAt(p);
  if (under < 0) return -1;
  if (fits(under)) return under;  // the nearest centre of all
  int best = -1;
  float bestDistance = 0.0f;
  const int x0 = grid.x(under), y0 = grid.y(under);
  for (int y = std::max(0, y0 - reach); y <= std::min(grid.height - 1, y0 + reach); ++y) {
    for (int x = std::max(0, x0 - reach); x <= std::min(grid.width - 1, x0 + reach); ++x) {
      const int c = y * grid.width + x;
      if (!fits(c)) continue;
      const float d = rc::distanceSquared(grid.center(c), p);
      if (best < 0 || d < bestDistance) {
        best = c;
        bestDistance = d;
      }
    }
  }
  return best;
}

}  // namespace

int nearestPassable(const NavGrid& grid, rc::Vec2 p, int region, int reach) {
  return nearestWhere(grid, p, reach, [&](int c) {
    return grid.passable(c) && (region < 0 || grid.region[static_cast<std::size_t>(c)] == region);
  });
}

rc::Vec2 clearOfHurt(const NavGrid& grid, rc::Vec2 p, int reach) {
  const int under = grid.cellAt(p);
  if (under < 0 || !grid.costly(under)) return p;
  const int c =
      nearestWhere(grid, p, reach, [&](int k) { return grid.passable(k) && !grid.costly(k); });
  return c < 0 ? p : grid.center(c);
}

void reachableCells(const NavGrid& grid, int start, int steps, PathSearch& search,
                    std::vector<int>& out) {
  out.clear();
  if (start < 0 || !grid.passable(start)) return;
  beginSearch(grid, search);
  const std::uint32_t stamp = search.stamp;
  auto at = [](auto& v, int c) -> auto& {
    return v[static_cast<std::size_t>(c)];
  };
  at(search.reached, start) = stamp;
  at(search.cost, start) = 0;
  out.push_back(start);
  for (std::size_t head = 0; head < out.size(); ++head) {
    const int c = out[head];
    if (at(search.cost, c) >= steps) continue;
    const int x = c % grid.width, y = c / grid.width;
    for (int k = 0; k < 4; ++k) {
      if (!canStep(grid, x, y, k)) continue;
      const int next = c + kDy[k] * grid.width + kDx[k];
      if (at(search.reached, next) == stamp) continue;
      at(search.reached, next) = stamp;
      at(search.cost, next) = at(search.cost, c) + 1;
      out.push_back(next);
    }
  }
}

bool walkable(const NavGrid& grid, rc::Vec2 a, rc::Vec2 b) {
  const rc::Vec2 d = b - a;
  // Samples a quarter cell apart: a roomy cell is clear of walls and hazards by the sample
  // spacing and half its diagonal beyond the actor's disc (kNavSpan).
  const int samples = static_cast<int>(rc::length(d) / (0.25f * grid.cell)) + 1;
  for (int k = 0; k <= samples; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(samples);
    const int c = grid.cellAt(a + t * d);
    if (c < 0 || (grid.flags[static_cast<std::size_t>(c)] & NavGrid::kRoomy) == 0) return false;
  }
  return true;
}

std::vector<rc::Vec2> smoothPath(const NavGrid& grid, rc::Vec2 from, const std::vector<int>& cells,
                                 std::size_t maxPoints) {
  std::vector<rc::Vec2> out;
  if (cells.empty() || maxPoints == 0) return out;
  // The turns of the path and its end: a straight run of cells needs no waypoint inside it.
  std::vector<rc::Vec2> turns;
  for (std::size_t k = 1; k + 1 < cells.size(); ++k) {
    const int in = cells[k] - cells[k - 1], outStep = cells[k + 1] - cells[k];
    if (in != outStep) turns.push_back(grid.center(cells[k]));
  }
  turns.push_back(grid.center(cells.back()));
  rc::Vec2 anchor = from;
  if (!walkable(grid, from, turns.front())) {
    // Not roomy from where it stands (near a wall, or off its first cell): by the first cell's
    // centre, then along the cells.
    anchor = grid.center(cells.front());
    if (rc::distanceSquared(anchor, from) > 0.01f) out.push_back(anchor);
  }
  std::size_t k = 0;
  while (k < turns.size() && out.size() < maxPoints) {
    std::size_t j = k;
    while (j + 1 < turns.size() && walkable(grid, anchor, turns[j + 1]))
      ++j;
    out.push_back(turns[j]);
    anchor = turns[j];
    k = j + 1;
  }
  return out;
}

std::optional<rc::Vec2> pointInsideWall(const NavGrid& grid, rc::Vec2 a, rc::Vec2 b) {
  const rc::Vec2 d = b - a;
  const int samples = static_cast<int>(rc::length(d) / (0.5f * grid.cell));
  for (int k = 1; k <= samples; ++k) {
    const rc::Vec2 p = a + (static_cast<float>(k) / static_cast<float>(samples + 1)) * d;
    const int c = grid.cellAt(p);
    if (c >= 0 && (grid.flags[static_cast<std::size_t>(c)] & NavGrid::kOpaque) != 0) return p;
  }
  return std::nullopt;
}

}  // namespace game
