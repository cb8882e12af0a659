// Weapons on small levels built in code, each against its closed form: penetration through 1..N
// crates and thin tile walls against the budget, ricochets as mirrors about the normal (and none
// above the angle), falloff along the whole path, shotgun patterns from the seed, grenades'
// bounces (e, head on, top-down; e^2 h under gravity), explosions in the open and behind walls,
// the weapon table's errors, and weapon selection and ammo.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "game/match/match.h"
#include "game/weapons/weapons.h"
#include "match_test_support.h"
#include "physics/trig.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace weapons_test {

using game::Level;
using game::LevelMaterial;
using game::Match;
using game::MatchConfig;
using game::PlayerInput;
using rc::Vec2;

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The bundled table, read once (every test measures against its numbers).
using match_test_support::bundled;
using match_test_support::emptyLevel;

const game::HitscanSpec& rifle() {
  return bundled().weapons[0].hitscan;
}

void addBox(Level& level, game::LevelObjectKind kind, Vec2 at, Vec2 half, LevelMaterial m = {},
            float angle = 0.0f) {
  game::LevelObject o;
  o.kind = kind;
  o.bodyType =
      kind == game::LevelObjectKind::prop ? rc::BodyType::dynamicBody : rc::BodyType::staticBody;
  o.position = at;
  o.angle = angle;
  o.material = m;
  o.shapes.push_back(rc::makeBox(half.x, half.y));
  level.objects.push_back(o);
}

void addWall(Level& level, Vec2 at, Vec2 half, LevelMaterial m = {}, float angle = 0.0f) {
  addBox(level, game::LevelObjectKind::wall, at, half, m, angle);
}

void addSpawn(Level& level, game::SpawnKind kind, Vec2 at) {
  game::LevelSpawn s;
  s.kind = kind;
  s.position = at;
  s.team = kind == game::SpawnKind::bot ? 1 : 0;
  level.spawns.push_back(s);
}

MatchConfig config(int bots, std::uint64_t seed = 1, const game::WeaponTable& table = bundled()) {
  MatchConfig c;
  c.bots = bots;
  c.seed = seed;
  c.weapons = table;
  return c;
}

LevelMaterial penetrable(float thickness) {
  LevelMaterial m;
  m.thickness = thickness;
  m.hard = false;
  return m;
}

// How many crossings of `thickness` a budget pays for, subtracting as the tracer does (float).
int affordable(float budget, float thickness) {
  int n = 0;
  while (thickness <= budget) {
    budget -= thickness;
    ++n;
  }
  return n;
}

// A rifle shot along +x from x = -10 through N crates 1 m wide (every 2 m from x = -6) of a
// given thickness, then an impenetrable wall at x = 10: it crosses as many as the budget affords
// and stops in the next, or at the wall; the path is the muzzle, each crate's entry and exit,
// and where it stopped.
TEST(Penetration, CratesCountedAgainstTheBudget) {
  const float budget = rifle().penetration;
  for (const float thickness : {0.3f, 0.45f, 0.15f}) {
    const int k = affordable(budget, thickness);
    ASSERT_EQ(k, static_cast<int>(std::floor(budget / thickness))) << thickness;
    for (int n = 1; n <= k + 2; ++n) {
      Level level = emptyLevel();
      addSpawn(level, game::SpawnKind::player, {-10, 0});
      for (int i = 0; i < n; ++i)
        addBox(level, game::LevelObjectKind::prop, {-6.0f + 2.0f * static_cast<float>(i), 0},
               {0.5f, 0.5f}, penetrable(thickness));
      addWall(level, {10.5f, 0}, {0.5f, 5});
      Match m(level, config(0));
      game::MatchState& s = m.state();
      s.actors[0].aim = 0;
      game::firePellets(s, 0, 0);
      ASSERT_EQ(s.shots.size(), 1u);
      const std::vector<Vec2>& path = s.shots[0].path;
      const int crossed = std::min(n, k);
      ASSERT_EQ(path.size(), static_cast<std::size_t>(2 + 2 * crossed)) << thickness << " " << n;
      for (int i = 0; i < crossed; ++i) {
        EXPECT_NEAR(path[static_cast<std::size_t>(1 + 2 * i)].x,
                    -6.5f + 2.0f * static_cast<float>(i), 1e-4f);
        EXPECT_NEAR(path[static_cast<std::size_t>(2 + 2 * i)].x,
                    -5.5f + 2.0f * static_cast<float>(i), 1e-4f);
      }
      // Stopped in the first crate it could not afford, or at the wall.
      const float end = n > k ? -6.5f + 2.0f * static_cast<float>(k) : 10.0f;
      EXPECT_NEAR(path.back().x, end, 1e-4f) << thickness << " " << n;
    }
  }
}

// The damage left after crossing n crates is in proportion to the budget left: a bot behind
// them takes damage * (budget - n t) / budget (inside the falloff's full range).
TEST(Penetration, DamageFollowsTheBudgetLeft) {
  const float thickness = 0.3f, budget = rifle().penetration;
  for (int n = 0; n <= affordable(budget, thickness); ++n) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-10, 0});
    addSpawn(level, game::SpawnKind::bot, {8, 0});
    for (int i = 0; i < n; ++i)
      addBox(level, game::LevelObjectKind::prop, {-6.0f + 2.0f * static_cast<float>(i), 0},
             {0.5f, 0.5f}, penetrable(thickness));
    Match m(level, config(1));
    game::MatchState& s = m.state();
    s.actors[0].aim = 0;
    game::firePellets(s, 0, 0);
    float left = budget;
    for (int i = 0; i < n; ++i)
      left -= thickness;
    const float expected = rifle().damage * left / budget;
    EXPECT_NEAR(s.actors[1].health, s.tuning.health - expected, 1e-3f) << n;
    EXPECT_EQ(s.shots[0].actorsHit, std::vector<std::size_t>{1});
  }
}

// Thin walls of tiles: two 0.2 m walls merged into one static body of one-sided chain loops (as
// the level reader merges tiles). The exit of each is found from behind: the path enters and
// leaves each wall at its faces, the nearest exit past the entry (not the far wall's). Walls of
// 0.6 with a budget of 1: the first is crossed, the second stops the shot.
TEST(Penetration, ThinTileWallsAreLeftWhereTheyEnd) {
  for (const float thickness : {0.3f, 0.6f}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-10, 0});
    game::LevelObject tiles;
    tiles.kind = game::LevelObjectKind::tiles;
    tiles.material = penetrable(thickness);
    tiles.material.hard = true;  // met head on it does not bounce
    for (const float x : {-2.0f, 3.0f}) {
      // Counter-clockwise: the solid on the left, hit from outside.
      const std::vector<Vec2> loop{{x, -2}, {x + 0.2f, -2}, {x + 0.2f, 2}, {x, 2}};
      for (const rc::ChainSegment& link : rc::makeChain(loop, true, true))
        tiles.shapes.emplace_back(link);
    }
    level.objects.push_back(tiles);
    addWall(level, {10.5f, 0}, {0.5f, 5});
    Match m(level, config(0));
    game::MatchState& s = m.state();
    s.actors[0].aim = 0;
    game::firePellets(s, 0, 0);
    const std::vector<Vec2>& path = s.shots[0].path;
    const std::vector<float> faces = thickness < 0.5f
                                         ? std::vector<float>{-10, -2, -1.8f, 3, 3.2f, 10}
                                         : std::vector<float>{-10, -2, -1.8f, 3};
    ASSERT_EQ(path.size(), faces.size()) << thickness;
    for (std::size_t i = 0; i < path.size(); ++i) {
      EXPECT_NEAR(path[i].x, faces[i], 1e-4f) << i;
      EXPECT_NEAR(path[i].y, 0.0f, 1e-6f) << i;
    }
  }
}

// A wall turned by alpha (its top face's normal (-sin alpha, cos alpha)) met at angles below the
// rifle's ricochet angle: the shot leaves along the mirror of the incoming direction about the
// normal, d - 2 (d.n) n, to float precision; at angles above it, it stops on the wall.
TEST(Ricochet, MirrorAboutTheNormalBelowTheAngleOnly) {
  const double limit = rifle().ricochetAngle / kDegree;
  ASSERT_NEAR(limit, 15.0, 1e-4);
  for (const double alpha : {0.0, 20.0, -35.0, 90.0}) {
    const double a = alpha * kDegree;
    const double nx = -std::sin(a), ny = std::cos(a);  // the face's normal
    const double tx = std::cos(a), ty = std::sin(a);   // along the face
    for (const double grazing : {1.0, 5.0, 10.0, 14.8, 15.2, 20.0, 45.0, 89.0}) {
      Level level = emptyLevel();
      addSpawn(level, game::SpawnKind::player, {-25, 25});
      addWall(level, {static_cast<float>(-0.5 * nx), static_cast<float>(-0.5 * ny)}, {20, 0.5f}, {},
              static_cast<float>(a));
      Match m(level, config(0));
      game::MatchState& s = m.state();
      // Towards the origin (on the face) from 8 m out, at `grazing` to the surface.
      const double g = grazing * kDegree;
      const double dx = std::cos(g) * tx - std::sin(g) * nx;
      const double dy = std::cos(g) * ty - std::sin(g) * ny;
      const Vec2 dir{static_cast<float>(dx), static_cast<float>(dy)};
      const Vec2 from{static_cast<float>(-8 * dx), static_cast<float>(-8 * dy)};
      game::traceShot(s, 0, 0, 0, from, dir);
      const std::vector<Vec2>& path = s.shots[0].path;
      ASSERT_GE(path.size(), 2u);
      EXPECT_NEAR(path[1].x, 0.0f, 1e-4f);
      EXPECT_NEAR(path[1].y, 0.0f, 1e-4f);
      if (grazing >= limit) {
        EXPECT_EQ(path.size(), 2u) << alpha << " " << grazing;  // stopped on the wall
        continue;
      }
      ASSERT_EQ(path.size(), 3u) << alpha << " " << grazing;  // bounced, then out of range
      const double dn = dx * nx + dy * ny;
      const double mx = dx - 2 * dn * nx, my = dy - 2 * dn * ny;
      const double ox = path[2].x - path[1].x, oy = path[2].y - path[1].y;
      const double len = std::hypot(ox, oy);
      // The angle between the measured and the mirrored directions.
      EXPECT_LT(std::fabs(std::atan2(ox * my - oy * mx, ox * mx + oy * my)), 5e-7)
          << alpha << " " << grazing;
      // The range counts the whole path: 8 m to the wall, the rest after it.
      EXPECT_NEAR(len, rifle().range - 8.0, 1e-3) << alpha << " " << grazing;
    }
  }
}

// Between two hard walls 1 m apart, a shot at 5 degrees bounces as many times as the rifle
// allows, then stops on the wall it meets next, at the closed-form points.
TEST(Ricochet, UpToTheBounceLimit) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-25, 25});
  addWall(level, {0, -0.5f}, {30, 0.5f});
  addWall(level, {0, 1.5f}, {30, 0.5f});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  const double g = 5 * kDegree;
  game::traceShot(s, 0, 0, 0, {-25, 0.5f},
                  {static_cast<float>(std::cos(g)), static_cast<float>(-std::sin(g))});
  const std::vector<Vec2>& path = s.shots[0].path;
  const int bounces = rifle().ricochets;
  ASSERT_EQ(path.size(), static_cast<std::size_t>(bounces + 2));
  double x = -25 + 0.5 / std::tan(g);
  for (int i = 1; i <= bounces + 1; ++i) {
    EXPECT_NEAR(path[static_cast<std::size_t>(i)].x, x, 2e-3) << i;
    EXPECT_NEAR(path[static_cast<std::size_t>(i)].y, i % 2 == 1 ? 0.0 : 1.0, 1e-4) << i;
    x += 1 / std::tan(g);
  }
}

// A bot on the bounced ray takes the falloff of the whole path (26 m: past the falloff's start)
// times what the bounce kept.
TEST(Ricochet, DamageAfterABounceFallsOffAlongTheWholePath) {
  const double g = 10 * kDegree;
  const double bx = -20 + 2 / std::tan(g);  // where a shot from (-20, 2) at -10 degrees lands
  const double along = 15;                  // the bot's centre, on the bounced ray
  const Vec2 bot{static_cast<float>(bx + along * std::cos(g)),
                 static_cast<float>(along * std::sin(g))};
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {-25, 25});
  addSpawn(level, game::SpawnKind::bot, bot);
  addWall(level, {0, -0.5f}, {30, 0.5f});
  Match m(level, config(1));
  game::MatchState& s = m.state();
  game::traceShot(s, 0, 0, 0, {-20, 2},
                  {static_cast<float>(std::cos(g)), static_cast<float>(-std::sin(g))});
  ASSERT_EQ(s.shots[0].actorsHit, std::vector<std::size_t>{1});
  const double distance = 2 / std::sin(g) + along - s.tuning.radius;
  ASSERT_GT(distance, rifle().falloffStart);
  const double expected =
      game::damageAt(rifle(), static_cast<float>(distance)) * (1.0 - rifle().ricochetLoss);
  EXPECT_NEAR(s.actors[1].health, s.tuning.health - expected, 2e-3);
}

// Shotgun: the pattern is the seed's (the same seed, the same pellets, bit for bit; another
// seed, another pattern), every pellet within the spread of the aim, all pellets recorded.
TEST(Shotgun, SeededPatternWithinTheCone) {
  const game::HitscanSpec& shotgun = bundled().weapons[1].hitscan;
  ASSERT_GT(shotgun.pellets, 1);
  ASSERT_GT(shotgun.spread, 0.0f);
  auto pattern = [&](std::uint64_t seed) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {0, 0});
    Match m(level, config(0, seed));
    game::MatchState& s = m.state();
    s.actors[0].aim = 0.7f;
    game::firePellets(s, 0, 1);
    std::vector<float> angles;
    for (const game::Shot& shot : s.shots) {
      const Vec2 d = shot.path[1] - shot.path[0];
      angles.push_back(std::atan2(d.y, d.x));
      EXPECT_EQ(shot.weapon, 1u);
    }
    return angles;
  };
  const std::vector<float> a = pattern(11), b = pattern(11), c = pattern(12);
  ASSERT_EQ(a.size(), static_cast<std::size_t>(shotgun.pellets));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  float lo = 1, hi = -1;
  for (const float angle : a) {
    EXPECT_LE(std::fabs(angle - 0.7f), shotgun.spread + 1e-5f);
    lo = std::min(lo, angle - 0.7f);
    hi = std::max(hi, angle - 0.7f);
  }
  EXPECT_GT(hi - lo, shotgun.spread / 2);  // spread out, not one ray
  // The distribution: uniform within the cone, both sides, mean near the aim.
  rc::Random rng(3);
  double sum = 0;
  float least = 1, most = -1;
  for (int i = 0; i < 100000; ++i) {
    const float d = game::pelletAngle(rng, 0.0f, shotgun);
    ASSERT_GE(d, -shotgun.spread);
    ASSERT_LT(d, shotgun.spread);
    sum += d;
    least = std::min(least, d);
    most = std::max(most, d);
  }
  EXPECT_NEAR(sum / 100000, 0.0, shotgun.spread * 0.01);
  EXPECT_LT(least, -0.99f * shotgun.spread);
  EXPECT_GT(most, 0.99f * shotgun.spread);
}

// What a bot expects of a gun (expectedDamagePerTick) against what the tracer deals: the
// bundled shotgun fired 400 times at an actor 3 m away (every pellet meets it: 80 a shot) and
// 4.5 m away, where asin(r / d) covers 0.744 of the spread: the mean damage a shot within 4%
// of the expected times the cooldown (the pellets that meet it are binomial: one standard
// deviation is 1% of the mean). Both inside the falloff's start, where each pellet deals its
// full damage. The rifle by closed form: its damage over its cooldown, the falloff's share at
// 40 m, nothing past its range; a grenade nothing.
TEST(Shotgun, ExpectedDamageIsWhatTheTracerDeals) {
  const game::WeaponSpec& shotgun = bundled().weapons[1];
  ASSERT_GT(shotgun.hitscan.falloffStart, 4.5f);
  for (const float d : {3.0f, 4.5f}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {0, 0});
    addSpawn(level, game::SpawnKind::bot, {d, 0});
    Match m(level, config(1, 7));
    game::MatchState& s = m.state();
    ASSERT_EQ(s.actors.size(), 2u);
    s.actors[0].aim = 0.0f;
    const int shots = 400;
    double dealt = 0;
    for (int k = 0; k < shots; ++k) {
      s.actors[1].health = s.tuning.health;
      s.shots.clear();
      game::firePellets(s, 0, 1);
      dealt += s.tuning.health - s.actors[1].health;
    }
    const float expected = game::expectedDamagePerTick(shotgun, d, s.tuning.radius) *
                           static_cast<float>(shotgun.cooldownTicks);
    const float share = std::min(1.0f, std::asin(s.tuning.radius / d) / shotgun.hitscan.spread);
    EXPECT_NEAR(expected,
                static_cast<float>(shotgun.hitscan.pellets) * shotgun.hitscan.damage * share, 1e-3f)
        << d;
    EXPECT_NEAR(dealt / shots, expected, 0.04 * expected) << d;
  }
  const game::WeaponSpec& gun = bundled().weapons[0];
  const float perTick = gun.hitscan.damage / static_cast<float>(gun.cooldownTicks);
  EXPECT_FLOAT_EQ(game::expectedDamagePerTick(gun, 10, 0.35f), perTick);
  EXPECT_FLOAT_EQ(game::expectedDamagePerTick(gun, 40, 0.35f),
                  perTick * game::falloffAt(gun.hitscan, 40));
  EXPECT_EQ(game::expectedDamagePerTick(gun, gun.hitscan.range + 1, 0.35f), 0.0f);
  EXPECT_EQ(game::expectedDamagePerTick(bundled().weapons[2], 10, 0.35f), 0.0f);
}

// The bundled grenade with no damping (top-down, damping is its rolling on the floor; over the
// ticks measured it would blur e) and a long fuse.
game::WeaponTable bounceTable() {
  game::WeaponTable t = bundled();
  game::GrenadeSpec& g = t.weapons[*t.grenade()].grenade;
  g.linearDamping = 0.0f;
  g.fuseTicks = 3600;
  return t;
}

// Top-down there is no gravity to bounce against, so the bounce is measured as it happens on a
// wall met head on: the speed after over the speed before is the restitution e (the grenade's,
// the larger of the pair), within 2%, at 4, 10 and 25 m/s.
TEST(Grenade, HeadOnBounceKeepsESpeed) {
  game::WeaponTable table = bounceTable();
  game::GrenadeSpec& g = table.weapons[*table.grenade()].grenade;
  for (const float speed : {4.0f, 10.0f, 25.0f}) {
    g.muzzleVelocity = speed;
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-8, 0});
    addWall(level, {0.5f, 0}, {0.5f, 5});
    Match m(level, config(0, 1, table));
    game::MatchState& s = m.state();
    s.actors[0].aim = 0;
    game::throwGrenade(s, 0, *table.grenade());
    const rc::BodyId body = s.grenades[0].body;
    const std::vector<PlayerInput> still{PlayerInput{}};
    float before = 0, after = 0;
    for (int t = 0; t < 600 && after == 0; ++t) {
      const float vx = s.world->linearVelocity(body).x;
      m.tick(still);
      const float now = s.world->linearVelocity(body).x;
      if (vx > 0 && now < 0) {
        before = vx;
        after = -now;
      }
    }
    ASSERT_GT(before, 0) << speed;
    EXPECT_NEAR(before, speed, 1e-4f * speed);
    EXPECT_NEAR(after / before, g.restitution, 0.02f * g.restitution) << speed;
    EXPECT_EQ(s.grenades[0].bounces, 1);
  }
}

// The issue's form of the same law: with gravity set in the level (0, -10), a grenade dropped
// from h onto a floor rises to e^2 h, within 2%.
TEST(Grenade, FirstBounceRisesToESquaredH) {
  const game::WeaponTable table = bounceTable();
  const float e = table.weapons[*table.grenade()].grenade.restitution;
  const float r = table.weapons[*table.grenade()].grenade.radius;
  for (const float h : {1.0f, 2.0f, 4.0f}) {
    Level level = emptyLevel();
    level.settings.gravity = {0, -10};
    addSpawn(level, game::SpawnKind::player, {-10, 0.35f});
    addWall(level, {0, -0.5f}, {20, 0.5f});
    Match m(level, config(0, 1, table));
    game::MatchState& s = m.state();
    game::throwGrenade(s, 0, *table.grenade());
    const rc::BodyId body = s.grenades[0].body;
    s.world->setTransform(body, {0, r + h}, 0);
    s.world->setLinearVelocity(body, {});
    const std::vector<PlayerInput> still{PlayerInput{}};
    bool bounced = false;
    float apex = 0;
    for (int t = 0; t < 600; ++t) {
      m.tick(still);
      const Vec2 v = s.world->linearVelocity(body);
      if (!bounced && v.y > 0) bounced = true;
      if (bounced) {
        apex = std::max(apex, s.world->position(body).y - r);
        if (v.y < 0) break;
      }
    }
    ASSERT_TRUE(bounced) << h;
    EXPECT_NEAR(apex, e * e * h, 0.02f * e * e * h) << h;
  }
}

// An explosion at the origin, radius R: a bot at d in the open takes damage (1 - d/R) and is
// pushed outward by impulse (1 - d/R); behind a wall a bot and a sleeping crate take nothing,
// are not pushed and not woken; a crate asleep in the open is woken and pushed.
TEST(Explosion, FallsOffInTheOpenAndStopsAtWalls) {
  const game::GrenadeSpec& g = bundled().weapons[*bundled().grenade()].grenade;
  const float radius = g.blastRadius;
  for (const bool wall : {false, true}) {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-20, 20});
    addSpawn(level, game::SpawnKind::bot, {2, 0});
    addSpawn(level, game::SpawnKind::bot, {-1, -3});  // under the wall's end: always in sight
    LevelMaterial crate = penetrable(0.3f);
    crate.density = 1;
    addBox(level, game::LevelObjectKind::prop, {0, 3}, {0.5f, 0.5f}, crate);
    if (wall) {
      addWall(level, {1, 0}, {0.2f, 1});     // between the origin and the bot at (2, 0)
      addWall(level, {0, 1.5f}, {1, 0.2f});  // between the origin and the crate at (0, 3)
    }
    Match m(level, config(2));
    game::MatchState& s = m.state();
    const std::vector<PlayerInput> still{PlayerInput{}, PlayerInput{}, PlayerInput{}};
    const rc::BodyId crateBody = s.built.bodies[0];
    // Let everything fall asleep (bots would walk: keep them still by hand).
    for (int t = 0; t < 120; ++t) {
      for (game::Actor& a : s.actors)
        s.world->setLinearVelocity(a.body, {});
      s.world->step(game::kTickSeconds);
    }
    ASSERT_FALSE(s.world->isAwake(crateBody));
    const float crateMass = s.world->mass(crateBody);
    const float botMass = s.world->mass(s.actors[1].body);
    game::explode(s, {0, 0}, g, 0);
    ASSERT_EQ(s.explosions.size(), 1u);
    const auto share = [&](float d) { return 1.0f - d / radius; };
    // The bot at (2, 0).
    const Vec2 v1 = s.world->linearVelocity(s.actors[1].body);
    if (wall) {
      EXPECT_EQ(s.actors[1].health, s.tuning.health);
      EXPECT_EQ(v1.x, 0.0f);
      EXPECT_EQ(v1.y, 0.0f);
      EXPECT_FALSE(s.world->isAwake(crateBody));
      EXPECT_EQ(s.world->linearVelocity(crateBody).x, 0.0f);
      EXPECT_EQ(s.world->linearVelocity(crateBody).y, 0.0f);
    } else {
      EXPECT_NEAR(s.actors[1].health, s.tuning.health - g.blastDamage * share(2), 1e-3f);
      EXPECT_NEAR(v1.x, g.blastImpulse * share(2) / botMass, 1e-4f);
      EXPECT_NEAR(v1.y, 0.0f, 1e-6f);
      EXPECT_TRUE(s.world->isAwake(crateBody));
      EXPECT_NEAR(s.world->linearVelocity(crateBody).y, g.blastImpulse * share(3) / crateMass,
                  1e-4f);
    }
    // The bot at (-1, -3), in sight either way: pushed along (-1, -3) / sqrt(10).
    const float d2 = std::sqrt(10.0f);
    const Vec2 v2 = s.world->linearVelocity(s.actors[2].body);
    EXPECT_NEAR(s.actors[2].health, s.tuning.health - g.blastDamage * share(d2), 1e-3f);
    EXPECT_NEAR(v2.x, -g.blastImpulse * share(d2) / botMass / d2, 1e-4f);
    EXPECT_NEAR(v2.y, -3 * g.blastImpulse * share(d2) / botMass / d2, 1e-4f);
    EXPECT_EQ(s.explosions[0].actorsHit.size(), wall ? 1u : 2u);
  }
}

// Through the tick: kButtonThrow throws a grenade (ammo down, a live body of the projectile
// kind); after its fuse it explodes where it lies (recorded for the view), its body leaves the
// world, and the next throw reuses its slot.
TEST(Grenade, ThrownFusedExplodedSlotReused) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  const std::size_t gi = *s.weapons.grenade();
  const game::WeaponSpec& spec = s.weapons.weapons[gi];
  const int ammo = s.actors[0].ammo[gi];
  const std::vector<PlayerInput> throwIt{game::makeInput({}, 0, game::kButtonThrow, 0)};
  const std::vector<PlayerInput> still{PlayerInput{}};
  m.tick(throwIt);
  ASSERT_EQ(s.grenades.size(), 1u);
  EXPECT_TRUE(s.grenades[0].live);
  EXPECT_EQ(s.actors[0].ammo[gi], ammo - 1);
  const rc::BodyId body = s.grenades[0].body;
  EXPECT_EQ(s.world->userData(body), game::gameUserData(game::GameKind::projectile, 0));
  EXPECT_TRUE(s.world->isBullet(body));
  int ticks = 1;
  Vec2 last{};
  while (s.explosions.empty() && ticks < 1000) {
    last = s.world->worldCenter(body);
    m.tick(still);
    ++ticks;
  }
  // Thrown in tick 0's weapons phase, it explodes in the weapons phase fuseTicks ticks later.
  EXPECT_EQ(ticks, spec.grenade.fuseTicks + 1);
  ASSERT_EQ(s.explosions.size(), 1u);
  EXPECT_EQ(s.explosions[0].center, last);
  EXPECT_EQ(s.explosions[0].radius, spec.grenade.blastRadius);
  EXPECT_FALSE(s.world->isValid(body));
  EXPECT_FALSE(s.grenades[0].live);
  m.tick(throwIt);
  EXPECT_EQ(s.grenades.size(), 1u);
  EXPECT_TRUE(s.grenades[0].live);
}

// PlayerInput::weapon chooses what the trigger fires: the shotgun's pellets, each weapon's own
// ammo; an index past the table fires nothing; an empty weapon fires nothing.
TEST(Weapons, SelectionAndAmmo) {
  Level level = emptyLevel();
  addSpawn(level, game::SpawnKind::player, {0, 0});
  Match m(level, config(0));
  game::MatchState& s = m.state();
  const game::WeaponTable& t = s.weapons;
  for (std::size_t w = 0; w < t.weapons.size(); ++w)
    EXPECT_EQ(s.actors[0].ammo[w], t.weapons[w].ammo);
  auto fire = [&](std::uint8_t weapon) {
    s.actors[0].cooldown = 0;
    m.tick(std::vector<PlayerInput>{game::makeInput({}, 0, game::kButtonFire, weapon)});
    return s.shots.size();
  };
  EXPECT_EQ(fire(1), static_cast<std::size_t>(t.weapons[1].hitscan.pellets));
  EXPECT_EQ(s.actors[0].ammo[1], t.weapons[1].ammo - 1);
  EXPECT_EQ(s.actors[0].ammo[0], t.weapons[0].ammo);
  EXPECT_EQ(fire(0), 1u);
  EXPECT_EQ(s.actors[0].cooldown, t.weapons[0].cooldownTicks);
  EXPECT_EQ(fire(7), 0u);
  s.actors[0].ammo[0] = 0;
  EXPECT_EQ(fire(0), 0u);
}

// Grenades and shotguns keep matches deterministic: the same seed and scripted inputs give the
// same hash at every tick.
TEST(Weapons, SameInputsSameHashes) {
  auto run = [] {
    Level level = emptyLevel();
    addSpawn(level, game::SpawnKind::player, {-5, 0});
    addSpawn(level, game::SpawnKind::bot, {5, 2});
    addSpawn(level, game::SpawnKind::bot, {6, -3});
    addWall(level, {0, 8}, {10, 0.5f});
    addWall(level, {0, -8}, {10, 0.5f});
    addWall(level, {10, 0}, {0.5f, 8});
    addWall(level, {-10, 0}, {0.5f, 8});
    addBox(level, game::LevelObjectKind::prop, {2, 0}, {0.5f, 0.5f}, penetrable(0.3f));
    Match m(level, config(2, 9));
    std::vector<std::uint64_t> hashes;
    for (int t = 0; t < 900; ++t) {
      const std::uint8_t buttons = t % 150 == 0 ? game::kButtonThrow : game::kButtonFire;
      const float aim = 0.3f * static_cast<float>(t % 7) - 0.9f;
      m.tick(std::vector<PlayerInput>{
          game::makeInput({0.3f, 0}, aim, buttons, static_cast<std::uint8_t>(t / 100 % 2))});
      hashes.push_back(m.hash());
    }
    return hashes;
  };
  EXPECT_EQ(run(), run());
}

// The weapon table: the bundled file reads; every bad file is one line naming the file and the
// field, never a crash.
TEST(WeaponTable, BundledAndBadFiles) {
  const game::WeaponTable& t = bundled();
  ASSERT_EQ(t.weapons.size(), 3u);
  EXPECT_EQ(t.weapons[0].name, "rifle");
  EXPECT_EQ(t.weapons[1].name, "shotgun");
  EXPECT_EQ(t.weapons[2].kind, game::WeaponKind::grenade);
  EXPECT_EQ(t.grenade(), std::optional<std::size_t>(2));
  EXPECT_NEAR(t.weapons[0].hitscan.ricochetSin, std::sin(15 * kDegree), 1e-6);

  const std::string rifleText =
      R"({"name": "rifle", "kind": "hitscan", "cooldownTicks": 8, "ammo": 90, "damage": 25,
          "range": 60, "falloff": {"start": 20, "end": 60, "min": 0.5}, "pellets": 1,
          "spreadDegrees": 0, "penetration": 1, "impulse": 4,
          "ricochet": {"bounces": 2, "maxAngleDegrees": 15, "damageLoss": 0.3}})";
  EXPECT_EQ(game::parseWeaponTable(R"({"weapons": [)" + rifleText + "]}", "w.json").weapons.size(),
            1u);
  auto error = [](const std::string& text) {
    try {
      game::parseWeaponTable(text, "w.json");
    } catch (const game::WeaponTableError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = R"({"weapons": [)" + rifleText + "]}";
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return error(text.replace(at, from.size(), to));
  };
  EXPECT_EQ(error("{"),
            "w.json: not valid JSON: parse error at line 1, column 2: syntax error "
            "while parsing object key - unexpected end of input; expected string "
            "literal");
  EXPECT_EQ(error("[]"), "w.json: must hold a JSON object, got []");
  EXPECT_EQ(error(R"({"weapons": []})"),
            "w.json: 'weapons' must be an array of 1 to 8 weapons, got []");
  EXPECT_EQ(error(R"({"weapon": []})"), "w.json: unknown field 'weapon'");
  EXPECT_EQ(with(R"("pellets": 1)", R"("pellets": 0)"),
            "w.json: weapons[0] (\"rifle\"): 'pellets' must be an integer from 1 to 64, got 0");
  EXPECT_EQ(with(R"("damage": 25)", R"("damage": "lots")"),
            "w.json: weapons[0] (\"rifle\"): 'damage' must be a number from 0 to 10000, got "
            "\"lots\"");
  EXPECT_EQ(with(R"("range": 60,)", ""), "w.json: weapons[0] (\"rifle\"): 'range' is missing");
  EXPECT_EQ(with(R"("min": 0.5)", R"("min": 1.5)"),
            "w.json: weapons[0] (\"rifle\"): 'falloff': 'min' must be a number from 0 to 1, got "
            "1.5");
  EXPECT_EQ(with(R"("bounces": 2,)", R"("bounces": 2, "bounce": 3,)"),
            "w.json: weapons[0] (\"rifle\"): 'ricochet': unknown field 'bounce'");
  EXPECT_EQ(with(R"("kind": "hitscan")", R"("kind": "laser")"),
            "w.json: weapons[0] (\"rifle\"): 'kind' must be \"hitscan\" or \"grenade\", got "
            "\"laser\"");
  EXPECT_EQ(error(R"({"weapons": [)" + rifleText + "," + rifleText + "]}"),
            "w.json: weapons[1] (\"rifle\"): 'name' \"rifle\" is taken");
  EXPECT_EQ(error(R"({"weapons": [1]})"), "w.json: weapons[0]: must be an object, got 1");
  // Hostile files: nesting (100,000 levels once crashed a reader rendering the value), a key
  // twice, names with control characters (escaped, cut: the message stays one line).
  EXPECT_EQ(error(std::string(100000, '[') + std::string(100000, ']')),
            "w.json: not a weapon table: JSON nested deeper than 16 levels");
  EXPECT_EQ(with(R"("ammo": 90,)", R"("ammo": 90, "ammo": 9,)"),
            "w.json: the key \"ammo\" appears twice in one object");
  const std::string named =
      with(R"("name": "rifle")", "\"name\": \"a\\nb\\u001b[31m" + std::string(60, 'x') + "\"");
  EXPECT_EQ(named.find('\n'), std::string::npos);
  EXPECT_EQ(named.find('\x1b'), std::string::npos);
  EXPECT_LT(named.size(), 160u) << named;
  try {
    game::loadWeaponTable("/no/such/weapons.json");
    ADD_FAILURE();
  } catch (const game::WeaponTableError& e) {
    EXPECT_STREQ(e.what(), "/no/such/weapons.json: cannot open the file: it does not exist");
  }
  // A device has no size to check: /dev/zero was read until memory ran out.
  try {
    game::loadWeaponTable("/dev/zero");
    ADD_FAILURE();
  } catch (const game::WeaponTableError& e) {
    EXPECT_STREQ(e.what(), "/dev/zero: cannot open the file: it is not a regular file");
  }
}

}  // namespace weapons_test
