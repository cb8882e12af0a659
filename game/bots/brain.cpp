// The decide phase: players take the input they were given; bots, and players without one (the
// autopilot), choose theirs from what they perceive: an enemy in sight is shot at (with aim
// error) while keeping a fighting distance; one seen lately is looked for where it was last
// seen (now and then throwing a grenade there: it may be behind cover); otherwise the bot walks to
// goals picked among the level's points.
#include <cmath>

#include "game/bots/sight.h"
#include "physics/trig.h"

namespace game {
namespace {

constexpr float kAimError = 0.06f;           // rad, either way
constexpr float kFar = 10.0f, kNear = 4.0f;  // m: the distance it keeps from an enemy
constexpr std::int64_t kMemoryTicks = 3 * kTicksPerSecond;
constexpr std::int64_t kGoalTicks = 10 * kTicksPerSecond;
constexpr int kStuckTicks = kTicksPerSecond;
// A grenade goes where an enemy was last seen when it is this far (m: outside the blast, within
// a throw's roll), the bot's turn comes (every 2 s, staggered across bots) and the first
// kThrowNear m of the throw are clear (a grenade thrown into a wall comes back).
constexpr float kThrowNear = 5.0f, kThrowFar = 12.0f;
constexpr std::int64_t kThrowEvery = 2 * kTicksPerSecond;

float angleOf(rc::Vec2 d) {
  return rc::atan2(d.y, d.x);
}

// Somewhere to walk to: a spawn, pickup, marker or path point of the level, at random.
rc::Vec2 pickGoal(MatchState& s, rc::Vec2 fallback) {
  std::vector<rc::Vec2> points;
  for (const LevelSpawn& p : s.built.spawns)
    points.push_back(p.position);
  for (const LevelPickup& p : s.built.pickups)
    points.push_back(p.position);
  for (const LevelMarker& p : s.built.markers)
    points.push_back(p.position);
  for (const LevelPath& path : s.built.paths)
    for (rc::Vec2 p : path.points)
      points.push_back(p);
  if (points.empty()) return fallback;
  return points[s.rng.below(static_cast<std::uint32_t>(points.size()))];
}

PlayerInput decide(MatchState& s, std::size_t i) {
  Actor& a = s.actors[i];
  BotMind& mind = s.minds[i];
  const rc::Vec2 at = s.world->worldCenter(a.body);
  const std::optional<std::size_t> enemy = nearestSeenEnemy(s, i);
  if (enemy) {
    mind.target = enemy;
    mind.lastSeen = s.world->worldCenter(s.actors[*enemy].body);
    mind.lastSeenTick = s.tick;
    const rc::Vec2 d = mind.lastSeen - at;
    const float distance = rc::length(d);
    const rc::Vec2 toward = distance > 0.0f ? (1.0f / distance) * d : rc::Vec2{1, 0};
    if ((s.tick + static_cast<std::int64_t>(i) * 17) % 90 == 0) mind.strafe = -mind.strafe;
    rc::Vec2 move = mind.strafe * rc::Vec2{-toward.y, toward.x};
    if (distance > kFar) move = toward;
    if (distance < kNear) move = -toward;
    const float aim = angleOf(d) + s.rng.uniform(-kAimError, kAimError);
    return makeInput(move, aim, kButtonFire, 0);
  }
  rc::Vec2 goal;
  std::uint8_t buttons = 0;
  if (mind.lastSeenTick >= 0 && s.tick - mind.lastSeenTick < kMemoryTicks) {
    goal = mind.lastSeen;  // where the enemy was: look there
    const std::optional<std::size_t> grenade = s.weapons.grenade();
    const float distance = rc::length(goal - at);
    // (Its hand is free in the weapons phase if the cooldown is at most 1: it counts down first.)
    if (grenade && a.ammo[*grenade] > 0 && a.cooldown <= 1 && distance > kThrowNear &&
        distance < kThrowFar && (s.tick + static_cast<std::int64_t>(i) * 13) % kThrowEvery == 0) {
      const float radius = s.weapons.weapons[*grenade].grenade.radius;
      const rc::Vec2 path = (kThrowNear / distance) * (goal - at);
      const rc::QueryFilter others = rc::QueryFilter::ignoring(a.body, {0xFFFFFFFFu, 0xFFFFFFFFu});
      if (!s.world->castCircle(at, radius, path, others)) {
        // Thrown: stop walking after it and step back the other way instead.
        buttons = kButtonThrow;
        mind.lastSeenTick = -1;
        mind.goal = at - path;
        mind.goalTick = s.tick;
        mind.stuckTicks = 0;
      }
    }
  } else {
    const bool reached = mind.goalTick >= 0 && rc::distanceSquared(at, mind.goal) < 1.0f;
    if (mind.goalTick < 0 || reached || s.tick - mind.goalTick > kGoalTicks ||
        mind.stuckTicks > kStuckTicks) {
      mind.goal = pickGoal(s, at);
      mind.goalTick = s.tick;
      mind.stuckTicks = 0;
    }
    goal = mind.goal;
  }
  const rc::Vec2 d = goal - at;
  if (rc::lengthSquared(d) < 0.01f) return makeInput({}, a.aim, 0, 0);
  const bool barelyMoving = rc::lengthSquared(s.world->linearVelocity(a.body)) < 0.25f;
  mind.stuckTicks = barelyMoving ? mind.stuckTicks + 1 : 0;
  return makeInput(rc::normalize(d), angleOf(d), buttons, 0);
}

}  // namespace

void decideBots(MatchState& s, std::span<const PlayerInput> inputs) {
  std::size_t player = 0;
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    Actor& a = s.actors[i];
    a.input = a.alive ? decide(s, i) : PlayerInput{};
    // A player's given input replaces the autopilot's choice, which is made all the same: the
    // match draws the same randomness whether the input came from the autopilot, a script or a
    // recording of either, so a recording replays exactly.
    if (a.kind == ActorKind::player && player++ < inputs.size()) a.input = inputs[player - 1];
  }
}

}  // namespace game
