// The rules (game/rules) on small levels built in code, each against its closed form or a case
// worked by hand: pickups (restored up to the maximum, not taken by who cannot use them, back
// after their delay, the nearest taker), exits (one score per entry, the actor sent back), the
// score per actor and per team, impacts (D = k mu (v - v0) above the threshold, nothing below,
// who is credited), and crates bouncing by their material's restitution.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "game/level/level_error.h"
#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/rules/damage.h"
#include "game/rules/impacts.h"
#include "game/rules/pickups.h"
#include "game/weapons/weapons.h"
#include "level_test_support.h"
#include "match_test_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace rules_test {

using game::Level;
using game::LevelMaterial;
using game::Match;
using game::MatchConfig;
using game::PlayerInput;
using rc::Vec2;

using match_test_support::addPickup;
using match_test_support::bundled;
using match_test_support::emptyLevel;

void addSpawn(Level& level, game::SpawnKind kind, Vec2 at) {
  game::LevelSpawn s;
  s.kind = kind;
  s.position = at;
  level.spawns.push_back(s);
}

void addWall(Level& level, Vec2 at, Vec2 half, LevelMaterial m = {}) {
  game::LevelObject o;
  o.kind = game::LevelObjectKind::wall;
  o.position = at;
  o.material = m;
  o.shapes.push_back(rc::makeBox(half.x, half.y));
  level.objects.push_back(o);
}

// A 1 x 1 m crate (1 kg at density 1), undamped unless asked.
std::size_t addCrate(Level& level, Vec2 at, LevelMaterial m = {}, float damping = 0.0f) {
  game::LevelObject o;
  o.kind = game::LevelObjectKind::prop;
  o.bodyType = rc::BodyType::dynamicBody;
  o.position = at;
  o.material = m;
  o.material.hard = false;
  o.linearDamping = o.angularDamping = damping;
  o.shapes.push_back(rc::makeBox(0.5f, 0.5f));
  level.objects.push_back(o);
  return level.objects.size() - 1;
}

// Bots decide for themselves (they walk and shoot): tests that want actors to stand still use
// players, whose inputs they give.
MatchConfig config(int bots, const game::WeaponTable& table = bundled(), int players = 1) {
  MatchConfig c;
  c.bots = bots;
  c.players = players;
  c.weapons = table;
  return c;
}

// Inputs that keep every player still (no autopilot).
std::vector<PlayerInput> still(std::size_t players = 1) {
  return std::vector<PlayerInput>(players);
}

// A health pickup of 25 (respawn 2 s) under the player: not taken at full health; at 90 it is
// taken and restores up to the maximum (100, not 115); gone exactly 120 ticks, then back; at 50
// the next one gives the whole 25.
TEST(Pickups, HealthUpToMaxNotAtFullBackAfterItsDelay) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addPickup(level, "health", 25, 2, {0.3f, 0});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  ASSERT_EQ(s.pickups.size(), 1u);
  const game::PickupState& p = s.pickups[0];
  EXPECT_EQ(p.item, game::PickupItem::health);
  EXPECT_EQ(p.respawnTicks, 120);
  for (int t = 0; t < 30; ++t)
    m.tick(still());
  EXPECT_TRUE(p.available);
  EXPECT_EQ(p.timesTaken, 0);
  s.actors[0].health = 90;
  m.tick(still());
  EXPECT_EQ(s.actors[0].health, 100.0f);
  EXPECT_FALSE(p.available);
  EXPECT_EQ(p.takenBy, 0);
  EXPECT_EQ(p.timesTaken, 1);
  // Standing on it at 50 health, the player takes it again the tick it is back.
  int gone = 1;  // the state the taking tick ended in
  while (p.timesTaken == 1 && gone < 1000) {
    s.actors[0].health = 50;
    m.tick(still());
    if (p.timesTaken == 1) {
      EXPECT_FALSE(p.available);
      EXPECT_EQ(s.actors[0].health, 50.0f);
      ++gone;
    }
  }
  EXPECT_EQ(gone, 120);
  EXPECT_EQ(p.timesTaken, 2);
  EXPECT_EQ(s.actors[0].health, 75.0f);
  EXPECT_FALSE(p.available);
}

// A pickup is touched when the discs' centres are at most the two radii apart (0.5 + 0.35): just
// inside it is taken, just outside not; a dead actor takes nothing; with respawn 0 it never
// comes back.
TEST(Pickups, ReachDeathAndNoRespawn) {
  for (const float gap : {-0.01f, 0.01f}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {0, 0});
    addPickup(level, "health", 10, 0, {0.85f + gap, 0});
    Match m(level, config(0));
    game::MatchState& s = m.state();
    s.actors[0].health = 50;
    m.tick(still());
    EXPECT_EQ(s.pickups[0].available, gap > 0) << gap;
    EXPECT_EQ(s.actors[0].health, gap > 0 ? 50.0f : 60.0f) << gap;
    for (int t = 0; t < 600; ++t)
      m.tick(still());
    EXPECT_EQ(s.pickups[0].available, gap > 0) << gap;  // never back
    EXPECT_EQ(s.pickups[0].respawnTick, -1);
  }
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addPickup(level, "health", 10, 0, {0, 0});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  game::killActor(s, 0, std::nullopt);
  m.tick(still());
  EXPECT_TRUE(s.pickups[0].available);
}

// Ammo in whole rounds (30.7 gives 30), up to what an actor spawns with: the rifle's 90 from 80
// is 10, from 50 is 30, at 90 not taken. The `weapon` property chooses the weapon (the
// shotgun's rounds, not the rifle's); a name not in the table is an error naming the pickup.
TEST(Pickups, AmmoCappedAndForTheNamedWeapon) {
  const game::WeaponTable& t = bundled();
  for (const int before : {80, 50, 90}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {0, 0});
    addPickup(level, "ammo", 30.7f, 10, {0, 0});
    Match m(level, config(0));
    game::MatchState& s = m.state();
    EXPECT_EQ(s.pickups[0].weapon, 0u);  // the table's first: the rifle
    s.actors[0].ammo[0] = before;
    m.tick(still());
    EXPECT_EQ(s.actors[0].ammo[0], std::min(before + 30, t.weapons[0].ammo)) << before;
    EXPECT_EQ(s.pickups[0].available, before == t.weapons[0].ammo) << before;
  }
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addPickup(level, "ammo", 4, 10, {0, 0}, "shotgun");
  Match m(level, config(0));
  game::MatchState& s = m.state();
  EXPECT_EQ(s.pickups[0].weapon, 1u);
  s.actors[0].ammo[1] = 2;
  m.tick(still());
  EXPECT_EQ(s.actors[0].ammo[1], 6);
  EXPECT_EQ(s.actors[0].ammo[0], t.weapons[0].ammo);

  Level bad = emptyLevel();
  addSpawn(bad, game::SpawnKind::player, {0, 0});
  addPickup(bad, "ammo", 4, 10, {0, 0}, "laser");
  try {
    Match broken(bad, config(0));
    ADD_FAILURE() << "a pickup for a weapon not in the table was accepted";
  } catch (const game::LevelError& e) {
    EXPECT_EQ(std::string(e.what()),
              "test: pickup 1: property 'weapon': no weapon 'laser' in the weapon table " +
                  t.source + " ('rifle', 'shotgun', 'grenade')");
  }
}

// Two actors touching a pickup: the nearer who can use it takes it; one at full health, nearer
// still, does not stand in the way. An unknown item is never taken.
TEST(Pickups, NearestWhoCanUseIt) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addSpawn(level, game::SpawnKind::player, {0.5f, 0});
  addSpawn(level, game::SpawnKind::player, {-0.6f, 0.0f});
  addPickup(level, "health", 30, 5, {0.1f, 0.5f});
  addPickup(level, "armour", 30, 5, {0.1f, 0.5f});
  Match m(level, config(0, bundled(), 3));
  game::MatchState& s = m.state();
  // Centres from the pickup: 0.51 (player 1), 0.64 (player 2), 0.86 (player 3: out of reach,
  // 0.85).
  s.actors[1].health = 40;
  s.actors[2].health = 40;
  const std::vector<PlayerInput> none(3);
  m.tick(none);
  EXPECT_EQ(s.pickups[0].takenBy, 1);
  EXPECT_EQ(s.actors[1].health, 70.0f);
  EXPECT_EQ(s.actors[0].health, 100.0f);
  EXPECT_EQ(s.pickups[1].item, game::PickupItem::unknown);
  EXPECT_TRUE(s.pickups[1].available);
}

// An exit zone made of two overlapping boxes: a player walking east into it scores one exit
// (not two: it enters both boxes in the same step), exitScore points for it and its team, and
// is back at its spawn at rest with the health it had; walking in again scores again.
TEST(Exit, ScoresOncePerEntryAndSendsTheActorBack) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-5, 0});
  game::LevelObject zone;
  zone.kind = game::LevelObjectKind::trigger;
  zone.position = {0, 0};
  zone.shapes.push_back(rc::makeBox(1, 1));
  zone.shapes.push_back(rc::makeBox(1, 1, {0.5f, 0}));
  level.objects.push_back(zone);
  level.triggers.push_back({level.objects.size() - 1, "exit"});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  s.actors[0].health = 60;
  const std::vector<PlayerInput> east{game::makeInput({1, 0}, 0, 0, 0)};
  int ticks = 0;
  while (s.actors[0].exits == 0 && ticks < 600) {
    m.tick(east);
    ++ticks;
  }
  ASSERT_EQ(s.actors[0].exits, 1);
  EXPECT_EQ(s.actors[0].score, s.rules.exitScore);
  ASSERT_EQ(s.teams.size(), 1u);
  EXPECT_EQ(s.teams[0].exits, 1);
  EXPECT_EQ(s.teams[0].score, s.rules.exitScore);
  EXPECT_EQ(s.world->worldCenter(s.actors[0].body), (Vec2{-5, 0}));
  EXPECT_EQ(s.world->linearVelocity(s.actors[0].body), (Vec2{0, 0}));
  EXPECT_EQ(s.actors[0].health, 60.0f);
  EXPECT_TRUE(s.actors[0].alive);
  EXPECT_EQ(s.actors[0].deaths, 0);
  // The same walk again: the edge reaches the zone (x = -1) after 3.65 m, like the first time.
  const int first = ticks;
  ticks = 0;
  while (s.actors[0].exits == 1 && ticks < 600) {
    m.tick(east);
    ++ticks;
  }
  EXPECT_EQ(s.actors[0].exits, 2);
  EXPECT_NEAR(ticks, first, 1);
}

// Score: an enemy's kill scores for the killer and its team; a death by its own hand, a kill
// zone (no attacker) or a team-mate is the victim's suicide and scores for no one. A team's
// numbers are its actors' sums.
TEST(Score, KillsDeathsSuicidesPerActorAndTeam) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-10, 0});
  addSpawn(level, game::SpawnKind::bot, {10, 0});
  addSpawn(level, game::SpawnKind::bot, {10, 5});
  Match m(level, config(2));
  game::MatchState& s = m.state();
  ASSERT_EQ(s.teams.size(), 2u);
  EXPECT_EQ(s.teams[0].team, 0);
  EXPECT_EQ(s.teams[1].team, 1);
  game::killActor(s, 1, 0);             // the player kills bot 1
  game::killActor(s, 0, 0);             // the player kills itself
  game::killActor(s, 2, 1);             // bot 1 kills bot 2, its team-mate
  game::killActor(s, 1, std::nullopt);  // dead already: nothing
  EXPECT_EQ(s.actors[0].kills, 1);
  EXPECT_EQ(s.actors[0].score, s.rules.killScore);
  EXPECT_EQ(s.actors[0].deaths, 1);
  EXPECT_EQ(s.actors[0].suicides, 1);
  EXPECT_EQ(s.actors[1].kills, 0);
  EXPECT_EQ(s.actors[1].score, 0);
  EXPECT_EQ(s.actors[1].deaths, 1);
  EXPECT_EQ(s.actors[1].suicides, 0);
  EXPECT_EQ(s.actors[2].deaths, 1);
  EXPECT_EQ(s.actors[2].suicides, 1);
  for (const game::TeamScore& t : s.teams) {
    game::TeamScore sum;
    for (const game::Actor& a : s.actors) {
      if (a.team != t.team) continue;
      sum.kills += a.kills;
      sum.deaths += a.deaths;
      sum.suicides += a.suicides;
      sum.exits += a.exits;
      sum.score += a.score;
    }
    EXPECT_EQ(t.kills, sum.kills);
    EXPECT_EQ(t.deaths, sum.deaths);
    EXPECT_EQ(t.suicides, sum.suicides);
    EXPECT_EQ(t.exits, sum.exits);
    EXPECT_EQ(t.score, sum.score);
  }
  EXPECT_EQ(s.teams[0].score, 1);
  EXPECT_EQ(s.teams[1].deaths, 2);
  EXPECT_EQ(s.teams[1].suicides, 1);
}

// The closed form: D = k mu (v - v0), mu the reduced mass, 0 at or below v0; a static body
// leaves the dynamic side's mass.
TEST(Impacts, ClosedForm) {
  const game::RuleTuning rules;
  EXPECT_EQ(game::reducedMass(1, 3), 0.75f);
  EXPECT_EQ(game::reducedMass(0, 3), 3.0f);
  EXPECT_EQ(game::reducedMass(2, 0), 2.0f);
  EXPECT_EQ(game::impactDamage(rules, 1, rules.impactSpeed), 0.0f);
  EXPECT_EQ(game::impactDamage(rules, 1, rules.impactSpeed - 1), 0.0f);
  EXPECT_FLOAT_EQ(game::impactDamage(rules, 0.5f, rules.impactSpeed + 4),
                  rules.impactDamage * 0.5f * 4);
}

// A 1 kg crate (40 health) sent at v into a standing actor (3.08 kg), top-down, undamped: below
// the threshold nothing happens; above it both take k mu (v - v0), the crash is recorded once.
TEST(Impacts, CrateIntoActorDealsTheFormula) {
  const float v0 = game::RuleTuning{}.impactSpeed;
  for (const float v : {v0 - 2, v0 - 0.1f, v0 + 0.5f, v0 + 4, v0 + 10}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {3, 0});
    LevelMaterial crate;
    crate.health = 40;
    const std::size_t c = addCrate(level, {-3, 0}, crate);
    Match m(level, config(0));
    game::MatchState& s = m.state();
    const rc::BodyId body = s.built.bodies[c];
    s.world->setLinearVelocity(body, {v, 0});
    const float mu = game::reducedMass(s.world->mass(body), s.world->mass(s.actors[0].body));
    ASSERT_NEAR(mu, 1.0f * 3.0788f / 4.0788f, 1e-3f);
    const float expected = s.rules.impactDamage * mu * (v - s.rules.impactSpeed);
    int crashes = 0;
    for (int t = 0; t < 90; ++t) {
      m.tick(still());
      crashes += static_cast<int>(s.crashes.size());
      if (!s.crashes.empty()) {
        EXPECT_NEAR(s.crashes[0].speed, v, 1e-3f);
        EXPECT_TRUE((s.crashes[0].actor == std::array<std::int32_t, 2>{0, -1}) ||
                    (s.crashes[0].actor == std::array<std::int32_t, 2>{-1, 0}));
        EXPECT_EQ(s.crashes[0].credited, -1);
      }
    }
    if (v <= s.rules.impactSpeed) {
      EXPECT_EQ(crashes, 0) << v;
      EXPECT_EQ(s.actors[0].health, 100.0f) << v;
      EXPECT_EQ(s.props[0].health, 40.0f) << v;
      continue;
    }
    EXPECT_EQ(crashes, 1) << v;
    EXPECT_NEAR(s.actors[0].health, 100.0f - expected, 1e-3f) << v;
    EXPECT_NEAR(s.props[0].health, 40.0f - expected, 1e-3f) << v;
  }
}

// Two actors meeting at nearly 20 m/s hurt neither; an actor sent at 12 m/s into a wall takes
// k m (12 - v0) (mu is its own mass against a static body).
TEST(Impacts, ActorsNeverHurtEachOtherWallsDo) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-2, 0});
  addSpawn(level, game::SpawnKind::player, {2, 0});
  addWall(level, {0, 10.5f}, {5, 0.5f});
  Match m(level, config(0, bundled(), 2));
  game::MatchState& s = m.state();
  s.world->setLinearVelocity(s.actors[0].body, {10, 0});
  s.world->setLinearVelocity(s.actors[1].body, {-10, 0});
  const std::vector<PlayerInput> none(2);
  for (int t = 0; t < 30; ++t)
    m.tick(none);
  EXPECT_EQ(s.actors[0].health, 100.0f);
  EXPECT_EQ(s.actors[1].health, 100.0f);
  // The player, north into the wall at y = 10 from 0.1 m away: the contact begins in the first
  // step, at the 12 m/s less the tick's braking (the player's input asks it to stand).
  s.world->setTransform(s.actors[0].body, {0, 9.55f}, 0);
  s.world->setLinearVelocity(s.actors[0].body, {0, 12});
  const float mass = s.world->mass(s.actors[0].body);
  for (int t = 0; t < 60; ++t) {
    s.world->setLinearVelocity(s.actors[1].body, {});
    m.tick(none);
    if (!s.crashes.empty()) break;
  }
  ASSERT_EQ(s.crashes.size(), 1u);
  EXPECT_NEAR(s.crashes[0].speed, 12.0f - s.tuning.acceleration / 60.0f, 1e-3f);
  EXPECT_NEAR(s.actors[0].health,
              100.0f - s.rules.impactDamage * mass * (s.crashes[0].speed - s.rules.impactSpeed),
              1e-3f);
}

// Credit: a blast (its damage 0, its push 15 N s, radius 1.5 m) throws a crate at a bot with 5
// health left, out of the blast's reach: the crate's impact kills it and the thrower scores;
// with no blame window it is the bot's suicide. A grenade thrown straight at a bot with 1
// health kills it, credited to the thrower.
TEST(Impacts, CreditGoesToTheBlastsThrower) {
  for (const std::int64_t window : {std::int64_t{120}, std::int64_t{-1}}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-20, 20});
    addSpawn(level, game::SpawnKind::bot, {4, 0});
    const std::size_t c = addCrate(level, {0, 0});
    Match m(level, config(1));
    game::MatchState& s = m.state();
    s.rules.blameTicks = window;
    s.actors[1].health = 5;
    game::GrenadeSpec g = bundled().weapons[2].grenade;
    g.blastDamage = 0;
    g.blastImpulse = 15;
    g.blastRadius = 1.5f;
    game::explode(s, {-0.5f, 0}, g, 0);
    EXPECT_NEAR(s.world->linearVelocity(s.built.bodies[c]).x, 15.0f * (1 - 0.5f / 1.5f), 1e-4f);
    EXPECT_EQ(s.props[0].blamed, 0);
    const std::vector<PlayerInput> none(2);
    for (int t = 0; t < 60 && s.actors[1].alive; ++t) {
      s.world->setLinearVelocity(s.actors[1].body, {});
      m.tick(none);
    }
    EXPECT_FALSE(s.actors[1].alive) << window;
    EXPECT_EQ(s.actors[0].kills, window > 0 ? 1 : 0);
    EXPECT_EQ(s.actors[1].suicides, window > 0 ? 0 : 1);
  }
  game::WeaponTable fast = bundled();
  fast.weapons[2].grenade.muzzleVelocity = 30;
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addSpawn(level, game::SpawnKind::bot, {4, 0});
  Match m(level, config(1, fast));
  game::MatchState& s = m.state();
  s.actors[0].aim = 0;
  s.actors[1].health = 1;
  game::throwGrenade(s, 0, 2);
  const std::vector<PlayerInput> none(2);
  for (int t = 0; t < 30 && s.actors[1].alive; ++t) {
    s.world->setLinearVelocity(s.actors[1].body, {});
    m.tick(none);
  }
  EXPECT_FALSE(s.actors[1].alive);
  EXPECT_EQ(s.actors[0].kills, 1);
  EXPECT_TRUE(s.grenades[0].live);  // the impact, not the blast
}

// A crate of restitution e, undamped, sent top-down at 6 m/s head on into a wall (restitution 0:
// the pair's is the larger, the crate's), turned by `angle`; the speed it comes back at, and
// its spin.
struct Rebound {
  float speed = 0, spin = 0;
};
Rebound headOn(float e, float angle) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-20, 20});
  addWall(level, {5.5f, 0}, {0.5f, 5});
  LevelMaterial m;
  m.restitution = e;
  const std::size_t c = addCrate(level, {0, 0}, m);
  level.objects[c].angle = angle;
  Match match(level, config(0));
  game::MatchState& s = match.state();
  const rc::BodyId body = s.built.bodies[c];
  s.world->setLinearVelocity(body, {6, 0});
  for (int t = 0; t < 120; ++t) {
    match.tick(still());
    if (s.world->linearVelocity(body).x < 0)
      return {-s.world->linearVelocity(body).x, s.world->angularVelocity(body)};
  }
  return {};
}

// Crates bounce by their level material. Met corner first (turned 45 degrees: one contact point,
// in line with the centre) a crate comes back at e v, and dropped so under the level's gravity
// (0, -10) from h it rises to e^2 h. Met flat (two contact points) it comes back at e v too,
// without turning: the engine bounces a manifold's two points together (one after the other,
// the first point's bounce turned the box and the second got less: 0.88 e v and 0.72 rad/s for
// a unit box at 6 m/s, e = 0.5; Box2D 2.4.1's block solver gives 3 m/s and 0). The bundled
// arena's bouncy barrel (restitution 0.3) carries its material into the world.
TEST(Bounce, CratesByTheirRestitution) {
  constexpr float kQuarter = 0.78539816f;
  for (const float e : {0.3f, 0.5f, 0.8f}) {
    const Rebound corner = headOn(e, kQuarter);
    EXPECT_NEAR(corner.speed, e * 6, 0.02f * e * 6) << e;
    EXPECT_NEAR(corner.spin, 0.0f, 1e-3f) << e;
    const Rebound flat = headOn(e, 0);
    EXPECT_NEAR(flat.speed, e * 6, 0.01f * e * 6) << e;
    EXPECT_NEAR(flat.spin, 0.0f, 1e-3f) << e;
    for (const float h : {1.0f, 3.0f}) {
      Level level = emptyLevel();
      level.settings.gravity = {0, -10};
      addSpawn(level, game::SpawnKind::player, {-20, 0.35f});
      addWall(level, {0, -0.5f}, {25, 0.5f});
      LevelMaterial m;
      m.restitution = e;
      const float half = std::sqrt(0.5f);  // the centre's height above the lowest corner
      const std::size_t c = addCrate(level, {0, half + h}, m);
      level.objects[c].angle = kQuarter;
      Match match(level, config(0));
      game::MatchState& s = match.state();
      const rc::BodyId body = s.built.bodies[c];
      bool bounced = false;
      float apex = 0;
      for (int t = 0; t < 600; ++t) {
        match.tick(still());
        const float vy = s.world->linearVelocity(body).y;
        if (!bounced && vy > 0) bounced = true;
        if (bounced) {
          apex = std::max(apex, s.world->position(body).y - half);
          if (vy < 0) break;
        }
      }
      ASSERT_TRUE(bounced) << e << " " << h;
      // 3%, or what a substep's gravity (10 m/s^2 for 1/240 s) on the rebound speed e v makes
      // of the apex, e v / 240, where that is more (slow bounces).
      const float v = std::sqrt(20.0f * h);
      EXPECT_NEAR(apex, e * e * h, std::max(0.03f * e * e * h, e * v / 240.0f)) << e << " " << h;
    }
  }
  Match arena(game::loadLevel(level_test::levelPath("arena.tmj")), config(0));
  const game::MatchState& s = arena.state();
  int bouncy = 0;
  for (std::size_t i = 0; i < s.level.objects.size(); ++i) {
    const game::LevelObject& o = s.level.objects[i];
    if (o.kind != game::LevelObjectKind::prop) continue;
    for (const rc::ShapeId shape : s.world->shapesOf(s.built.bodies[i]))
      EXPECT_EQ(s.world->restitution(shape), o.material.restitution);
    bouncy += o.material.restitution == 0.3f;
  }
  EXPECT_EQ(bouncy, 1);
}

// The rules' state enters the hash: a pickup taken, a score, a prop's blame each change it.
TEST(Rules, StateEntersTheHash) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  addPickup(level, "health", 10, 5, {10, 0});
  addCrate(level, {5, 5});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  const std::uint64_t h = m.hash();
  s.pickups[0].available = false;
  EXPECT_NE(m.hash(), h);
  s.pickups[0].available = true;
  EXPECT_EQ(m.hash(), h);
  s.teams[0].exits = 1;
  EXPECT_NE(m.hash(), h);
  s.teams[0].exits = 0;
  s.actors[0].suicides = 1;
  EXPECT_NE(m.hash(), h);
  s.actors[0].suicides = 0;
  s.props[0].blamedTick = 3;
  EXPECT_NE(m.hash(), h);
  s.props[0].blamedTick = -1;
  EXPECT_EQ(m.hash(), h);
}

}  // namespace rules_test
