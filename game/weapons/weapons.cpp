// The weapons phase: every living actor whose input pulls the trigger fires, if its weapon is
// ready and loaded. Shots are taken now, against where everything is before the step.
#include "game/weapons/weapons.h"

#include <algorithm>

#include "game/rules/damage.h"
#include "physics/trig.h"

namespace game {

float damageAt(const WeaponSpec& weapon, float distance) {
  if (distance <= weapon.falloffStart) return weapon.damage;
  if (distance >= weapon.falloffEnd) return weapon.minDamage * weapon.damage;
  const float t = (distance - weapon.falloffStart) / (weapon.falloffEnd - weapon.falloffStart);
  return weapon.damage * (1.0f - t * (1.0f - weapon.minDamage));
}

void fireHitscan(MatchState& s, std::size_t shooter, const WeaponSpec& weapon) {
  const Actor& a = s.actors[shooter];
  const rc::SinCos sc = rc::sincos(a.aim);
  const rc::Vec2 dir{sc.cosine, sc.sine};
  const rc::Vec2 from = s.world->worldCenter(a.body);
  Shot shot;
  shot.shooter = shooter;
  shot.path.push_back(from);
  const rc::QueryFilter filter = rc::QueryFilter::ignoring(a.body, {0xFFFFFFFFu, 0xFFFFFFFFu});
  const std::optional<rc::WorldHit> hit = s.world->castRay(from, weapon.range * dir, filter);
  if (!hit) {
    shot.path.push_back(from + weapon.range * dir);
    s.shots.push_back(std::move(shot));
    return;
  }
  shot.path.push_back(hit->point);
  const float distance = hit->fraction * weapon.range;
  const float damage = damageAt(weapon, distance);
  if (const std::optional<GameRef> ref = gameRefOf(hit->bodyUserData);
      ref && ref->kind == GameKind::actor) {
    shot.actorsHit.push_back(ref->index);
    damageActor(s, ref->index, damage, shooter);
  } else if (const std::optional<LevelRef> level = levelRefOf(hit->bodyUserData)) {
    damageProp(s, level->index, damage);
  }
  if (s.world->isValid(hit->body) && s.world->type(hit->body) == rc::BodyType::dynamicBody &&
      s.world->isEnabled(hit->body))
    s.world->applyLinearImpulse(hit->body, weapon.impulse * dir, hit->point);
  s.shots.push_back(std::move(shot));
}

void fireWeapons(MatchState& s) {
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    Actor& a = s.actors[i];
    if (a.cooldown > 0) --a.cooldown;
    if (!a.alive || (a.input.buttons & kButtonFire) == 0 || a.cooldown > 0 || a.ammo <= 0) continue;
    a.cooldown = kRifle.cooldownTicks;
    --a.ammo;
    fireHitscan(s, i, kRifle);
  }
}

}  // namespace game
