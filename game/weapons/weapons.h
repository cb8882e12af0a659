// Weapons: the weapons phase of the tick (fuses, then every actor's trigger and throw) and what
// an actor carries. The table (weapon_table.h) says what each weapon does; hitscan.h traces
// shots, shotgun.h spreads pellets, grenade.h throws grenades, explosion.h blasts.
#pragma once

#include <cstddef>

#include "game/match/match.h"
#include "game/weapons/explosion.h"
#include "game/weapons/grenade.h"
#include "game/weapons/hitscan.h"
#include "game/weapons/shotgun.h"
#include "game/weapons/weapon_table.h"

namespace game {

// Every weapon of the table loaded with what an actor carries when it (re)spawns.
void arm(Actor& actor, const WeaponTable& table);

// The actor's selected weapon (PlayerInput::weapon) fired now, if it is in the table: a hitscan
// weapon fires its pellets, a grenade is thrown. Ammo and cooldown are the caller's.
void fireWeapon(MatchState& s, std::size_t actor, std::size_t weapon);

}  // namespace game
