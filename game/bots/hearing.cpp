#include "game/bots/hearing.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "game/bots/memory.h"
#include "game/bots/navigation.h"
#include "game/weapons/hitscan.h"

namespace game {

void makeSound(MatchState& s, SoundKind kind, std::size_t maker, rc::Vec2 position, float radius) {
  Sound sound;
  sound.kind = kind;
  sound.maker = static_cast<std::int32_t>(maker);
  sound.team = s.actors[maker].team;
  sound.position = position;
  sound.radius = radius;
  s.sounds.push_back(sound);
}

void makeFootstep(MatchState& s, std::size_t actor, float speed) {
  if (speed < kSilentSpeed || (s.tick + static_cast<std::int64_t>(actor)) % kStrideTicks != 0)
    return;
  makeSound(s, SoundKind::footstep, actor, s.world->worldCenter(s.actors[actor].body),
            kFootstepSeconds * speed);
}

int wallsBetween(const MatchState& s, rc::Vec2 from, rc::Vec2 to, int limit) {
  if (limit <= 0) return 0;
  const rc::QueryFilter walls = staticSolids(*s.world);
  if (limit == 1) return s.world->castRay(from, to - from, walls) ? 1 : 0;
  const std::vector<rc::WorldHit> hits = s.world->castRayAll(from, to - from, walls);
  const float length = rc::length(to - from);
  if (!(length > 0.0f))
    return static_cast<int>(std::min<std::size_t>(hits.size(), static_cast<std::size_t>(limit)));
  // One wall may be several convex pieces (a concave outline split): the pieces the ray crosses
  // with no open space between them (one's exit within kWallSeam of the next's entry) are one
  // wall. Where the ray leaves a piece, as a fraction of the way: exitOf (a solid's far side, a
  // tile region's outline), or `to` if it does not.
  const rc::Vec2 dir = (1.0f / length) * (to - from);
  auto leaves = [&](const rc::WorldHit& h) {
    const std::optional<RayExit> exit = exitOf(*s.world, h, dir, (1.0f - h.fraction) * length);
    return exit ? h.fraction + exit->distance / length : 1.0f;
  };
  const float seam = kWallSeam / length;
  int count = 0;
  float end = 0.0f;
  for (const rc::WorldHit& h : hits) {
    if (count > 0 && h.fraction <= end + seam) {
      end = std::max(end, leaves(h));
      continue;
    }
    if (++count >= limit) break;
    end = leaves(h);
  }
  return count;
}

std::optional<int> hears(const MatchState& s, std::size_t listener, const Sound& sound) {
  const Actor& me = s.actors[listener];
  if (!me.alive || sound.maker == static_cast<std::int32_t>(listener) || sound.team == me.team)
    return std::nullopt;
  const rc::Vec2 at = s.world->worldCenter(me.body);
  const float distance = rc::distance(at, sound.position);
  if (!(distance <= sound.radius)) return std::nullopt;
  // Walls it can afford: the largest k with distance <= radius / 2^k; one more makes it
  // inaudible, so counting stops there.
  int affordable = 0;
  for (float r = sound.radius * 0.5f; distance <= r && affordable < 30; r *= 0.5f)
    ++affordable;
  const int walls = wallsBetween(s, sound.position, at, affordable + 1);
  if (walls > affordable) return std::nullopt;
  return walls;
}

void listen(MatchState& s, std::size_t listener) {
  for (const Sound& sound : s.sounds) {
    const std::optional<int> walls = hears(s, listener, sound);
    if (!walls) continue;
    Perception p;
    p.actor = sound.maker;
    p.sense = Sense::heard;
    p.position = sound.position;
    p.strength = kHeardStrength;
    remember(s.minds[listener], p, s.tick);
    s.heard.push_back(
        {static_cast<std::int32_t>(listener), sound, *walls, std::ldexp(sound.radius, -*walls)});
  }
}

}  // namespace game
