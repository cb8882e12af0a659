// Movement: every living actor's velocity moves towards what its input asks, by at most its
// acceleration in a tick (top-down: no gravity, so this is all that moves it but collisions).
// Running is heard: a footstep now and then, louder the faster (bots/hearing.h).
#include <cmath>

#include "game/bots/hearing.h"
#include "game/match/match.h"

namespace game {

void moveActors(MatchState& s) {
  const float maxChange = s.tuning.acceleration * kTickSeconds;
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    Actor& a = s.actors[i];
    if (!a.alive) continue;
    a.aim = aimOf(a.input);
    const rc::Vec2 wanted = s.tuning.maxSpeed * moveOf(a.input);
    const rc::Vec2 now = s.world->linearVelocity(a.body);
    rc::Vec2 change = wanted - now;
    const float len = rc::length(change);
    if (len > maxChange) change = (maxChange / len) * change;
    if (change != rc::Vec2{}) s.world->setLinearVelocity(a.body, now + change);
    makeFootstep(s, i, rc::length(now + change));
  }
}

}  // namespace game
