// Sight: a bot sees what is inside its view cone and range and not hidden behind anything (a
// line-of-sight ray cast). Bots are not omniscient: they act on this and on hearing (hearing.h)
// alone, through their memory (memory.h).
//
// A bot looks every kLookEvery ticks, staggered by its index (bot i on the ticks t with
// (t + i) % kLookEvery == 0): the ray casts are the costly part of perception, and a fifth of a
// second's reaction is human. Decisions run every tick, from memory.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

inline constexpr int kLookEvery = 3;

struct SightTuning {
  float range = 25.0f;           // m
  float halfAngle = 1.0471976f;  // rad: a 120 degree cone
};

// Whether `other`'s centre is inside the viewer's cone (about its aim, edges included) and range.
bool inCone(const MatchState& s, std::size_t viewer, std::size_t other,
            const SightTuning& tuning = {});

// Whether `viewer` sees `other` now: inside the cone about the viewer's aim, within range, and
// the first thing a ray from the viewer's centre to the other's meets is the other's body.
bool sees(const MatchState& s, std::size_t viewer, std::size_t other,
          const SightTuning& tuning = {});

// The nearest living enemy the viewer sees, if any.
std::optional<std::size_t> nearestSeenEnemy(const MatchState& s, std::size_t viewer,
                                            const SightTuning& tuning = {});

// Whether it is the viewer's tick to look (see kLookEvery).
bool looksAt(std::int64_t tick, std::size_t viewer);

// The viewer's sight now: every living enemy inside its cone gets a line-of-sight ray (listed in
// MatchState::sightRays for the view); those it reaches are remembered as seen, with their
// position and velocity. The same answer as sees(), cheaper: a ray the navigation grid proves
// blocked (pointInsideWall) is not cast; its record ends at the point found inside the wall.
// MatchState::minds[viewer].lastLook becomes this tick.
void look(MatchState& s, std::size_t viewer, const SightTuning& tuning = {});

}  // namespace game
