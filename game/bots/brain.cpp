// The decide phase: players take the input they were given; bots, and players without one (the
// autopilot), perceive (hearing every tick, sight every kLookEvery ticks, staggered) into their
// memory and choose their input from it alone, by a small state machine:
//
//   patrol       nothing remembered: walk between the level's patrol points (its spawns,
//                pickups, markers and path points, and open places spread between them), along
//                grid paths (navigation.h)
//   fetch        hurt (at most kHurtFraction of full health) or short of rounds (every gun at
//                most kLowAmmoFraction of a spawn's), and no enemy in sight (or none remembered;
//                or out of rounds altogether): walk to the nearest pickup there that gives what it
//                lacks (a bot knows the map: where pickups are and whether they are there now),
//                facing the way it walks, or the enemy it remembers
//   investigate  the strongest memory is a sound: walk to where it came from, facing it; once
//                there, look around until the memory fades
//   chase        the strongest memory is an enemy seen but no longer in sight: walk to where it
//                should be by now, facing it; now and then a grenade goes there first (never
//                near a friend: a team knows where its own are)
//   attack       the strongest memory is an enemy in sight: shoot at it with aim error (never
//                through a friend), with the gun that deals the most at that distance of those
//                with rounds left, keeping a fighting distance and sidestepping
//   take cover   hurt (at most kHurtFraction of full health), hit again and an enemy
//                remembered: go to the nearest place it cannot see (cover.h), face it, fire
//                back when it shows; after kHideTicks (health does not come back) it fights on
//                as above until the next hit
//   flee         the same, with no cover in reach: run to the place farthest from it
//
// The memory fading to nothing brings every behaviour back to patrol. A patrolling bot stuck
// against an actor created before it gives way: it turns to a patrol point whose way leads away
// from what it touches (two bots meeting in a one-tile corridor would otherwise push each other
// for ever). A bot turns at
// most kTurnRate: its view cone, and so what it can see, follows its aim.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "game/bots/cover.h"
#include "game/bots/hearing.h"
#include "game/bots/memory.h"
#include "game/bots/navigation.h"
#include "game/bots/sight.h"
#include "game/rules/pickups.h"
#include "game/weapons/hitscan.h"
#include "physics/trig.h"

namespace game {

const char* behaviourName(Behaviour behaviour) {
  switch (behaviour) {
    case Behaviour::patrol:
      return "patrol";
    case Behaviour::investigate:
      return "investigate";
    case Behaviour::chase:
      return "chase";
    case Behaviour::attack:
      return "attack";
    case Behaviour::takeCover:
      return "take cover";
    case Behaviour::flee:
      return "flee";
    case Behaviour::fetch:
      return "fetch";
  }
  return "?";
}

const char* soundKindName(SoundKind kind) {
  switch (kind) {
    case SoundKind::footstep:
      return "footstep";
    case SoundKind::shot:
      return "shot";
    case SoundKind::explosion:
      return "explosion";
  }
  return "?";
}

namespace {

constexpr float kHurtFraction = 0.5f;
constexpr float kLowAmmoFraction = 0.25f;
constexpr float kTurnRate = 8.0f;  // rad/s: half a turn in 0.4 s
constexpr float kTurnPerTick = kTurnRate / kTicksPerSecond;
constexpr float kScanPerTick = 2.0f / kTicksPerSecond;  // rad: looking around where it went
// Aim error, uniform either way: a base and more for a target that moves (rad per m/s).
constexpr float kAimError = 0.04f, kAimErrorPerSpeed = 0.01f;
constexpr float kFireCone = 0.15f;           // rad: it fires once its aim is this near the target
constexpr float kFar = 10.0f, kNear = 4.0f;  // m: the distance it keeps from an enemy
constexpr std::int64_t kLead = 30;           // ticks: how far ahead it expects a seen enemy
constexpr std::int64_t kGoalTicks = 60 * kTicksPerSecond;   // a patrol goal is given up after
constexpr int kStuckTicks = kTicksPerSecond / 2;            // barely moving: sidestep
constexpr std::int64_t kReplanTicks = kTicksPerSecond / 2;  // a moving target: replan at most
constexpr std::int64_t kCoverTicks = 2 * kTicksPerSecond;   // seen in cover: find another after
constexpr std::int64_t kHideTicks = 4 * kTicksPerSecond;    // in cover or fleeing at most
constexpr float kWaypointReach = 0.4f;                      // m
constexpr float kArrive = 0.75f;                            // m: a goal is reached
constexpr float kPersonalSpace = 1.5f;  // m, centre to centre: friends keep apart
constexpr float kApartWeight = 1.5f;    // how hard: a friend touching adds 0.8 of a step away
constexpr float kHazardProbe = 0.6f;    // m: how far ahead a walk is checked for hazards
// A grenade goes where an enemy was last seen when it is this far (m: outside the blast, within
// a throw's roll), the bot's turn comes (every 2 s, staggered across bots) and the first
// kThrowNear m of the throw are clear (a grenade thrown into a wall comes back) and no friend is
// near where it lands; then the bot steps back for the fuse's time.
constexpr float kThrowNear = 5.0f, kThrowFar = 12.0f;
constexpr std::int64_t kThrowEvery = 2 * kTicksPerSecond;

float angleOf(rc::Vec2 d) {
  return rc::atan2(d.y, d.x);
}

// The angle in (-pi, pi].
float wrapAngle(float a) {
  while (a > rc::kPi)
    a -= 2.0f * rc::kPi;
  while (a <= -rc::kPi)
    a += 2.0f * rc::kPi;
  return a;
}

// The aim turned towards `wanted` by at most a tick's turn.
float turnToward(float aim, float wanted) {
  const float delta = wrapAngle(wanted - aim);
  return aim + std::fmax(-kTurnPerTick, std::fmin(kTurnPerTick, delta));
}

// Whether a step of `move` from `at` leaves plain ground for a hurt zone's margin (a costly cell
// kHazardProbe ahead, from one that is not).
bool intoHurt(const MatchState& s, rc::Vec2 at, rc::Vec2 move) {
  if (move == rc::Vec2{}) return false;
  const int here = s.nav.cellAt(at), ahead = s.nav.cellAt(at + kHazardProbe * move);
  return here >= 0 && ahead >= 0 && s.nav.costly(ahead) && !s.nav.costly(here);
}

// Plans the bot's route to `target` from `at` now: grid cells from the nearest passable one to
// the one nearest the target (down a distance field for a patrol point, else by A*), smoothed.
// An empty route (no grid, no path) means walking straight at the target.
void plan(MatchState& s, std::size_t i, rc::Vec2 at, rc::Vec2 target) {
  NavRoute& route = s.minds[i].route;
  route = NavRoute{};
  route.target = target;
  route.planned = s.tick;
  const NavGrid& nav = s.nav;
  const int start = nearestPassable(nav, at);
  if (start < 0) return;
  const int goal = nearestPassable(nav, target, nav.region[static_cast<std::size_t>(start)]);
  if (goal < 0) return;
  std::vector<int>& cells = s.navSearch.path;
  const auto point = std::find(nav.patrol.begin(), nav.patrol.end(), goal);
  const bool found =
      point != nav.patrol.end() && nav.center(goal) == target
          ? pathToPatrolPoint(nav, start, static_cast<std::size_t>(point - nav.patrol.begin()),
                              s.navSearch, cells)
          : findPath(nav, start, goal, s.navSearch, cells);
  if (!found) return;
  const std::vector<rc::Vec2> points = smoothPath(nav, at, cells, kRouteWaypoints);
  for (const rc::Vec2 p : points)
    route.points[route.length++] = p;
  route.partial = route.length == kRouteWaypoints && points.back() != nav.center(goal);
}

// The way to walk towards `target` this tick (a unit vector, or zero once there): along the
// route, planned again when there is none, at the end of a partial one, when the target has moved
// a metre from where it was planned to (at once when the behaviour changed since, else at most
// every kReplanTicks), or once when the bot has
// been stuck for twice kStuckTicks (pushed off its route). Stuck for kStuckTicks, it sidesteps,
// one way or the other in turn, to slide past what blocks it.
rc::Vec2 steer(MatchState& s, std::size_t i, rc::Vec2 at, rc::Vec2 target) {
  BotMind& mind = s.minds[i];
  NavRoute& route = mind.route;
  const bool moved =
      (s.tick - route.planned >= kReplanTicks || route.planned < mind.behaviourSince) &&
      rc::distanceSquared(route.target, target) > 1.0f;
  if (route.planned < 0 || (route.next >= route.length && route.partial) || moved ||
      mind.stuckTicks == 2 * kStuckTicks)
    plan(s, i, at, target);
  auto way = [&]() -> rc::Vec2 {
    while (route.next < route.length &&
           rc::distanceSquared(at, route.points[route.next]) < kWaypointReach * kWaypointReach)
      ++route.next;
    const rc::Vec2 to = route.next < route.length ? route.points[route.next] : target;
    const rc::Vec2 d = to - at;
    if (rc::lengthSquared(d) < kArrive * kArrive && route.next >= route.length) return {};
    const rc::Vec2 ahead = rc::normalize(d);
    if (mind.stuckTicks < kStuckTicks) return ahead;
    const float side =
        (static_cast<int>(i) + mind.stuckTicks / kStuckTicks) % 2 == 0 ? 1.0f : -1.0f;
    return rc::normalize(ahead + side * rc::Vec2{-ahead.y, ahead.x});
  };
  rc::Vec2 dir = way();
  // About to enter a hazard's margin (pushed off its route, or sidestepping): plan again from
  // here, once a tick; the route starts on the nearest cell that is no hazard. About to leave
  // plain ground for a hurt zone's margin on a route planned a while ago (pushed off it: the
  // straight walk to its next waypoint may now cross the zone): plan again too, at most every
  // kReplanTicks (a new route may cross it on purpose, where going round costs more).
  const int probe = s.nav.cellAt(at + kHazardProbe * dir);
  const bool hazard =
      probe >= 0 && (s.nav.flags[static_cast<std::size_t>(probe)] & NavGrid::kHazard) != 0;
  const bool hurt = s.tick - route.planned >= kReplanTicks && intoHurt(s, at, dir);
  if ((hazard || hurt) && route.planned != s.tick) {
    plan(s, i, at, target);
    dir = way();
  }
  return dir;
}

// Where the actors it touches are, from `at`: the sum of the directions to those whose index is
// below `below` (zero when it touches none): what a bot bumped into, felt, not seen.
rc::Vec2 bumpedInto(const MatchState& s, std::size_t i, rc::Vec2 at, std::size_t below) {
  const float touch = 2.0f * s.tuning.radius + 0.05f;
  rc::Vec2 sum{};
  for (std::size_t j = 0; j < below && j < s.actors.size(); ++j) {
    if (j == i || !s.actors[j].alive) continue;
    const rc::Vec2 d = s.centers[j] - at;
    if (rc::lengthSquared(d) < touch * touch) sum += d;
  }
  return sum;
}

// Somewhere to patrol to: one of the grid's patrol points in the bot's region (not the one it
// stands on), at random, and if `away` is not zero one whose way sets off against it; without a
// grid, one of the level's places.
rc::Vec2 pickGoal(MatchState& s, rc::Vec2 at, rc::Vec2 away) {
  const NavGrid& nav = s.nav;
  const int start = nearestPassable(nav, at);
  if (start < 0 || nav.patrol.empty()) {
    std::vector<rc::Vec2> places;
    for (const LevelSpawn& p : s.built.spawns)
      places.push_back(p.position);
    for (const LevelPickup& p : s.built.pickups)
      places.push_back(p.position);
    if (places.empty()) return at;
    return places[s.rng.below(static_cast<std::uint32_t>(places.size()))];
  }
  const std::int32_t region = nav.region[static_cast<std::size_t>(start)];
  int fallback = start;
  for (int tries = 0; tries < 8; ++tries) {
    const std::size_t point = s.rng.below(static_cast<std::uint32_t>(nav.patrol.size()));
    const int c = nav.patrol[point];
    if (c == start || nav.region[static_cast<std::size_t>(c)] != region) continue;
    fallback = c;
    if (away == rc::Vec2{}) return nav.center(c);
    std::vector<int>& cells = s.navSearch.path;
    if (pathToPatrolPoint(nav, start, point, s.navSearch, cells) && cells.size() > 1 &&
        rc::dot(nav.center(cells[1]) - nav.center(cells[0]), away) < 0.0f)
      return nav.center(c);
  }
  return nav.center(fallback);
}

// At most kHurtFraction of full health: a hit sends it to cover, and it fetches health.
bool isHurt(const MatchState& s, const Actor& a) {
  return a.health <= kHurtFraction * s.tuning.health;
}

bool isGun(const WeaponSpec& weapon) {
  return weapon.kind == WeaponKind::hitscan;
}

// Short of rounds: it has guns and each has at most kLowAmmoFraction of a spawn's rounds left
// (a full shotgun still fights when the rifle is low). Out of rounds: none has any.
bool isShortOfRounds(const MatchState& s, const Actor& a) {
  bool guns = false;
  for (std::size_t w = 0; w < s.weapons.weapons.size(); ++w) {
    const WeaponSpec& weapon = s.weapons.weapons[w];
    if (!isGun(weapon)) continue;
    guns = true;
    if (static_cast<float>(a.ammo[w]) > kLowAmmoFraction * static_cast<float>(weapon.ammo))
      return false;
  }
  return guns;
}
bool isOutOfRounds(const MatchState& s, const Actor& a) {
  for (std::size_t w = 0; w < s.weapons.weapons.size(); ++w)
    if (isGun(s.weapons.weapons[w]) && a.ammo[w] > 0) return false;
  return true;
}

// The gun it fires at an enemy `distance` m away: of those with rounds left, the one that deals
// the most a tick there to an actor (expectedDamagePerTick); of equals (none reaching, say), the
// one reaching farthest, then the lower index. With no rounds at all, the one it holds (it fires
// nothing).
std::uint8_t chooseGun(const MatchState& s, const Actor& a, float distance) {
  std::uint8_t best = a.input.weapon;
  float bestDamage = -1.0f, bestRange = 0.0f;
  for (std::size_t w = 0; w < s.weapons.weapons.size(); ++w) {
    const WeaponSpec& weapon = s.weapons.weapons[w];
    if (!isGun(weapon) || a.ammo[w] <= 0) continue;
    const float damage = expectedDamagePerTick(weapon, distance, s.tuning.radius);
    if (damage > bestDamage || (damage == bestDamage && weapon.hitscan.range > bestRange)) {
      best = static_cast<std::uint8_t>(w);
      bestDamage = damage;
      bestRange = weapon.hitscan.range;
    }
  }
  return best;
}

// The pickup a bot goes for (fetch): the nearest (straight, ties to the lower index) that is
// there, on the bot's part of the grid, and gives what it lacks (health when hurt, rounds of a
// gun when short of them); none when it lacks nothing.
std::optional<rc::Vec2> neededPickup(const MatchState& s, std::size_t i, rc::Vec2 at) {
  const Actor& a = s.actors[i];
  const bool hurt = isHurt(s, a);
  const bool shortOfRounds = isShortOfRounds(s, a);
  if (!hurt && !shortOfRounds) return std::nullopt;
  const int start = nearestPassable(s.nav, at);
  const std::int32_t region = start >= 0 ? s.nav.region[static_cast<std::size_t>(start)] : -1;
  std::optional<rc::Vec2> best;
  float bestDistance = 0.0f;
  for (const PickupState& p : s.pickups) {
    const bool wanted = (hurt && p.item == PickupItem::health) ||
                        (shortOfRounds && p.item == PickupItem::ammo &&
                         p.weapon < s.weapons.weapons.size() && isGun(s.weapons.weapons[p.weapon]));
    if (!p.available || !wanted || !(pickupGift(s, a, p) > 0.0f)) continue;
    if (start >= 0) {
      // Reachable from here: a cell of its region from whose centre an actor touches it (the
      // cell under it, usually; a pickup tucked into a corner may have none, and a bot sent
      // there would wait beside it for ever).
      const int under = s.nav.cellAt(p.position);
      const int cell = s.nav.passable(under) ? under : nearestPassable(s.nav, p.position, region);
      const float touch = p.radius + s.tuning.radius;
      if (cell < 0 || s.nav.region[static_cast<std::size_t>(cell)] != region ||
          !(rc::distanceSquared(s.nav.center(cell), p.position) < touch * touch))
        continue;
    }
    const float d = rc::distanceSquared(at, p.position);
    if (!best || d < bestDistance) {
      best = p.position;
      bestDistance = d;
    }
  }
  return best;
}

// The behaviour its memory, health and rounds call for (finding cover when a hurt bot is hit,
// the pickup to fetch into mind.goal).
Behaviour choose(MatchState& s, std::size_t i, rc::Vec2 at) {
  BotMind& mind = s.minds[i];
  const std::optional<rc::Vec2> pickup = neededPickup(s, i, at);
  auto fetch = [&]() {
    if (mind.goal != *pickup || mind.behaviour != Behaviour::fetch) {
      mind.goal = *pickup;
      mind.route.planned = -1;
    }
    return Behaviour::fetch;
  };
  if (mind.focus < 0) return pickup ? fetch() : Behaviour::patrol;
  const MemoryEntry& threat = mind.memory[static_cast<std::size_t>(mind.focus)];
  const float health = s.actors[i].health;
  if (isHurt(s, s.actors[i])) {
    const bool hiding = mind.behaviour == Behaviour::takeCover || mind.behaviour == Behaviour::flee;
    const bool hit = health < mind.health;
    const bool blown = hiding && inSight(mind, threat) && s.tick - mind.goalTick >= kCoverTicks;
    if (hit || blown) {
      const std::optional<CoverSpot> spot = findCover(s, i, threat.position);
      mind.goal = spot ? spot->position : at + (at - threat.position);
      mind.goalTick = s.tick;
      mind.route.planned = -1;
      return spot && spot->hidden ? Behaviour::takeCover : Behaviour::flee;
    }
    if (hiding && s.tick - mind.behaviourSince < kHideTicks) return mind.behaviour;
  }
  // Out of rounds, it cannot fight; short of them or hurt, it fetches while nothing is in sight.
  if (pickup && isOutOfRounds(s, s.actors[i])) return fetch();
  if (inSight(mind, threat)) return Behaviour::attack;
  if (pickup) return fetch();
  return threat.sense == Sense::seen ? Behaviour::chase : Behaviour::investigate;
}

// Whether it can throw a grenade at `target` now (see kThrowNear).
bool throwsAt(MatchState& s, std::size_t i, rc::Vec2 at, rc::Vec2 target) {
  const Actor& a = s.actors[i];
  const std::optional<std::size_t> grenade = s.weapons.grenade();
  const float distance = rc::length(target - at);
  // (Its hand is free in the weapons phase if the cooldown is at most 1: it counts down first.)
  if (!grenade || a.ammo[*grenade] <= 0 || a.cooldown > 1 || !(distance > kThrowNear) ||
      !(distance < kThrowFar) || (s.tick + static_cast<std::int64_t>(i) * 13) % kThrowEvery != 0)
    return false;
  // Not where a friend is (a team knows where its own are): within the blast and a metre more.
  const GrenadeSpec& spec = s.weapons.weapons[*grenade].grenade;
  const float unsafe = spec.blastRadius + 1.0f;
  for (std::size_t j = 0; j < s.actors.size(); ++j) {
    const Actor& other = s.actors[j];
    if (j != i && other.alive && other.team == a.team &&
        rc::distanceSquared(s.centers[j], target) < unsafe * unsafe)
      return false;
  }
  const float radius = spec.radius;
  const rc::Vec2 path = (kThrowNear / distance) * (target - at);
  return !s.world->castCircle(at, radius, path,
                              rc::QueryFilter::ignoring(a.body, {0xFFFFFFFFu, 0xFFFFFFFFu}));
}

// Whether no friend stands in the line of fire from `at` to `target` (within a body's width of
// it, and not beyond the target): a team knows where its own are.
bool clearOfFriends(const MatchState& s, std::size_t i, rc::Vec2 at, rc::Vec2 target) {
  const rc::Vec2 d = target - at;
  const float length2 = rc::lengthSquared(d);
  if (!(length2 > 0.0f)) return true;
  const float width = 2.0f * s.tuning.radius;
  for (std::size_t j = 0; j < s.actors.size(); ++j) {
    const Actor& other = s.actors[j];
    if (j == i || !other.alive || other.team != s.actors[i].team) continue;
    const rc::Vec2 p = s.centers[j] - at;
    const float t = rc::dot(p, d) / length2;
    if (t > 0.0f && t < 1.0f && rc::distanceSquared(p, t * d) < width * width) return false;
  }
  return true;
}

// A moving bot's way bent away from friends nearer than kPersonalSpace (centre to centre), the
// more the nearer, where it has room (a roomy cell): bots that go to the same sound would
// otherwise crowd, push and stall each other (and the contacts between them were what made a
// match's physics dearer).
rc::Vec2 keepApart(const MatchState& s, std::size_t i, rc::Vec2 at, rc::Vec2 move) {
  // Only with room to spare: in a corridor a bent way presses into the wall (giving way is what
  // clears corridors).
  const int cell = s.nav.cellAt(at);
  if (cell < 0 || (s.nav.flags[static_cast<std::size_t>(cell)] & NavGrid::kRoomy) == 0) return move;
  rc::Vec2 push{};
  for (std::size_t j = 0; j < s.actors.size(); ++j) {
    const Actor& other = s.actors[j];
    if (j == i || !other.alive || other.team != s.actors[i].team) continue;
    const rc::Vec2 d = at - s.centers[j];
    const float d2 = rc::lengthSquared(d);
    if (!(d2 < kPersonalSpace * kPersonalSpace) || !(d2 > 0.0f)) continue;
    const float distance = std::sqrt(d2);
    push += ((kPersonalSpace - distance) / (kPersonalSpace * distance)) * d;
  }
  if (push == rc::Vec2{}) return move;
  const rc::Vec2 bent = move + kApartWeight * push;
  return rc::lengthSquared(bent) > 1e-6f ? rc::normalize(bent) : move;
}

PlayerInput decide(MatchState& s, std::size_t i) {
  Actor& a = s.actors[i];
  BotMind& mind = s.minds[i];
  const rc::Vec2 at = s.centers[i];
  mind.focus = strongestMemory(mind, s.tick);
  const Behaviour next = choose(s, i, at);
  if (next != mind.behaviour) {
    if (next != Behaviour::takeCover && next != Behaviour::flee) mind.goalTick = -1;
    mind.behaviour = next;
    mind.behaviourSince = s.tick;
    mind.stuckTicks = 0;
  }
  const MemoryEntry* threat =
      mind.focus >= 0 ? &mind.memory[static_cast<std::size_t>(mind.focus)] : nullptr;
  rc::Vec2 move{};
  float aim = a.aim;
  std::uint8_t buttons = 0;
  std::uint8_t weapon = a.input.weapon;  // the one it held, until it fights
  switch (mind.behaviour) {
    case Behaviour::patrol: {
      const bool reached =
          mind.goalTick >= 0 && rc::distanceSquared(at, mind.goal) < kArrive * kArrive;
      // Stuck against an actor created before it, it gives way (the first keeps going); stuck
      // for longer, whatever blocks it, it goes elsewhere.
      const bool yields = mind.stuckTicks >= kStuckTicks && bumpedInto(s, i, at, i) != rc::Vec2{};
      if (mind.goalTick < 0 || reached || s.tick - mind.goalTick > kGoalTicks || yields ||
          mind.stuckTicks >= 2 * kStuckTicks) {
        const bool stuck = mind.stuckTicks >= kStuckTicks;
        mind.goal = pickGoal(s, at, stuck ? bumpedInto(s, i, at, s.actors.size()) : rc::Vec2{});
        mind.goalTick = s.tick;
        mind.route.planned = -1;
        mind.stuckTicks = 0;
      }
      move = steer(s, i, at, mind.goal);
      if (move != rc::Vec2{}) aim = turnToward(a.aim, angleOf(move));
      break;
    }
    case Behaviour::investigate:
    case Behaviour::chase: {
      const rc::Vec2 target = expectedPosition(*threat, s.tick, kLead);
      if (mind.behaviour == Behaviour::chase && mind.goalTick < 0 && throwsAt(s, i, at, target)) {
        // Thrown: step back the other way while it flies.
        buttons = kButtonThrow;
        // (Not into a hurt zone: it would wait there for the blast.)
        mind.goal = clearOfHurt(s.nav, at - (kThrowNear / rc::length(target - at)) * (target - at));
        mind.goalTick = s.tick;
        mind.route.planned = -1;
      }
      const bool steppingBack = mind.goalTick >= 0 && s.tick - mind.goalTick < 2 * kTicksPerSecond;
      // Where the enemy was, or, if that is in a hurt zone, the nearest ground clear of it: the
      // bot looks in from there.
      const rc::Vec2 there = clearOfHurt(s.nav, target);
      move = steer(s, i, at, steppingBack ? mind.goal : there);
      if (rc::distanceSquared(at, there) < kArrive * kArrive ||
          (move == rc::Vec2{} && !steppingBack))
        aim = a.aim + kScanPerTick;  // there, and nothing: look around
      else
        aim = turnToward(a.aim, angleOf(target - at));
      break;
    }
    case Behaviour::attack: {
      const rc::Vec2 target = expectedPosition(*threat, s.tick, kLookEvery);
      const rc::Vec2 d = target - at;
      const float distance = rc::length(d);
      const rc::Vec2 toward = distance > 0.0f ? (1.0f / distance) * d : rc::Vec2{1, 0};
      if ((s.tick + static_cast<std::int64_t>(i) * 17) % 90 == 0) mind.strafe = -mind.strafe;
      move = mind.strafe * rc::Vec2{-toward.y, toward.x};
      if (distance > kFar) move = toward;
      if (distance < kNear) move = -toward;
      // These steps ignore the grid: none from plain ground into a hurt zone's margin (a
      // sidestep turns the other way, else the bot stands); in the margin already (pushed there,
      // or a sidestep from a cell at its edge), the bot fights while it walks out to the nearest
      // clear ground (sidesteps from there took one 40 ticks into the arena's zone).
      if (const rc::Vec2 clear = clearOfHurt(s.nav, at); clear != at) {
        move = steer(s, i, at, clear);
      } else if (intoHurt(s, at, move)) {
        const bool strafing = distance <= kFar && distance >= kNear;
        if (strafing) mind.strafe = -mind.strafe;
        move = strafing && !intoHurt(s, at, -move) ? -move : rc::Vec2{};
      }
      const float error = kAimError + kAimErrorPerSpeed * rc::length(threat->velocity);
      const float exact = angleOf(d);
      aim = turnToward(a.aim, exact + s.rng.uniform(-error, error));
      weapon = chooseGun(s, a, distance);
      if (std::fabs(wrapAngle(exact - aim)) < kFireCone && clearOfFriends(s, i, at, target))
        buttons = kButtonFire;
      break;
    }
    case Behaviour::fetch: {
      move = steer(s, i, at, mind.goal);
      // Facing the enemy it remembers (it may show up), else the way it walks.
      if (threat != nullptr)
        aim = turnToward(a.aim, angleOf(threat->position - at));
      else if (move != rc::Vec2{})
        aim = turnToward(a.aim, angleOf(move));
      break;
    }
    case Behaviour::takeCover:
    case Behaviour::flee: {
      move = steer(s, i, at, mind.goal);
      const rc::Vec2 d = threat->position - at;
      aim = turnToward(a.aim, angleOf(d));
      weapon = chooseGun(s, a, rc::length(d));
      if (inSight(mind, *threat) && std::fabs(wrapAngle(angleOf(d) - aim)) < kFireCone &&
          clearOfFriends(s, i, at, threat->position))
        buttons = kButtonFire;
      break;
    }
  }
  mind.health = a.health;
  const bool barelyMoving = rc::lengthSquared(s.world->linearVelocity(a.body)) < 0.25f;
  mind.stuckTicks = move != rc::Vec2{} && barelyMoving ? mind.stuckTicks + 1 : 0;
  if (move != rc::Vec2{}) move = keepApart(s, i, at, move);
  return makeInput(move, aim, buttons, weapon);
}

// What the actor perceives this tick: the last tick's sounds, and a look when its turn comes.
void perceive(MatchState& s, std::size_t i) {
  forgetFaded(s.minds[i], s.tick);
  if (looksAt(s.tick, i)) look(s, i);
  listen(s, i);
}

}  // namespace

void decideBots(MatchState& s, std::span<const PlayerInput> inputs) {
  // Where everyone is as the phase begins (nothing moves until it is over).
  s.centers.resize(s.actors.size());
  for (std::size_t i = 0; i < s.actors.size(); ++i)
    s.centers[i] = s.world->worldCenter(s.actors[i].body);
  std::size_t player = 0;
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    Actor& a = s.actors[i];
    if (a.alive) {
      if (s.config.profile) {
        const auto start = std::chrono::steady_clock::now();
        perceive(s, i);
        s.profile.perception +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      } else {
        perceive(s, i);
      }
      a.input = decide(s, i);
    } else {
      a.input = PlayerInput{};
    }
    // A player's given input replaces the autopilot's choice, which is made all the same: the
    // match perceives and draws the same randomness whether the input came from the autopilot,
    // a script or a recording of either, so a recording replays exactly.
    if (a.kind == ActorKind::player && player++ < inputs.size()) a.input = inputs[player - 1];
  }
}

}  // namespace game
