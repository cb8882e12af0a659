// Damage, death and destruction.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

// Takes `amount` off the actor's health; at zero it dies: its body leaves the world (disabled,
// so that it can come back) and the death is scored (score.h: a kill for an enemy attacker, a
// suicide otherwise). attacker: the actor who dealt it, if any.
void damageActor(MatchState& s, std::size_t actor, float amount,
                 std::optional<std::size_t> attacker);
void killActor(MatchState& s, std::size_t actor, std::optional<std::size_t> attacker);

// The state of level object `object` if the match follows it (a dynamic or destructible prop).
PropState* propOf(MatchState& s, std::size_t object);

// Takes `amount` off a destructible prop's health (level object `object`); at zero its body is
// destroyed. Props without health are not hurt.
void damageProp(MatchState& s, std::size_t object, float amount);

}  // namespace game
