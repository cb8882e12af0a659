// The weapons phase: grenades whose fuse has run out explode (against the world as the last step
// left it), then every living actor whose input pulls the trigger fires the weapon it selected,
// or throws a grenade, if it is ready and loaded. Shots are taken now, before the step, and heard
// (bots/hearing.h: kShotRadius from the shooter); a throw is silent, its blast is not.
#include "game/weapons/weapons.h"

#include "game/bots/hearing.h"

namespace game {

void arm(Actor& actor, const WeaponTable& table) {
  actor.ammo.fill(0);
  for (std::size_t w = 0; w < table.weapons.size(); ++w)
    actor.ammo[w] = table.weapons[w].ammo;
}

void fireWeapon(MatchState& s, std::size_t actor, std::size_t weapon) {
  if (s.weapons.weapons[weapon].kind == WeaponKind::grenade) {
    throwGrenade(s, actor, weapon);
  } else {
    firePellets(s, actor, weapon);
  }
}

void fireWeapons(MatchState& s) {
  explodeDueGrenades(s);
  const std::optional<std::size_t> grenade = s.weapons.grenade();
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    Actor& a = s.actors[i];
    if (a.cooldown > 0) --a.cooldown;
    if (!a.alive || a.cooldown > 0) continue;
    // A throw takes precedence over the trigger (it is the rarer, deliberate act); with no
    // grenade left the trigger still fires.
    std::optional<std::size_t> weapon;
    if ((a.input.buttons & kButtonThrow) != 0 && grenade && a.ammo[*grenade] > 0) {
      weapon = grenade;
    } else if ((a.input.buttons & kButtonFire) != 0 && a.input.weapon < s.weapons.weapons.size() &&
               a.ammo[a.input.weapon] > 0) {
      weapon = a.input.weapon;
    }
    if (!weapon) continue;
    a.cooldown = s.weapons.weapons[*weapon].cooldownTicks;
    --a.ammo[*weapon];
    fireWeapon(s, i, *weapon);
    if (s.weapons.weapons[*weapon].kind == WeaponKind::hitscan)
      makeSound(s, SoundKind::shot, i, s.world->worldCenter(a.body), kShotRadius);
  }
}

}  // namespace game
