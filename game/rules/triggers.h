// Trigger zones: the level's sensors and their `action`, acted on when a living actor enters
// (the step's sensor begin events, in the world's order):
//   kill   the actor dies (no one is credited: a suicide);
//   exit   the actor reached the way out: an exit scores for it and its team (score.h), and it
//          leaves the arena and comes back in at once at its respawn point (the spawn farthest
//          from its enemies), at rest, with the health and ammo it had. A deathmatch goes on, so
//          an exit is an objective worth RuleTuning::exitScore points rather than the end of the
//          match; sending the actor away makes each exit one score (standing in the zone, or
//          stepping out and in, cannot farm it).
//   hurt   every living actor inside loses the zone's damagePerSecond (10 unless the level says),
//          a tick's worth each tick, for as long as it stays; dying of it is a suicide.
// Other actions do nothing.
#pragma once

#include <vector>

#include "game/match/match.h"

namespace game {

void applyTriggers(MatchState& s);

// Which actors' shapes overlap the trigger body's shapes now (exactly; the query sees only
// actors), one flag per actor, living or not: what a hurt zone acts on.
void actorsInside(const MatchState& s, rc::BodyId zone, std::vector<bool>& inside);

}  // namespace game
