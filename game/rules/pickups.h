// Pickups: the level's health and ammo items. A pickup is a circle on the floor (the level's
// position and radius), not a body: the rules check every tick whether a living actor's disc
// touches it (the distance between centres at most the sum of the radii), which is what a sensor
// would report, without putting bodies into the world (its snapshot, hash and broadphase stay
// the level's) and without following sensor begin and end events to learn who is still standing
// on it (an actor at full health on a health pack takes it the tick it is hurt).
//
// Each tick, after the step (the rules phase), in the level's order:
//   - a taken pickup whose time has come is back;
//   - an available pickup goes to the nearest living actor touching it that can use it (ties to
//     the lower index): health below the actor's maximum (ActorTuning::health) for "health",
//     rounds of its weapon below what an actor spawns with (WeaponSpec::ammo) for "ammo". It
//     gives its amount, up to that maximum (ammo in whole rounds, the amount rounded down), and
//     is gone for `respawn` seconds (rounded to ticks, at least one; 0: for good).
// An item the game does not know, or an amount that gives nothing, is never taken.
#pragma once

#include <vector>

#include "game/level/level.h"
#include "game/level/level_builder.h"
#include "game/match/match.h"
#include "game/weapons/weapon_table.h"

namespace game {

// The level's pickups resolved against the weapon table: an "ammo" pickup gives rounds of the
// weapon its `weapon` property names (the table's first weapon without one: the bundled rifle).
// A name not in the table is a LevelError naming the level, the pickup and the table's weapons.
std::vector<PickupState> makePickups(const Level& level, const BuiltLevel& built,
                                     const WeaponTable& weapons);

// What the pickup would give the actor now (health points or rounds): 0 if it cannot use it.
float pickupGift(const MatchState& s, const Actor& actor, const PickupState& pickup);

// The rules' pickups step, above.
void updatePickups(MatchState& s);

}  // namespace game
