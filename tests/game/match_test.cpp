// The match (game/match, bots, weapons, rules) on small levels built in code: inputs recorded
// exactly, sight cones to the edge, hitscan damage against its closed form, death and respawn
// at the spawn farthest from enemies, trigger zones, and the same seed giving the same hashes.
// Bots' perception and behaviours have their own tests (bots_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "game/bots/sight.h"
#include "game/match/actors.h"
#include "game/match/input.h"
#include "game/match/match.h"
#include "game/rules/damage.h"
#include "game/weapons/weapons.h"
#include "match_test_support.h"
#include "physics/random.h"
#include "physics/trig.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace match_test {

using game::Level;
using game::Match;
using game::MatchConfig;
using game::PlayerInput;
using rc::Vec2;

using match_test_support::config;

// An empty 40 x 40 m room with a player spawn at `player` and bot spawns at `bots`, and, if
// `wall` is true, a 1 x 6 m wall centred at the origin.
Level room(Vec2 player, std::vector<Vec2> bots, bool wall = false) {
  if (!wall) return match_test_support::room(player, bots);
  return match_test_support::room(player, bots, {{{0, 0}, {0.5f, 3}}});
}

// Every input the encoding can hold survives bytes and back; continuous controls land on the
// nearest step (1/127 of full speed, 1/65536 of a turn) and are read back as that step.
TEST(Input, RecordsExactly) {
  rc::Random rng(5);
  for (int i = 0; i < 10000; ++i) {
    PlayerInput in;
    in.moveX = static_cast<std::int8_t>(static_cast<int>(rng.below(255)) - 127);
    in.moveY = static_cast<std::int8_t>(static_cast<int>(rng.below(255)) - 127);
    in.aim = static_cast<std::uint16_t>(rng.below(65536));
    in.buttons = static_cast<std::uint8_t>(rng.below(256));
    in.weapon = static_cast<std::uint8_t>(rng.below(256));
    ASSERT_EQ(game::fromBytes(game::toBytes(in)), in);
    // Reading and writing again changes nothing: the game sees only what a recording holds.
    ASSERT_EQ(game::makeInput(game::moveOf(in), game::aimOf(in), in.buttons, in.weapon).aim,
              in.aim);
  }
  const PlayerInput half = game::makeInput({0.5f, 0}, rc::kPi / 2, game::kButtonFire, 0);
  EXPECT_EQ(half.moveX, 64);  // 0.5 * 127 = 63.5, rounded away from zero
  EXPECT_EQ(half.moveY, 0);
  EXPECT_EQ(half.aim, 16384);
  EXPECT_EQ(game::makeInput({}, -rc::kPi / 2, 0, 0).aim, 49152);  // negative angles wrap
  EXPECT_LE(rc::length(game::moveOf(game::makeInput({1, 1}, 0, 0, 0))), 1.0f);
  EXPECT_EQ(game::makeInput({std::nanf(""), 0}, std::nanf(""), 0, 0), PlayerInput{});
}

// A bot facing +x (a 120 degree cone, 25 m) sees a player just inside the cone's edge and not
// one just outside it, nor one beyond its range, nor one behind a wall.
TEST(Sight, ConeEdgesRangeAndWalls) {
  for (const float half : {0.3f, 1.0471976f}) {
    const float inside = half - 0.01f, outside = half + 0.01f;
    for (const float angle : {inside, outside, -inside, -outside}) {
      const Vec2 at{10 * std::cos(angle), 10 * std::sin(angle)};
      Match m(room(at, {{0, 0}}), config(1));
      game::MatchState& s = m.state();
      s.actors[1].aim = 0;  // the bot, facing +x
      game::SightTuning tuning;
      tuning.halfAngle = half;
      EXPECT_EQ(game::sees(s, 1, 0, tuning), std::fabs(angle) < half) << half << " " << angle;
    }
  }
  Match far(room({-10, 0}, {{14, 0}}), config(1));
  far.state().actors[1].aim = rc::kPi;
  EXPECT_TRUE(game::sees(far.state(), 1, 0));  // 24 m
  game::SightTuning shortSight;
  shortSight.range = 20;
  EXPECT_FALSE(game::sees(far.state(), 1, 0, shortSight));
  Match walled(room({-5, 0}, {{5, 0}}, true), config(1));
  walled.state().actors[1].aim = rc::kPi;
  EXPECT_FALSE(game::sees(walled.state(), 1, 0));
  Match open(room({-5, 0}, {{5, 0}}, false), config(1));
  open.state().actors[1].aim = rc::kPi;
  EXPECT_TRUE(game::sees(open.state(), 1, 0));
}

// A rifle shot loses damage linearly from falloffStart to falloffEnd; the target's health drops
// by exactly damageAt(distance).
TEST(Weapons, HitscanDamageFollowsTheFalloff) {
  Match probe(room({-1, 0}, {}), config(0));
  const game::HitscanSpec rifle = probe.state().weapons.weapons[0].hitscan;
  EXPECT_EQ(game::damageAt(rifle, 5), rifle.damage);
  EXPECT_EQ(game::damageAt(rifle, rifle.falloffEnd + 1), rifle.minDamage * rifle.damage);
  const float middle = (rifle.falloffStart + rifle.falloffEnd) / 2;
  EXPECT_FLOAT_EQ(game::damageAt(rifle, middle), rifle.damage * (1 - 0.5f * (1 - rifle.minDamage)));
  for (const float distance : {5.0f, 30.0f}) {
    Match m(room({-distance / 2, 0}, {{distance / 2, 0}}), config(1));
    game::MatchState& s = m.state();
    s.actors[0].aim = 0;  // the player at -x aims at the bot at +x
    game::firePellets(s, 0, 0);
    ASSERT_EQ(s.shots.size(), 1u);
    ASSERT_EQ(s.shots[0].actorsHit, std::vector<std::size_t>{1});
    // The ray meets the bot's disc at its near side.
    const float hitDistance = distance - s.tuning.radius;
    EXPECT_NEAR(s.actors[1].health, s.tuning.health - game::damageAt(rifle, hitDistance), 1e-3f);
    EXPECT_NEAR(s.shots[0].path[1].x, distance / 2 - s.tuning.radius, 1e-3f);
  }
}

// Four hits kill (25 damage, 100 health): the body leaves the world, the shooter scores, and
// three seconds later the victim is back, at full health, at the spawn farthest from its enemy.
TEST(Rules, DeathAndRespawnAtTheFarthestSpawn) {
  Match m(room({-15, 0}, {{-10, 0}, {15, 15}, {12, -3}}), config(1));
  game::MatchState& s = m.state();
  for (int k = 0; k < 4; ++k)
    game::damageActor(s, 1, 25, 0);
  EXPECT_FALSE(s.actors[1].alive);
  EXPECT_EQ(s.actors[1].deaths, 1);
  EXPECT_EQ(s.actors[0].kills, 1);
  EXPECT_FALSE(s.world->isEnabled(s.actors[1].body));
  EXPECT_TRUE(
      s.world->castRay({-15, 0}, {30, 0}, rc::QueryFilter::ignoring(s.actors[0].body))->body !=
      s.actors[1].body);
  const std::vector<PlayerInput> still{PlayerInput{}};
  int ticks = 0;
  while (!s.actors[1].alive && ticks < 1000) {
    m.tick(still);
    ++ticks;
  }
  EXPECT_EQ(ticks, 3 * game::kTicksPerSecond);
  EXPECT_EQ(s.actors[1].health, s.tuning.health);
  // Spawns at 5, 33.5 and 27.2 m from the player at (-15, 0): the second.
  const Vec2 back = s.world->worldCenter(s.actors[1].body);
  EXPECT_NEAR(back.x, 15, 0.1f);
  EXPECT_NEAR(back.y, 15, 0.1f);
}

// room() with the player at (-5, 0), no bots, and one trigger zone `shape` about the origin
// (trigger.object is set here).
Level roomWithZone(const rc::Shape& shape, game::LevelTrigger trigger) {
  Level level = room({-5, 0}, {});
  match_test_support::addTrigger(level, {0, 0}, shape, trigger);
  return level;
}

// A kill trigger zone kills whoever walks in.
TEST(Rules, KillTrigger) {
  Match m(roomWithZone(rc::makeBox(1, 1), {0, "kill"}), config(0));
  const std::vector<PlayerInput> east{game::makeInput({1, 0}, 0, 0, 0)};
  int t = 0;
  while (m.state().actors[0].alive && t < 300) {
    m.tick(east);
    ++t;
  }
  EXPECT_FALSE(m.state().actors[0].alive);
  EXPECT_EQ(m.state().actors[0].deaths, 1);
  // The player's edge reaches the pit's edge (x = -1) after 3.65 m: 0.73 s at 5 m/s, plus the
  // 0.125 s it takes to reach full speed, minus the half of it it covers while doing so.
  EXPECT_NEAR(static_cast<float>(t) / game::kTicksPerSecond, 3.65f / 5.0f + 0.0625f, 0.05f);
}

// A hurt zone takes its damagePerSecond off whoever stands in it, a tick's worth a tick, nothing
// once they step out, and dying in it is a suicide.
TEST(Rules, HurtTriggerTakesItsDamagePerSecondWhileInside) {
  Match m(roomWithZone(rc::makeBox(2, 2), {0, "hurt", 24.0f}), config(0));
  const game::Actor& player = m.state().actors[0];
  const std::vector<PlayerInput> east{game::makeInput({1, 0}, 0, 0, 0)};
  const std::vector<PlayerInput> west{game::makeInput({-1, 0}, 0, 0, 0)};
  const std::vector<PlayerInput> still{game::makeInput({}, 0, 0, 0)};
  const float full = player.health;
  // Walk in until the centre is in the zone's middle, then stand.
  int t = 0;
  while (m.state().world->position(player.body).x < 0.0f && t < 300) {
    m.tick(east);
    ++t;
  }
  for (int k = 0; k < 30; ++k)
    m.tick(still);  // coming to rest, still inside
  ASSERT_LT(player.health, full);
  const float before = player.health;
  for (int k = 0; k < game::kTicksPerSecond; ++k)
    m.tick(still);
  EXPECT_NEAR(before - player.health, 24.0f, 1e-3f);  // one second: 60 ticks of 0.4
  // Out (the player's 0.5 m radius clear of the zone's edge at x = -2): health stays.
  while (m.state().world->position(player.body).x > -3.0f && t < 1000) {
    m.tick(west);
    ++t;
  }
  for (int k = 0; k < 30; ++k)
    m.tick(still);
  const float outside = player.health;
  for (int k = 0; k < game::kTicksPerSecond; ++k)
    m.tick(still);
  EXPECT_EQ(player.health, outside);
  // Back in and staying: dead after outside / 24 seconds more, no one credited.
  int ticks = 0;
  while (player.alive && ticks < 20 * game::kTicksPerSecond) {
    m.tick(m.state().world->position(player.body).x < 0.0f ? east : still);
    ++ticks;
  }
  EXPECT_FALSE(player.alive);
  EXPECT_EQ(player.deaths, 1);
  EXPECT_EQ(player.suicides, 1);
  EXPECT_EQ(player.kills, 0);
  EXPECT_GT(static_cast<float>(ticks) / game::kTicksPerSecond, outside / 24.0f);
  EXPECT_LT(static_cast<float>(ticks) / game::kTicksPerSecond, outside / 24.0f + 1.0f);
}

// An actor's team is its spawn's: a bot spawned on the player's team never fights it, one on
// its own team (the default for bots) does; without a team, players are 0 and bots 1.
TEST(Match, SpawnTeamsDecideWhoIsAnEnemy) {
  // Whether the player, standing 8 m from the bot in plain view for 5 s, was ever hurt.
  auto playerHurt = [](int botTeam, int& team) {
    Level level = room({-4, 0}, {{4, 0}});
    level.spawns[1].team = botTeam;
    Match m(level, config(1));
    const std::vector<PlayerInput> still{game::makeInput({}, 0, 0, 0)};
    const float full = m.state().actors[0].health;
    bool hurt = false;
    for (int t = 0; t < 5 * game::kTicksPerSecond; ++t) {
      m.tick(still);
      hurt = hurt || m.state().actors[0].health < full || m.state().actors[0].deaths > 0;
    }
    team = m.state().actors[1].team;
    return hurt;
  };
  int team = -2;
  EXPECT_FALSE(playerHurt(0, team));  // an ally
  EXPECT_EQ(team, 0);
  EXPECT_TRUE(playerHurt(7, team));  // another team: an enemy
  EXPECT_EQ(team, 7);
  EXPECT_TRUE(playerHurt(-1, team));  // no team: a bot's, 1
  EXPECT_EQ(team, 1);
}

// The same level, seed and inputs give the same hash at every tick; another seed another match.
TEST(Match, SameSeedSameHashes) {
  auto run = [](std::uint64_t seed) {
    Match m(room({-12, -8}, {{12, 8}, {10, -10}, {-10, 12}}), config(3, seed));
    std::vector<std::uint64_t> hashes;
    for (int t = 0; t < 1200; ++t) {
      m.tick();
      hashes.push_back(m.hash());
    }
    return hashes;
  };
  const std::vector<std::uint64_t> a = run(7), b = run(7), c = run(8);
  EXPECT_EQ(a, b);
  EXPECT_NE(a.back(), c.back());
}

}  // namespace match_test
