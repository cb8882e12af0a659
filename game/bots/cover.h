// Cover: where a hurt bot goes. The nearest place (by steps on the navigation grid, within
// kCoverSteps) with an obstacle beside it on the threat's side, from which a ray to the threat
// meets a static body: the threat cannot see it there. Only the first kCoverRays such places are
// tried (the rays are what costs). When none is hidden, the reachable place farthest from the
// threat: the bot flees.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

inline constexpr int kCoverSteps = 24;  // grid steps (12 m on half-metre cells)
inline constexpr int kCoverRays = 16;

struct CoverSpot {
  rc::Vec2 position{};
  bool hidden = false;  // cover; false: only away (flee)
};

// Where actor `actor` should go from a threat at `threat`; nothing when it stands on no
// passable cell (or the level has no grid).
std::optional<CoverSpot> findCover(MatchState& s, std::size_t actor, rc::Vec2 threat);

}  // namespace game
