#include "game/bots/sight.h"

#include <cmath>

#include "physics/trig.h"

namespace game {

bool sees(const MatchState& s, std::size_t viewer, std::size_t other, const SightTuning& tuning) {
  const Actor& me = s.actors[viewer];
  const Actor& them = s.actors[other];
  if (!me.alive || !them.alive || viewer == other) return false;
  const rc::Vec2 from = s.world->worldCenter(me.body);
  const rc::Vec2 to = s.world->worldCenter(them.body);
  const rc::Vec2 d = to - from;
  const float distance2 = rc::lengthSquared(d);
  if (distance2 > tuning.range * tuning.range) return false;
  // Inside the cone: the angle between the aim and the direction, compared by its cosine.
  const rc::SinCos sc = rc::sincos(me.aim);
  const float along = sc.cosine * d.x + sc.sine * d.y;
  const float limit = rc::cos(tuning.halfAngle);
  if (distance2 > 0.0f && along < limit * std::sqrt(distance2)) return false;
  const rc::QueryFilter filter = rc::QueryFilter::ignoring(me.body, {0xFFFFFFFFu, 0xFFFFFFFFu});
  const std::optional<rc::WorldHit> hit = s.world->castRay(from, d, filter);
  return hit && hit->body == them.body;
}

std::optional<std::size_t> nearestSeenEnemy(const MatchState& s, std::size_t viewer,
                                            const SightTuning& tuning) {
  const Actor& me = s.actors[viewer];
  std::optional<std::size_t> best;
  float bestDistance = 0.0f;
  const rc::Vec2 from = s.world->worldCenter(me.body);
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    const Actor& other = s.actors[i];
    if (i == viewer || !other.alive || other.team == me.team) continue;
    const float d = rc::distanceSquared(from, s.world->worldCenter(other.body));
    if (best && d >= bestDistance) continue;
    if (!sees(s, viewer, i, tuning)) continue;
    best = i;
    bestDistance = d;
  }
  return best;
}

}  // namespace game
