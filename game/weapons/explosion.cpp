#include "game/weapons/explosion.h"

#include <algorithm>
#include <vector>

#include "game/bots/hearing.h"
#include "game/rules/damage.h"
#include "game/rules/impacts.h"

namespace game {

void explode(MatchState& s, rc::Vec2 center, const GrenadeSpec& grenade, std::size_t thrower) {
  Explosion e;
  e.thrower = thrower;
  e.center = center;
  e.radius = grenade.blastRadius;
  rc::World& world = *s.world;
  // Candidates: every shape the blast's disc overlaps (sorted by shape id), one body each, in
  // the order of its first shape.
  constexpr rc::ProxyFilter kAll{0xFFFFFFFFu, 0xFFFFFFFFu};
  const rc::QueryFilter everything(kAll);
  const std::vector<rc::ShapeRef> touched =
      world.overlapShape(rc::makeCircle({}, e.radius), rc::Transform{center, {}}, everything);
  std::vector<rc::BodyId> bodies;
  for (const rc::ShapeRef& r : touched)
    if (world.type(r.body) == rc::BodyType::dynamicBody &&
        std::find(bodies.begin(), bodies.end(), r.body) == bodies.end())
      bodies.push_back(r.body);
  // Walls are what hides a target: any static body in the way.
  const rc::QueryFilter walls(kAll, [&world](const rc::ShapeRef& r) {
    return world.type(r.body) == rc::BodyType::staticBody;
  });
  for (const rc::BodyId body : bodies) {
    const rc::Vec2 target = world.worldCenter(body);
    const rc::Vec2 d = target - center;
    const float distance = rc::length(d);
    if (!(distance < e.radius)) continue;
    if (world.castRay(center, d, walls)) continue;  // behind a wall
    const float share = 1.0f - distance / e.radius;
    const std::uint64_t userData = world.userData(body);
    world.wake(body);
    if (distance > 0.0f)
      world.applyLinearImpulse(body, (grenade.blastImpulse * share / distance) * d, target);
    ++e.bodiesPushed;
    blameBlast(s, userData, thrower);
    if (const std::optional<GameRef> ref = gameRefOf(userData);
        ref && ref->kind == GameKind::actor) {
      e.actorsHit.push_back(ref->index);
      damageActor(s, ref->index, grenade.blastDamage * share, thrower);
    } else if (const std::optional<LevelRef> level = levelRefOf(userData)) {
      damageProp(s, level->index, grenade.blastDamage * share);
    }
  }
  makeSound(s, SoundKind::explosion, thrower, center, kExplosionRadius);
  s.explosions.push_back(std::move(e));
}

}  // namespace game
