// Actors' bodies: creating them at the match's start, choosing where they (re)spawn.
#pragma once

#include <cstddef>

#include "game/match/match.h"

namespace game {

// The collision category of actors' shapes (the level's are in LevelFilters).
inline constexpr rc::ProxyFilter kActorFilter{1u << 3, 0xFFFFFFFFu};

// The match's players, then its bots, each at a spawn of its kind (in the level's order,
// wrapping around when there are more actors than spawns).
void spawnActors(MatchState& s);

// Where an actor comes back: the spawn of its kind farthest from every living enemy (ties to the
// first in the level's order), or its kind's first spawn when no enemy lives.
rc::Vec2 respawnPoint(const MatchState& s, std::size_t actor);

// Brings a dead actor back at `where`, at full health, at rest.
void revive(MatchState& s, std::size_t actor, rc::Vec2 where);

}  // namespace game
