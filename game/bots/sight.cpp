#include "game/bots/sight.h"

#include <cmath>

#include "game/bots/memory.h"
#include "game/bots/navigation.h"
#include "physics/trig.h"

namespace game {
namespace {

rc::QueryFilter othersThan(const Actor& me) {
  return rc::QueryFilter::ignoring(me.body, {0xFFFFFFFFu, 0xFFFFFFFFu});
}

}  // namespace

bool inCone(const MatchState& s, std::size_t viewer, std::size_t other, const SightTuning& tuning) {
  const Actor& me = s.actors[viewer];
  const Actor& them = s.actors[other];
  if (!me.alive || !them.alive || viewer == other) return false;
  const rc::Vec2 d = s.world->worldCenter(them.body) - s.world->worldCenter(me.body);
  const float distance2 = rc::lengthSquared(d);
  if (distance2 > tuning.range * tuning.range) return false;
  // The angle between the aim and the direction, compared by its cosine.
  const rc::SinCos sc = rc::sincos(me.aim);
  const float along = sc.cosine * d.x + sc.sine * d.y;
  const float limit = rc::cos(tuning.halfAngle);
  return !(distance2 > 0.0f && along < limit * std::sqrt(distance2));
}

bool sees(const MatchState& s, std::size_t viewer, std::size_t other, const SightTuning& tuning) {
  if (!inCone(s, viewer, other, tuning)) return false;
  const Actor& me = s.actors[viewer];
  const rc::Vec2 from = s.world->worldCenter(me.body);
  const rc::Vec2 to = s.world->worldCenter(s.actors[other].body);
  const std::optional<rc::WorldHit> hit = s.world->castRay(from, to - from, othersThan(me));
  return hit && hit->body == s.actors[other].body;
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

bool looksAt(std::int64_t tick, std::size_t viewer) {
  return (tick + static_cast<std::int64_t>(viewer)) % kLookEvery == 0;
}

void look(MatchState& s, std::size_t viewer, const SightTuning& tuning) {
  const Actor& me = s.actors[viewer];
  BotMind& mind = s.minds[viewer];
  mind.lastLook = s.tick;
  const rc::Vec2 from = s.world->worldCenter(me.body);
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    const Actor& other = s.actors[i];
    if (other.team == me.team || !inCone(s, viewer, i, tuning)) continue;
    const rc::Vec2 to = s.world->worldCenter(other.body);
    // The grid answers first when it can: a point inside a wall short of the target's disc means
    // the ray would meet the wall first (most rays in a maze); the same answer, no cast.
    const rc::Vec2 d = to - from;
    const float distance = rc::length(d);
    if (distance > s.tuning.radius) {
      const rc::Vec2 reach = from + ((distance - s.tuning.radius) / distance) * d;
      if (const std::optional<rc::Vec2> wall = pointInsideWall(s.nav, from, reach)) {
        s.sightRays.push_back(
            {static_cast<std::int32_t>(viewer), static_cast<std::int32_t>(i), from, *wall, false});
        continue;
      }
    }
    const std::optional<rc::WorldHit> hit = s.world->castRay(from, d, othersThan(me));
    const bool clear = hit && hit->body == other.body;
    s.sightRays.push_back({static_cast<std::int32_t>(viewer), static_cast<std::int32_t>(i), from,
                           clear ? to : (hit ? hit->point : to), clear});
    if (!clear) continue;
    Perception p;
    p.actor = static_cast<std::int32_t>(i);
    p.sense = Sense::seen;
    p.position = to;
    p.velocity = s.world->linearVelocity(other.body);
    p.strength = 1.0f;
    remember(mind, p, s.tick);
  }
}

}  // namespace game
