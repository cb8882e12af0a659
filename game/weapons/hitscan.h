// Hitscan ballistics: a shot is a ray cast through the world (the quadtree), followed through
// what it can afford to cross and off what it grazes, its damage falling with the distance it
// has travelled.
//
// Along the ray, at each surface met:
//   - a hard material (LevelMaterial::hard) met at less than the weapon's ricochet angle
//     (between the ray and the surface) reflects the shot about the hit normal,
//     d' = d - 2 (d.n) n, while it has bounces left; each bounce keeps (1 - ricochetLoss) of
//     the damage;
//   - otherwise a material whose thickness the shot's penetration budget can pay for is
//     crossed: the budget drops by the thickness and the damage is in proportion to the budget
//     left (a shot that spent 30% of its budget does 70% of the damage); the ray goes on from
//     where it leaves the material;
//   - otherwise the shot stops there (kImpenetrable walls always stop it).
// The range and the falloff count the whole path, bounces and crossings included. Everything the
// shot meets takes the damage it had on arrival (actors, destructible props) and a dynamic body
// is pushed by the weapon's impulse in the same proportion; these effects are applied once the
// path is traced, in the order met.
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"
#include "game/weapons/grenade.h"
#include "game/weapons/weapon_table.h"

namespace game {

// Shots see everything but projectiles: a grenade in flight is too small to shoot down.
inline constexpr rc::ProxyFilter kShotFilter{0xFFFFFFFFu, ~kProjectileFilter.category};

// Where a ray that entered a body at `entry`, going along the unit vector `dir`, leaves its
// solid, if within `reach` m of the entry (the shape's far side; a tile region's outline, the
// link nearest the entry): shots going through, and hearing counting the walls between.
struct RayExit {
  rc::WorldHit hit;
  float distance;  // from the entry, m
};
std::optional<RayExit> exitOf(const rc::World& world, const rc::WorldHit& entry, rc::Vec2 dir,
                              float reach);

// The falloff's factor at `distance` m (1 up to falloffStart, minDamage from falloffEnd on) and
// the damage it gives.
float falloffAt(const HitscanSpec& weapon, float distance);
float damageAt(const HitscanSpec& weapon, float distance);

// What a weapon deals a tick, on average, to a disc of `radius` m at `distance` m aimed at its
// centre (a bot's choice of gun): each pellet's damage there, times the share of the pellets
// that meet the disc (they leave uniformly within the spread either side of the aim; the disc
// covers asin(radius / distance) either side), over the cooldown. Zero for a grenade and beyond
// the range. Penetration and ricochets are not counted: an aimed shot meets the disc first.
float expectedDamagePerTick(const WeaponSpec& weapon, float distance, float radius);

// One shot (one pellet) of hitscan weapon `weapon` from `from` along the unit vector `dir`,
// the shooter's own body ignored: traced, its effects applied, recorded in MatchState::shots.
void traceShot(MatchState& s, std::size_t shooter, std::size_t weapon, int pellet, rc::Vec2 from,
               rc::Vec2 dir);

}  // namespace game
