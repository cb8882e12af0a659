// Explosions: a blast at a point pushes and hurts what it reaches. A body is reached when its
// centre of mass lies within the blast's radius and a line-of-sight ray from the blast's centre
// to it meets no static body (walls, merged tiles, static props): a target behind a wall takes
// nothing and is not pushed, not even woken. What is reached is woken and takes, by the fraction
// 1 - d / radius of its distance d, the blast's damage (actors, destructible props) and its
// impulse, outward at its centre of mass (dynamic bodies: actors, props, other grenades).
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"
#include "game/weapons/weapon_table.h"

namespace game {

// The blast of a grenade of spec `grenade` at `center`, thrown by `thrower` (credited with the
// kills): applied now, recorded in MatchState::explosions, heard (bots/hearing.h).
void explode(MatchState& s, rc::Vec2 center, const GrenadeSpec& grenade, std::size_t thrower);

}  // namespace game
