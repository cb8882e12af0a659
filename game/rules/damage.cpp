#include "game/rules/damage.h"

#include <algorithm>

#include "game/rules/score.h"

namespace game {

void killActor(MatchState& s, std::size_t actor, std::optional<std::size_t> attacker) {
  Actor& a = s.actors[actor];
  if (!a.alive) return;
  a.alive = false;
  a.health = 0.0f;
  a.respawnTick = s.tick + static_cast<std::int64_t>(s.tuning.respawnSeconds * kTicksPerSecond);
  s.world->setLinearVelocity(a.body, {});
  s.world->setEnabled(a.body, false);
  scoreDeath(s, actor, attacker);
}

void damageActor(MatchState& s, std::size_t actor, float amount,
                 std::optional<std::size_t> attacker) {
  Actor& a = s.actors[actor];
  if (!a.alive || !(amount > 0.0f)) return;
  a.health = std::max(0.0f, a.health - amount);
  if (a.health == 0.0f) killActor(s, actor, attacker);
}

PropState* propOf(MatchState& s, std::size_t object) {
  for (PropState& p : s.props)
    if (p.object == object) return &p;
  return nullptr;
}

void damageProp(MatchState& s, std::size_t object, float amount) {
  PropState* p = propOf(s, object);
  if (p == nullptr || !p->destructible || p->destroyed || !(amount > 0.0f)) return;
  p->health = std::max(0.0f, p->health - amount);
  if (p->health == 0.0f) {
    p->destroyed = true;
    s.world->destroyBody(p->body);
  }
}

}  // namespace game
