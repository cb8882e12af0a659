// Weapons: what each one does (one table) and firing them.
#pragma once

#include <cstddef>

#include "game/match/match.h"

namespace game {

struct WeaponSpec {
  const char* name;
  int cooldownTicks;   // between shots
  int ammoPerSpawn;    // what an actor carries when it (re)spawns
  float damage;        // per hit at close range
  float range;         // m
  float falloffStart;  // m: full damage up to here,
  float falloffEnd;    // then down linearly to minDamage * damage here
  float minDamage;     // fraction
  float impulse;       // N s given to a dynamic body hit
};

// The rifle: hitscan, a shot every 8 ticks.
inline constexpr WeaponSpec kRifle{"rifle", 8, 90, 25.0f, 60.0f, 20.0f, 60.0f, 0.5f, 4.0f};

// Damage of a hit at `distance` metres (falloff as the spec says).
float damageAt(const WeaponSpec& weapon, float distance);

// One hitscan shot from `shooter` along its aim: ray cast through the world, the shooter's own
// body ignored; damages the first actor or destructible prop it meets, pushes a dynamic body,
// and records the shot's path in MatchState::shots.
void fireHitscan(MatchState& s, std::size_t shooter, const WeaponSpec& weapon);

}  // namespace game
