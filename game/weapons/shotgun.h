// Pellets: a hitscan weapon fires `pellets` rays at once, each turned off the aim by an angle
// drawn from the match's generator, uniform within the weapon's spread either side, pellet by
// pellet in order (the same seed gives the same pattern). A rifle is the one-pellet case; with
// no spread nothing is drawn.
#pragma once

#include <cstddef>

#include "game/match/match.h"
#include "game/weapons/weapon_table.h"

namespace game {

// The direction (radians) of the next pellet fired along `aim`.
float pelletAngle(rc::Random& rng, float aim, const HitscanSpec& weapon);

// Every pellet of hitscan weapon `weapon` from the actor's centre along its aim.
void firePellets(MatchState& s, std::size_t shooter, std::size_t weapon);

}  // namespace game
