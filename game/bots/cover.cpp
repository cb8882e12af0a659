#include "game/bots/cover.h"

#include <utility>
#include <vector>

#include "game/bots/navigation.h"

namespace game {

std::optional<CoverSpot> findCover(MatchState& s, std::size_t actor, rc::Vec2 threat) {
  const NavGrid& grid = s.nav;
  const rc::Vec2 at = s.world->worldCenter(s.actors[actor].body);
  const int start = nearestPassable(grid, at);
  if (start < 0) return std::nullopt;
  std::vector<int> cells;
  reachableCells(grid, start, kCoverSteps, s.navSearch, cells);
  const rc::QueryFilter walls = staticSolids(*s.world);
  // A candidate has an impassable neighbour on the threat's side: something may stand between.
  auto shielded = [&grid, threat](int c) {
    const int x = grid.x(c), y = grid.y(c);
    const rc::Vec2 toThreat = threat - grid.center(c);
    for (const auto& [dx, dy] :
         {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
      const int nx = x + dx, ny = y + dy;
      const bool wall = nx < 0 || ny < 0 || nx >= grid.width || ny >= grid.height ||
                        !grid.passable(ny * grid.width + nx);
      if (wall && static_cast<float>(dx) * toThreat.x + static_cast<float>(dy) * toThreat.y > 0.0f)
        return true;
    }
    return false;
  };
  int rays = 0;
  int farthest = start;
  float farthestDistance = rc::distanceSquared(grid.center(start), threat);
  for (const int c : cells) {
    if (grid.costly(c)) continue;  // no hiding in a hurt zone
    const rc::Vec2 p = grid.center(c);
    const float d = rc::distanceSquared(p, threat);
    if (d > farthestDistance) {
      farthest = c;
      farthestDistance = d;
    }
    if (rays >= kCoverRays || c == start || !shielded(c)) continue;
    ++rays;
    if (s.world->castRay(threat, p - threat, walls)) return CoverSpot{p, true};
  }
  return CoverSpot{grid.center(farthest), false};
}

}  // namespace game
