// Sight: a bot sees what is inside its view cone and range and not hidden behind anything (a
// line-of-sight ray cast). Bots are not omniscient: they act on this alone.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

struct SightTuning {
  float range = 25.0f;           // m
  float halfAngle = 1.0471976f;  // rad: a 120 degree cone
};

// Whether `viewer` sees `other` now: inside the cone about the viewer's aim, within range, and
// the first thing a ray from the viewer's centre to the other's meets is the other's body.
bool sees(const MatchState& s, std::size_t viewer, std::size_t other,
          const SightTuning& tuning = {});

// The nearest living enemy the viewer sees, if any.
std::optional<std::size_t> nearestSeenEnemy(const MatchState& s, std::size_t viewer,
                                            const SightTuning& tuning = {});

}  // namespace game
