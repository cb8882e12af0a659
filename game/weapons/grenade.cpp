#include "game/weapons/grenade.h"

#include <optional>

#include "game/weapons/explosion.h"
#include "physics/trig.h"

namespace game {
namespace {

// The gap between the thrower's disc and the grenade as it leaves the hand (m).
constexpr float kHandGap = 0.05f;

// The lowest free slot, or a new one: slots are reused in order, so the same throws give the
// same slots (and user data) in every run.
std::size_t freeSlot(MatchState& s) {
  for (std::size_t i = 0; i < s.grenades.size(); ++i)
    if (!s.grenades[i].live) return i;
  s.grenades.emplace_back();
  return s.grenades.size() - 1;
}

}  // namespace

void throwGrenade(MatchState& s, std::size_t thrower, std::size_t weapon) {
  const GrenadeSpec& g = s.weapons.weapons[weapon].grenade;
  const Actor& a = s.actors[thrower];
  const rc::SinCos sc = rc::sincos(a.aim);
  const rc::Vec2 dir{sc.cosine, sc.sine};
  const rc::Vec2 center = s.world->worldCenter(a.body);
  const float out = s.tuning.radius + g.radius + kHandGap;
  // Swept from the thrower's centre: a wall nearer than the hand stops it where it touches.
  float reach = out;
  const rc::QueryFilter others = rc::QueryFilter::ignoring(a.body, {0xFFFFFFFFu, 0xFFFFFFFFu});
  if (const std::optional<rc::WorldHit> hit =
          s.world->castCircle(center, g.radius, out * dir, others))
    reach = hit->fraction * out;
  const std::size_t slot = freeSlot(s);
  rc::BodyDef def;
  def.type = rc::BodyType::dynamicBody;
  def.position = center + reach * dir;
  def.linearVelocity = s.world->linearVelocity(a.body) + g.muzzleVelocity * dir;
  def.linearDamping = g.linearDamping;
  def.angularDamping = g.linearDamping;
  def.bullet = true;
  def.userData = gameUserData(GameKind::projectile, slot);
  rc::ShapeDef sd;
  sd.density = g.density;
  sd.friction = g.friction;
  sd.restitution = g.restitution;
  sd.filter = kProjectileFilter;
  sd.userData = def.userData;
  Grenade& grenade = s.grenades[slot];
  grenade = Grenade{};
  grenade.thrower = thrower;
  grenade.weapon = weapon;
  grenade.fuse = g.fuseTicks;
  grenade.live = true;
  grenade.body = s.world->createBody(def);
  s.world->createShape(grenade.body, rc::makeCircle({}, g.radius), sd);
}

void explodeDueGrenades(MatchState& s) {
  for (Grenade& g : s.grenades) {
    if (!g.live || --g.fuse > 0) continue;
    const rc::Vec2 center = s.world->worldCenter(g.body);
    s.world->destroyBody(g.body);
    g.live = false;
    g.body = {};
    explode(s, center, s.weapons.weapons[g.weapon].grenade, g.thrower);
  }
}

void countGrenadeBounces(MatchState& s) {
  for (const rc::ContactHitEvent& e : s.world->contactEvents().hit) {
    for (const rc::ShapeRef* side : {&e.a, &e.b}) {
      const std::optional<GameRef> ref = gameRefOf(side->bodyUserData);
      if (!ref || ref->kind != GameKind::projectile || ref->index >= s.grenades.size()) continue;
      Grenade& g = s.grenades[ref->index];
      if (g.live && g.body == side->body) ++g.bounces;
    }
  }
}

}  // namespace game
