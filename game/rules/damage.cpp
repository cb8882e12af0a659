#include "game/rules/damage.h"

#include <algorithm>

namespace game {

void killActor(MatchState& s, std::size_t actor, std::optional<std::size_t> attacker) {
  Actor& a = s.actors[actor];
  if (!a.alive) return;
  a.alive = false;
  a.health = 0.0f;
  ++a.deaths;
  a.respawnTick = s.tick + static_cast<std::int64_t>(s.tuning.respawnSeconds * kTicksPerSecond);
  s.world->setLinearVelocity(a.body, {});
  s.world->setEnabled(a.body, false);
  if (attacker && *attacker != actor && s.actors[*attacker].team != a.team)
    ++s.actors[*attacker].kills;
}

void damageActor(MatchState& s, std::size_t actor, float amount,
                 std::optional<std::size_t> attacker) {
  Actor& a = s.actors[actor];
  if (!a.alive || !(amount > 0.0f)) return;
  a.health = std::max(0.0f, a.health - amount);
  if (a.health == 0.0f) killActor(s, actor, attacker);
}

void damageProp(MatchState& s, std::size_t object, float amount) {
  for (PropState& p : s.props) {
    if (p.object != object || p.destroyed || !(amount > 0.0f)) continue;
    p.health = std::max(0.0f, p.health - amount);
    if (p.health == 0.0f) {
      p.destroyed = true;
      s.world->destroyBody(p.body);
    }
    return;
  }
}

}  // namespace game
