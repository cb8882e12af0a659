// The weapon table: every number that makes a weapon what it is (damage, ranges, spread,
// penetration budgets, ricochets, grenades' bodies, fuses and blasts), read from one data file,
// assets/weapons.json, so that tuning a weapon is an edit of data, not of code.
//
// A bad file is an error, one line naming the file and the field
// ("assets/weapons.json: weapons[1] (\"shotgun\"): 'pellets' must be an integer from 1 to 64,
// got 0"), never a fallback: a match played with other weapons than asked is another match.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace game {

class WeaponTableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Actors carry at most this many weapons (their ammo is a fixed array).
inline constexpr std::size_t kMaxWeapons = 8;

enum class WeaponKind : std::uint8_t {
  hitscan,  // ray casts: a rifle (one pellet) or a shotgun (a spread of pellets)
  grenade,  // a thrown body that bounces and explodes when its fuse runs out
};
const char* weaponKindName(WeaponKind kind);

struct HitscanSpec {
  float damage = 25.0f;  // per pellet, before any loss
  float range = 60.0f;   // m, along the whole path (bounces included)
  // Falloff with the distance travelled: full damage up to `start`, then down linearly to
  // `minDamage` times it at `end` and beyond.
  float falloffStart = 20.0f, falloffEnd = 60.0f, minDamage = 0.5f;
  int pellets = 1;
  float spread = 0.0f;  // rad: each pellet leaves within this angle either side of the aim
  // Budget spent crossing materials (LevelMaterial::thickness, ActorTuning::thickness); the
  // damage left is in proportion to the budget left.
  float penetration = 0.0f;
  int ricochets = 0;           // bounces at most
  float ricochetAngle = 0.0f;  // rad: bounces off hard surfaces met at less than this
  float ricochetSin = 0.0f;    // its sine (rc::sincos), what the tracer compares
  float ricochetLoss = 0.0f;   // fraction of the damage lost per bounce
  float impulse = 4.0f;        // N s given to a dynamic body hit at full damage
};

struct GrenadeSpec {
  float muzzleVelocity = 12.0f;  // m/s, added to the thrower's velocity
  float radius = 0.1f;           // m
  float density = 2.0f;          // kg/m^2
  float restitution = 0.6f;
  float friction = 0.4f;
  float linearDamping = 1.2f;  // 1/s: rolling on the floor (top-down: nothing else slows it)
  int fuseTicks = 120;
  float blastRadius = 5.0f;    // m
  float blastDamage = 100.0f;  // at the centre, down linearly to 0 at the radius
  float blastImpulse = 15.0f;  // N s at the centre, down linearly to 0 at the radius
};

struct WeaponSpec {
  std::string name;
  WeaponKind kind = WeaponKind::hitscan;
  int cooldownTicks = 8;  // before the actor can fire or throw again
  int ammo = 90;          // what an actor carries when it (re)spawns
  HitscanSpec hitscan;    // kind hitscan
  GrenadeSpec grenade;    // kind grenade
};

struct WeaponTable {
  std::string source;  // the file it was read from
  std::string text;    // what the file said (a recording carries it: weapons.json may change)
  std::vector<WeaponSpec> weapons;
  // The weapon thrown by kButtonThrow: the table's first grenade, if it has one.
  std::optional<std::size_t> grenade() const;
};

// The file read and checked; WeaponTableError on any problem.
WeaponTable loadWeaponTable(const std::string& path);
// The same from text already read (`source` names it in messages).
WeaponTable parseWeaponTable(std::string_view text, const std::string& source);
// The bundled table, assets/weapons.json (found by its source path, or $RICOCHET_WEAPONS).
std::string bundledWeaponTablePath();

}  // namespace game
