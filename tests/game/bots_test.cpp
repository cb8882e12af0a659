// Bots that perceive (game/bots): sight cones exact to the edge through perception, hearing
// through walls by the halving rule, footsteps by speed, memory that fades, each behaviour
// transition, A* against Dijkstra on random grids, the navigation grid of a level (and what it
// knows of tile walls' insides, which lets sight skip rays), a bot crossing the maze, and bots
// that never react to what they could not perceive over a long run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <string>
#include <vector>

#include "game/bots/cover.h"
#include "game/bots/hearing.h"
#include "game/bots/memory.h"
#include "game/bots/navigation.h"
#include "game/bots/sight.h"
#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/rules/triggers.h"
#include "game/weapons/hitscan.h"
#include "level_test_support.h"
#include "match_test_support.h"
#include "physics/random.h"
#include "physics/trig.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace bots_test {

using game::Behaviour;
using game::Level;
using game::Match;
using game::MatchConfig;
using game::MatchState;
using game::NavGrid;
using game::PlayerInput;
using rc::Vec2;

using match_test_support::addPickup;
using match_test_support::addTrigger;
using match_test_support::Box;
using match_test_support::config;
using match_test_support::room;

Vec2 position(const MatchState& s, std::size_t actor) {
  return s.world->worldCenter(s.actors[actor].body);
}

// The memory entry a bot has about an actor, if any.
const game::MemoryEntry* recall(const MatchState& s, std::size_t bot, std::size_t actor) {
  for (const game::MemoryEntry& e : s.minds[bot].memory)
    if (e.actor == static_cast<std::int32_t>(actor)) return &e;
  return nullptr;
}

float angleTo(const MatchState& s, std::size_t from, std::size_t to) {
  const Vec2 d = position(s, to) - position(s, from);
  return std::atan2(d.y, d.x);
}

float angleBetween(float a, float b) {
  float d = std::fmod(std::fabs(a - b), 2 * rc::kPi);
  return d > rc::kPi ? 2 * rc::kPi - d : d;
}

const std::vector<PlayerInput> kStill{PlayerInput{}};
const std::vector<PlayerInput> kShootNorth{game::makeInput({}, rc::kPi / 2, game::kButtonFire, 0)};

// ---- Sight through perception -------------------------------------------------------------

// The cone's edges are exact through perception too: a player a thousandth of a radian inside
// the half-angle is remembered as seen by the bot's look, one a thousandth outside is not (and
// gets no ray); nor one beyond the range.
TEST(Perception, SightConeEdgesExact) {
  const float half = game::SightTuning{}.halfAngle;
  for (const float angle : {half - 1e-3f, half + 1e-3f, -(half - 1e-3f), -(half + 1e-3f)}) {
    const Vec2 at{10 * std::cos(angle), 10 * std::sin(angle)};
    Match m(room(at, {{0, 0}}), config(1));
    MatchState& s = m.state();
    s.actors[1].aim = 0;
    game::look(s, 1);
    const bool inside = std::fabs(angle) < half;
    EXPECT_EQ(recall(s, 1, 0) != nullptr, inside) << angle;
    EXPECT_EQ(s.sightRays.size(), inside ? 1u : 0u) << angle;
    if (inside) {
      EXPECT_EQ(recall(s, 1, 0)->sense, game::Sense::seen);
      EXPECT_TRUE(s.sightRays[0].clear);
    }
  }
  // 25 m is the range: 24.9 seen, 25.1 not.
  for (const float d : {24.9f, 25.1f}) {
    Match m(room({-10, 0}, {{d - 10, 0}}), config(1));
    m.state().actors[1].aim = rc::kPi;
    game::look(m.state(), 1);
    EXPECT_EQ(recall(m.state(), 1, 0) != nullptr, d < 25) << d;
  }
  // Behind a wall: the ray is cast and stops at the wall; nothing remembered.
  Match walled(room({-5, 0}, {{5, 0}}, {{{0, 0}, {0.5f, 3}}}), config(1));
  walled.state().actors[1].aim = rc::kPi;
  game::look(walled.state(), 1);
  EXPECT_EQ(recall(walled.state(), 1, 0), nullptr);
  ASSERT_EQ(walled.state().sightRays.size(), 1u);
  EXPECT_FALSE(walled.state().sightRays[0].clear);
  EXPECT_NEAR(walled.state().sightRays[0].to.x, 0.5f, 1e-3f);
}

// Sight runs every kLookEvery ticks, staggered by index: bot i looks on ticks t with
// (t + i) % kLookEvery == 0; hearing every tick.
TEST(Perception, LooksStaggeredAcrossBots) {
  Match m(room({-15, -15}, {{0, 0}, {5, 0}, {10, 0}}), config(3));
  for (int t = 0; t < 12; ++t) {
    m.tick(kStill);
    for (std::size_t i = 1; i <= 3; ++i) {
      const std::int64_t last = m.state().minds[i].lastLook;
      if (last < 0) {
        EXPECT_LT(t, game::kLookEvery - 1);  // not its turn yet
        continue;
      }
      EXPECT_LE(t - last, game::kLookEvery - 1);
      EXPECT_EQ((last + static_cast<std::int64_t>(i)) % game::kLookEvery, 0);
    }
  }
}

// Over a minute, a bot never reacts to a silent player standing behind it or walled in: its
// memory of the player only ever comes from looks that saw it (checked with sees() before each
// tick), it stays on patrol until one has, and it fires only while its latest look saw the
// player. Walled in, the player is never seen, never remembered, never shot at; in the open the
// patrolling bot finds it sooner or later.
TEST(Perception, NeverReactsToWhatItCannotPerceive) {
  for (const bool wall : {false, true}) {
    std::vector<Box> walls;
    if (wall) {
      // A closed chamber round the player at (8, 0).
      walls = {{{6, 0}, {0.25f, 2.25f}},
               {{10, 0}, {0.25f, 2.25f}},
               {{8, 2}, {2.25f, 0.25f}},
               {{8, -2}, {2.25f, 0.25f}}};
    }
    Match m(room({8, 0}, {{-4, 0}}, walls), config(1, 3));
    MatchState& s = m.state();
    s.actors[1].aim = rc::kPi;  // facing away from the player
    std::int64_t lastSeen = -1;
    std::vector<std::int64_t> seenTicks;
    int fired = 0, seenLooks = 0;
    for (int t = 0; t < 60 * game::kTicksPerSecond && s.actors[0].alive; ++t) {
      if (game::looksAt(t, 1) && game::sees(s, 1, 0)) {
        lastSeen = t;
        seenTicks.push_back(t);
        ++seenLooks;
      }
      const bool lookNow = game::looksAt(t, 1);
      const bool sawNow = lookNow && lastSeen == t;
      m.tick(kStill);
      const game::MemoryEntry* e = recall(s, 1, 0);
      if (e != nullptr) {
        ASSERT_EQ(e->sense, game::Sense::seen) << "wall " << wall << " tick " << t;
        ASSERT_TRUE(std::binary_search(seenTicks.begin(), seenTicks.end(), e->tick))
            << "wall " << wall << " tick " << t;
      }
      if (lastSeen < 0) {
        ASSERT_EQ(s.minds[1].behaviour, Behaviour::patrol) << "wall " << wall << " tick " << t;
      }
      const bool fires = (s.actors[1].input.buttons & game::kButtonFire) != 0;
      fired += fires;
      // It fires only on what its latest look saw (this tick's look, or the last one).
      if (fires) {
        ASSERT_GE(lastSeen, s.minds[1].lastLook) << "wall " << wall << " tick " << t;
      }
      if (lookNow) {
        ASSERT_EQ(sawNow, e != nullptr && e->tick == t) << "wall " << wall << " tick " << t;
      }
    }
    if (wall) {
      EXPECT_EQ(seenLooks, 0);
      EXPECT_EQ(fired, 0);
    } else {
      EXPECT_GT(seenLooks, 0);
      EXPECT_GT(fired, 0);
    }
  }
}

// ---- Hearing --------------------------------------------------------------------------------

// The walls rule: each wall a ray from the sound to the listener enters halves the radius. A
// sound 6 m away through two walls is heard at a radius of 24.1 (6.025 after halving twice),
// not at 23.9 (5.975); through one wall 3 m away at 6.1, not 5.9; in the open at the distance
// itself. Its own team's sounds and its own are never heard.
TEST(Hearing, EachWallHalvesTheRadius) {
  Match m(room({-15, -15}, {{0, 0}}, {{{2, 0}, {0.25f, 5}}, {{4, 0}, {0.25f, 5}}}), config(1));
  MatchState& s = m.state();
  auto sound = [](Vec2 at, float radius, std::int32_t team = 0) {
    game::Sound snd;
    snd.kind = game::SoundKind::shot;
    snd.maker = 0;
    snd.team = team;
    snd.position = at;
    snd.radius = radius;
    return snd;
  };
  EXPECT_EQ(game::wallsBetween(s, {6, 0}, {0, 0}, 10), 2);
  EXPECT_EQ(game::hears(s, 1, sound({6, 0}, 24.1f)), 2);
  EXPECT_FALSE(game::hears(s, 1, sound({6, 0}, 23.9f)));
  EXPECT_EQ(game::hears(s, 1, sound({3, 0}, 6.1f)), 1);
  EXPECT_FALSE(game::hears(s, 1, sound({3, 0}, 5.9f)));
  EXPECT_EQ(game::hears(s, 1, sound({-3, 0}, 3.01f)), 0);
  EXPECT_FALSE(game::hears(s, 1, sound({-3, 0}, 2.99f)));
  EXPECT_FALSE(game::hears(s, 1, sound({-3, 0}, 10, 1)));  // its own team
  game::Sound own = sound({-3, 0}, 10);
  own.maker = 1;
  EXPECT_FALSE(game::hears(s, 1, own));
}

// A wall of pieces (a concave outline split into convex ones, tiles side by side) is one wall:
// two boxes touching along the ray count once; 5 cm of open space between them makes two.
TEST(Hearing, PiecesOfOneWallCountOnce) {
  Match touching(room({-15, -15}, {{0, 0}}, {{{2, 0}, {0.25f, 5}}, {{2.5f, 0}, {0.25f, 5}}}),
                 config(1));
  EXPECT_EQ(game::wallsBetween(touching.state(), {6, 0}, {0, 0}, 10), 1);
  EXPECT_EQ(game::wallsBetween(touching.state(), {0, 0}, {6, 0}, 10), 1);
  Match apart(room({-15, -15}, {{0, 0}}, {{{2, 0}, {0.25f, 5}}, {{2.55f, 0}, {0.25f, 5}}}),
              config(1));
  EXPECT_EQ(game::wallsBetween(apart.state(), {6, 0}, {0, 0}, 10), 2);
  Match three(room({-15, -15}, {{0, 0}},
                   {{{2, 0}, {0.25f, 5}}, {{2.5f, 0}, {0.25f, 5}}, {{4, 0}, {0.25f, 5}}}),
              config(1));
  EXPECT_EQ(game::wallsBetween(three.state(), {6, 0}, {0, 0}, 10), 2);
  EXPECT_EQ(game::wallsBetween(three.state(), {6, 0}, {0, 0}, 1), 1);  // counted up to the limit
}

// Merged tiles are one-sided outlines, which a ray only enters: two tile regions with open
// space between are two walls, each found to end where its outline does (cast back from the
// listener, the whole body's, not the link's).
TEST(Hearing, TileRegionsCountOnceEach) {
  Level level = room({-15, -15}, {{0, 0}});
  game::LevelObject tiles;
  tiles.kind = game::LevelObjectKind::tiles;
  for (const float x : {1.5f, 3.5f}) {
    // Counter-clockwise: the solid on the left, entered from outside.
    const std::vector<Vec2> loop{{x, -2}, {x + 1, -2}, {x + 1, 2}, {x, 2}};
    for (const rc::ChainSegment& link : rc::makeChain(loop, true, true))
      tiles.shapes.emplace_back(link);
  }
  level.objects.push_back(tiles);
  Match m(level, config(1));
  EXPECT_EQ(game::wallsBetween(m.state(), {6, 0}, {0, 0}, 10), 2);
  EXPECT_EQ(game::wallsBetween(m.state(), {0, 0}, {6, 0}, 10), 2);
  EXPECT_EQ(game::wallsBetween(m.state(), {3, 0}, {0, 0}, 10), 1);
}

// Footsteps by speed: a player running (5 m/s) makes a footstep every kStrideTicks that carries
// 8 m; one walking at 2 m/s is silent. A bot penned in (1 x 1 m, so it stays put; the pen's wall
// halves the radius to 4 m) hears the runner pass 2.5 m away, and remembers where it was, exactly
// when hears() says it should; the walker it never hears.
TEST(Hearing, FootstepsBySpeed) {
  for (const float speed : {1.0f, 0.4f}) {
    const std::vector<Box> pen{{{0.6f, 0}, {0.1f, 0.7f}},
                               {{-0.6f, 0}, {0.1f, 0.7f}},
                               {{0, 0.6f}, {0.7f, 0.1f}},
                               {{0, -0.6f}, {0.7f, 0.1f}}};
    Match m(room({-2.5f, -10}, {{0, 0}}, pen), config(1));
    MatchState& s = m.state();
    const std::vector<PlayerInput> run{game::makeInput({0, speed}, rc::kPi / 2, 0, 0)};
    int footsteps = 0, heard = 0;
    for (int t = 0; t < 4 * game::kTicksPerSecond; ++t) {
      int expected = 0;
      for (const game::Sound& snd : s.sounds)
        expected += game::hears(s, 1, snd).has_value();
      m.tick(run);
      ASSERT_EQ(static_cast<int>(s.heard.size()), expected) << t;
      for (const game::HeardSound& h : s.heard) {
        EXPECT_EQ(h.sound.kind, game::SoundKind::footstep);
        EXPECT_EQ(h.walls, 1);
        const game::MemoryEntry* e = recall(s, 1, 0);
        ASSERT_NE(e, nullptr);
        EXPECT_EQ(e->sense, game::Sense::heard);
        EXPECT_EQ(e->position, h.sound.position);
        ++heard;
      }
      for (const game::Sound& snd : s.sounds) {
        if (snd.maker != 0) continue;
        ++footsteps;
        EXPECT_EQ(snd.kind, game::SoundKind::footstep);
        EXPECT_NEAR(snd.radius, game::kFootstepSeconds * 5.0f * speed, 0.05f);
      }
    }
    if (speed == 1.0f) {
      EXPECT_GE(footsteps, 10);
      EXPECT_GE(heard, 2);
    } else {
      EXPECT_EQ(footsteps, 0);
      EXPECT_EQ(heard, 0);
      EXPECT_EQ(recall(s, 1, 0), nullptr);
    }
  }
}

// A bot facing away turns to a gunshot it can hear: the player behind it fires once into the
// ceiling; the next tick the bot has heard it (patrol -> investigate), within half a second it
// faces the player, and as soon as its look sees it, it attacks.
TEST(Hearing, TurnsToAGunshot) {
  Match m(room({-6, 0}, {{0, 0}}), config(1));
  MatchState& s = m.state();
  s.actors[1].aim = 0;
  const std::vector<PlayerInput> shoot{game::makeInput({}, rc::kPi / 2, game::kButtonFire, 0)};
  m.tick(shoot);
  ASSERT_EQ(s.sounds.size(), 1u);
  EXPECT_EQ(s.sounds[0].kind, game::SoundKind::shot);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::patrol);
  m.tick(kStill);
  ASSERT_NE(recall(s, 1, 0), nullptr);
  EXPECT_EQ(recall(s, 1, 0)->sense, game::Sense::heard);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::investigate);
  ASSERT_EQ(s.heard.size(), 1u);
  EXPECT_EQ(s.heard[0].walls, 0);
  int t = 0;
  while (s.minds[1].behaviour != Behaviour::attack && t < game::kTicksPerSecond) {
    m.tick(kStill);
    ++t;
  }
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::attack);
  EXPECT_LE(t, game::kTicksPerSecond / 2);
  EXPECT_LT(angleBetween(s.actors[1].aim, angleTo(s, 1, 0)), 1.1f);
}

// ---- Memory ---------------------------------------------------------------------------------

// Confidence fades linearly to zero (sight over kSeenFadeTicks, hearing from kHeardStrength over
// kHeardFadeTicks); what is seen overrides what was heard, a sound does not override a fresh
// sighting; a full memory gives up its weakest slot; faded entries are forgotten.
TEST(Memory, FadesAndReplaces) {
  game::BotMind mind;
  game::Perception seen{3, game::Sense::seen, {1, 2}, {0.5f, 0}, 1.0f};
  game::remember(mind, seen, 100);
  ASSERT_EQ(mind.memory[0].actor, 3);
  EXPECT_EQ(game::confidence(mind.memory[0], 100), 1.0f);
  EXPECT_FLOAT_EQ(game::confidence(mind.memory[0], 100 + game::kSeenFadeTicks / 2), 0.5f);
  EXPECT_EQ(game::confidence(mind.memory[0], 100 + game::kSeenFadeTicks), 0.0f);
  const Vec2 ahead = game::expectedPosition(mind.memory[0], 160, 30);
  EXPECT_FLOAT_EQ(ahead.x, 1 + 0.5f * 0.5f);  // 30 ticks at most: half a second at 0.5 m/s
  game::Perception heard{3, game::Sense::heard, {7, 7}, {}, game::kHeardStrength};
  game::remember(mind, heard, 110);  // a fresh sighting is worth more
  EXPECT_EQ(mind.memory[0].sense, game::Sense::seen);
  game::remember(mind, heard, 200);  // 100 ticks on, the sighting is worth 0.72
  EXPECT_EQ(mind.memory[0].sense, game::Sense::heard);
  EXPECT_EQ(mind.memory[0].position, (Vec2{7, 7}));
  game::remember(mind, seen, 201);  // seeing beats hearing
  EXPECT_EQ(mind.memory[0].sense, game::Sense::seen);
  for (std::int32_t actor = 4; actor < 7; ++actor)
    game::remember(mind, {actor, game::Sense::heard, {}, {}, game::kHeardStrength}, 202);
  EXPECT_EQ(game::strongestMemory(mind, 202), 0);
  // Full: a new actor takes the weakest slot (the heard ones, all equal: the lowest of them).
  game::remember(mind, {9, game::Sense::seen, {}, {}, 1.0f}, 203);
  EXPECT_EQ(mind.memory[1].actor, 9);
  game::forgetFaded(mind, 202 + game::kHeardFadeTicks);
  EXPECT_EQ(mind.memory[2].actor, -1);
  EXPECT_EQ(mind.memory[0].actor, 3);
  game::forgetFaded(mind, 203 + game::kSeenFadeTicks);
  EXPECT_EQ(game::strongestMemory(mind, 203 + game::kSeenFadeTicks), -1);
}

// ---- Behaviour transitions ------------------------------------------------------------------

// Runs until the bot's behaviour is `wanted` (or `limit` ticks); the ticks it took.
int runUntil(Match& m, std::size_t bot, Behaviour wanted, int limit,
             const std::vector<PlayerInput>& inputs = kStill) {
  int t = 0;
  while (m.state().minds[bot].behaviour != wanted && t < limit) {
    m.tick(inputs);
    ++t;
  }
  return t;
}

// Bot 1, turned to face west (where these tests put the player), until it sees the player and
// attacks (at most 10 ticks).
void faceThePlayer(Match& m) {
  m.state().actors[1].aim = rc::kPi;
  runUntil(m, 1, Behaviour::attack, 10);
}

// patrol -> investigate on a shot heard through a wall; investigate -> attack once, walking
// round the wall by its path, it sees the shooter; the walk is a path around the wall, not into
// it (the bot never stalls against it).
TEST(Behaviour, PatrolInvestigateAttack) {
  // A 12 m wall between them; the player fires once, to the north, then stands still.
  Match m(room({6, 0}, {{-6, 0}}, {{{0, 0}, {0.5f, 6}}}), config(1));
  MatchState& s = m.state();
  s.actors[1].aim = rc::kPi;
  m.tick(kStill);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::patrol);
  m.tick(kShootNorth);
  m.tick(kStill);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::investigate);
  ASSERT_EQ(s.heard.size(), 1u);
  EXPECT_EQ(s.heard[0].walls, 1);
  // Its route goes round an end of the wall (|y| > 6 somewhere).
  const game::NavRoute& route = s.minds[1].route;
  ASSERT_GT(route.length, 1);
  bool around = false;
  for (int k = 0; k < route.length; ++k)
    around |= std::fabs(route.points[static_cast<std::size_t>(k)].y) > 6.2f;
  EXPECT_TRUE(around);
  const int t = runUntil(m, 1, Behaviour::attack, 4 * game::kTicksPerSecond);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::attack) << t;
}

// attack -> chase when the enemy goes out of sight (behind a wall), towards where it was last
// seen; chase -> patrol once the memory has faded (kSeenFadeTicks after the last sighting), and
// not before.
TEST(Behaviour, AttackChaseThenFadeToPatrol) {
  Match m(room({-8, 0}, {{4, 0}}, {{{-2, 8}, {10, 0.5f}}}), config(1));
  MatchState& s = m.state();
  faceThePlayer(m);
  ASSERT_EQ(s.minds[1].behaviour, Behaviour::attack);
  // The player vanishes behind the wall (to y = 15, north of the wall at y = 8), silently.
  s.world->setTransform(s.actors[0].body, {-8, 15}, 0);
  const std::int64_t lastSeen = recall(s, 1, 0)->tick;
  runUntil(m, 1, Behaviour::chase, 10);
  ASSERT_EQ(s.minds[1].behaviour, Behaviour::chase);
  // It heads for where it saw the player: nearer after a second (if it has not seen it again).
  const float before = rc::distance(position(s, 1), {-8, 0});
  for (int k = 0; k < game::kTicksPerSecond && s.minds[1].behaviour == Behaviour::chase; ++k)
    m.tick(kStill);
  if (s.minds[1].behaviour == Behaviour::chase) {
    EXPECT_LT(rc::distance(position(s, 1), {-8, 0}), before);
  }
  // Never in sight again (the player is behind the wall, and bots looking around do not see
  // through walls): patrol exactly when the sighting has faded.
  while (s.minds[1].behaviour != Behaviour::patrol &&
         s.tick < lastSeen + 2 * game::kSeenFadeTicks) {
    ASSERT_NE(s.minds[1].behaviour, Behaviour::attack);
    m.tick(kStill);
  }
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::patrol);
  EXPECT_EQ(s.minds[1].behaviourSince, lastSeen + game::kSeenFadeTicks);
}

// attack -> take cover when hurt (at half health or less, and hit): the spot it goes to is one
// the enemy cannot see (a ray from the enemy meets the wall), and it gets there; 4 s later, not
// hit again, take cover -> chase. With nothing to hide behind it flees instead, to a place farther
// from the enemy.
TEST(Behaviour, HurtTakesCoverOrFlees) {
  {
    Match m(room({-10, 0}, {{0, 0}}, {{{2, -4}, {0.5f, 2}}}), config(1));
    MatchState& s = m.state();
    faceThePlayer(m);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::attack);
    s.actors[1].health = 40;
    m.tick(kStill);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::takeCover);
    const std::int64_t hidAt = s.minds[1].behaviourSince;
    const Vec2 spot = s.minds[1].goal;
    EXPECT_TRUE(s.world->castRay({-10, 0}, spot - Vec2{-10, 0}, game::staticSolids(*s.world)));
    EXPECT_GT(spot.x, 2.0f);  // behind the wall, from the player at x = -10
    for (int k = 0; k < 3 * game::kTicksPerSecond; ++k)
      m.tick(kStill);
    EXPECT_LT(rc::distance(position(s, 1), spot), 1.0f);
    EXPECT_FALSE(game::sees(s, 0, 1, {100.0f, rc::kPi}));  // hidden from the player
    // Health does not come back: after 4 s in cover, not hit again, it goes after the player it
    // still remembers (chase: out of sight).
    runUntil(m, 1, Behaviour::chase, 2 * game::kTicksPerSecond);
    EXPECT_EQ(s.minds[1].behaviour, Behaviour::chase);
    EXPECT_EQ(s.minds[1].behaviourSince - hidAt, 4 * game::kTicksPerSecond);
  }
  {
    Match m(room({-10, 0}, {{0, 0}}), config(1));
    MatchState& s = m.state();
    faceThePlayer(m);
    s.actors[1].health = 40;
    m.tick(kStill);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::flee);
    EXPECT_GT(rc::distance(s.minds[1].goal, {-10, 0}), rc::distance(position(s, 1), {-10, 0}) + 5);
  }
}

// A bot that lacks something and sees no enemy fetches the nearest pickup there that gives it:
// hurt, the nearer of two health packs (13 m away: its goal from the first tick, taken within
// 5 s at 4 m/s); out of rounds, the ammo pack (within 10 s). A pack already taken is passed
// over for the other. With nothing lacking it patrols again. A nearer pack inside a block,
// which no actor can touch, is never its goal.
TEST(Behaviour, FetchesThePickupItNeeds) {
  Level level = room({-15, -15}, {{0, 0}}, {{{-5, 0}, {1, 1}}});
  addPickup(level, "health", 50, 30, {-12, 5});
  addPickup(level, "ammo", 20, 30, {12, -5});
  addPickup(level, "health", 50, 30, {-14, -12});
  addPickup(level, "health", 50, 30, {-5, 0});  // inside the block
  MatchConfig c = config(1);
  c.players = 0;
  Match m(std::move(level), c);
  MatchState& s = m.state();
  ASSERT_EQ(s.actors.size(), 1u);
  ASSERT_EQ(s.pickups.size(), 4u);
  auto runUntilTaken = [&m, &s](std::size_t pickup, int limit) {
    int t = 0;
    while (s.pickups[pickup].timesTaken == 0 && t < limit) {
      m.tick();
      ++t;
    }
    return t;
  };
  m.tick();
  EXPECT_EQ(s.minds[0].behaviour, Behaviour::patrol);
  s.actors[0].health = 40;
  m.tick();
  EXPECT_EQ(s.minds[0].behaviour, Behaviour::fetch);
  EXPECT_EQ(s.minds[0].goal, (Vec2{-12, 5}));
  int t = runUntilTaken(0, 5 * game::kTicksPerSecond);
  EXPECT_EQ(s.pickups[0].timesTaken, 1) << "after " << t << " ticks";
  EXPECT_EQ(s.actors[0].health, 90.0f);
  // The rifle empty and the shotgun full, it is not short of rounds; both low, it is.
  s.actors[0].ammo[0] = 0;
  m.tick();
  EXPECT_EQ(s.minds[0].behaviour, Behaviour::patrol);
  s.actors[0].ammo[1] = s.weapons.weapons[1].ammo / 4;
  t = runUntilTaken(1, 10 * game::kTicksPerSecond);
  EXPECT_EQ(s.pickups[1].timesTaken, 1) << "after " << t << " ticks";
  EXPECT_EQ(s.actors[0].ammo[0], std::min(20, s.weapons.weapons[0].ammo));
  // Hurt again, the nearer health pack gone: the other one.
  s.actors[0].health = 40;
  t = runUntilTaken(2, 10 * game::kTicksPerSecond);
  EXPECT_EQ(s.pickups[2].timesTaken, 1) << "after " << t << " ticks";
  EXPECT_FALSE(s.pickups[0].available);
  EXPECT_EQ(s.pickups[3].timesTaken, 0);
  m.tick();
  EXPECT_EQ(s.minds[0].behaviour, Behaviour::patrol);
}

// Hurt, with an enemy remembered but out of sight, a bot fetches health instead of chasing; out
// of rounds (every gun empty), it fetches rounds even with the enemy in sight (it cannot fight),
// facing it.
TEST(Behaviour, FetchesBeforeChasingAndWhenOutOfRounds) {
  Level level = room({-10, 0}, {{0, 0}}, {{{2, -4}, {0.5f, 2}}});
  addPickup(level, "health", 50, 30, {10, 10});
  addPickup(level, "ammo", 20, 30, {10, -10});
  {
    Match m(level, config(1));
    MatchState& s = m.state();
    faceThePlayer(m);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::attack);
    s.actors[1].ammo[0] = 0;
    s.actors[1].ammo[1] = 0;
    m.tick(kStill);
    EXPECT_EQ(s.minds[1].behaviour, Behaviour::fetch);
    EXPECT_EQ(s.minds[1].goal, (Vec2{10, -10}));
    for (int k = 0; k < 10; ++k)
      m.tick(kStill);
    EXPECT_LT(std::fabs(angleBetween(s.actors[1].aim, angleTo(s, 1, 0))), 0.2f);
  }
  {
    Match m(level, config(1));
    MatchState& s = m.state();
    faceThePlayer(m);
    // The player steps behind the wall's line of sight: the bot would chase; hurt, it fetches.
    s.world->setTransform(s.actors[0].body, {2, -12}, 0.0f);
    s.actors[1].health = 60;  // above kHurtFraction: it chases
    runUntil(m, 1, Behaviour::chase, game::kTicksPerSecond);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::chase);
    s.actors[1].health = 45;  // hurt, not by a hit it saw: no cover
    s.minds[1].health = 45;
    m.tick(kStill);
    EXPECT_EQ(s.minds[1].behaviour, Behaviour::fetch);
    EXPECT_EQ(s.minds[1].goal, (Vec2{10, 10}));
  }
}

// A bot fights with the gun that deals the most at the distance (expectedDamagePerTick) among
// those with rounds left. With the bundled table the rifle, at any distance; the rifle empty,
// the shotgun (it fires: its rounds go down, where before it pulled an empty trigger). With a
// shotgun that fires as fast as the rifle: the rifle 15 m away, the shotgun 4 m away, the rifle
// again once the shotgun is empty.
TEST(Behaviour, FightsWithTheGunThatDealsTheMost) {
  const auto inRange = [](MatchState& s, Match& m, Vec2 at) {
    s.world->setTransform(s.actors[0].body, at, 0);
    for (int k = 0; k <= game::kLookEvery; ++k)
      m.tick(kStill);
    return s.actors[1].input.weapon;
  };
  {
    Match m(room({-10, 0}, {{0, 0}}), config(1));
    MatchState& s = m.state();
    faceThePlayer(m);
    ASSERT_EQ(s.minds[1].behaviour, Behaviour::attack);
    EXPECT_EQ(inRange(s, m, {-8, 0}), 0);
    EXPECT_EQ(inRange(s, m, {-4, 0}), 0);
    s.actors[1].ammo[0] = 0;
    const int rounds = s.actors[1].ammo[1];
    for (int k = 0; k < 2 * game::kTicksPerSecond && s.actors[1].ammo[1] == rounds; ++k) {
      s.actors[0].health = s.tuning.health;  // the target stays
      m.tick(kStill);
    }
    EXPECT_EQ(s.minds[1].behaviour, Behaviour::attack);
    EXPECT_EQ(s.actors[1].input.weapon, 1);
    EXPECT_EQ(s.actors[1].ammo[1], rounds - 1);
  }
  game::WeaponTable fast = match_test_support::bundled();
  fast.weapons[1].cooldownTicks = fast.weapons[0].cooldownTicks;
  MatchConfig c = config(1);
  c.weapons = fast;
  Match m(room({-15, 0}, {{0, 0}}), c);
  MatchState& s = m.state();
  faceThePlayer(m);
  ASSERT_EQ(s.minds[1].behaviour, Behaviour::attack);
  const float radius = s.tuning.radius;
  EXPECT_GT(game::expectedDamagePerTick(fast.weapons[0], 15, radius),
            game::expectedDamagePerTick(fast.weapons[1], 15, radius));
  EXPECT_LT(game::expectedDamagePerTick(fast.weapons[0], 4, radius),
            game::expectedDamagePerTick(fast.weapons[1], 4, radius));
  EXPECT_EQ(inRange(s, m, {-15, 0}), 0);
  EXPECT_EQ(inRange(s, m, {-4, 0}), 1);
  s.actors[1].ammo[1] = 0;
  EXPECT_EQ(inRange(s, m, {-4, 0}), 0);
}

// investigate -> patrol when the sound is forgotten: kHeardFadeTicks after hearing it, and not
// before (it went there and looked around, finding nothing).
TEST(Behaviour, InvestigateFadesToPatrol) {
  Match m(room({6, 0}, {{-6, 0}}, {{{0, 0}, {0.5f, 6}}}), config(1));
  MatchState& s = m.state();
  m.tick(kShootNorth);
  // The player leaves at once, silently, to a place the bot cannot see (outside the room).
  s.world->setTransform(s.actors[0].body, {0, 30}, 0);
  m.tick(kStill);
  ASSERT_EQ(s.minds[1].behaviour, Behaviour::investigate);
  const std::int64_t heardAt = recall(s, 1, 0)->tick;
  const int t = runUntil(m, 1, Behaviour::patrol, 10 * game::kTicksPerSecond);
  EXPECT_EQ(s.minds[1].behaviour, Behaviour::patrol);
  EXPECT_EQ(s.minds[1].behaviourSince, heardAt + game::kHeardFadeTicks) << t;
}

// Two patrolling bots sent at each other down a one-tile corridor: the later one gives way
// (turns to a patrol point whose way leads off), the first gets through, and neither stays stuck.
TEST(Behaviour, PatrolGivesWayInACorridor) {
  // A 16 m corridor one metre wide along y = 0, from x = -8 to 8.
  Match m(room({-15, -15}, {{-7, 0}, {7, 0}}, {{{0, 1}, {8, 0.5f}}, {{0, -1}, {8, 0.5f}}}), [] {
    MatchConfig c = config(2);
    c.players = 0;
    return c;
  }());
  MatchState& s = m.state();
  s.minds[0].goal = {9, 0};
  s.minds[1].goal = {-9, 0};
  s.minds[0].goalTick = s.minds[1].goalTick = 0;
  bool gaveWay = false;
  int longestStuck = 0, t = 0;
  for (; t < 10 * game::kTicksPerSecond && rc::distance(position(s, 0), {9, 0}) > 0.75f; ++t) {
    m.tick();
    gaveWay |= s.minds[1].goal != Vec2{-9, 0};
    longestStuck = std::max({longestStuck, s.minds[0].stuckTicks, s.minds[1].stuckTicks});
    ASSERT_EQ(s.minds[0].goal, (Vec2{9, 0})) << t;  // the first never gives way
  }
  EXPECT_LT(rc::distance(position(s, 0), {9, 0}), 0.75f) << t;
  EXPECT_TRUE(gaveWay);
  EXPECT_LE(longestStuck, game::kTicksPerSecond);
}

// ---- Navigation -----------------------------------------------------------------------------

// Dijkstra over the same moves and costs (a step 70 straight or 99 diagonally, times 1 + 2 for
// each end in a costly cell, as navigation.h documents): the cost of the cheapest path, or -1.
std::int32_t dijkstra(const NavGrid& g, int start, int goal) {
  std::vector<std::int32_t> cost(static_cast<std::size_t>(g.size()),
                                 std::numeric_limits<std::int32_t>::max());
  using Item = std::pair<std::int32_t, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  cost[static_cast<std::size_t>(start)] = 0;
  open.push({0, start});
  while (!open.empty()) {
    const auto [c, at] = open.top();
    open.pop();
    if (c != cost[static_cast<std::size_t>(at)]) continue;
    if (at == goal) return c;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int x = g.x(at) + dx, y = g.y(at) + dy;
        if (x < 0 || y < 0 || x >= g.width || y >= g.height) continue;
        if (!g.passable(y * g.width + x)) continue;
        if (dx != 0 && dy != 0 &&
            (!g.passable(g.y(at) * g.width + x) || !g.passable(y * g.width + g.x(at))))
          continue;
        const int costlyEnds =
            ((g.flags[static_cast<std::size_t>(at)] & NavGrid::kCostly) != 0) +
            ((g.flags[static_cast<std::size_t>(y * g.width + x)] & NavGrid::kCostly) != 0);
        const std::int32_t next = c + (dx != 0 && dy != 0 ? 99 : 70) * (1 + 2 * costlyEnds);
        if (next < cost[static_cast<std::size_t>(y * g.width + x)]) {
          cost[static_cast<std::size_t>(y * g.width + x)] = next;
          open.push({next, y * g.width + x});
        }
      }
    }
  }
  return -1;
}

// Random cell flags for a grid: blocked with probability `blocked`, else costly with probability
// `costly`.
std::vector<std::uint8_t> randomFlags(rc::Random& rng, int cells, float blocked, float costly) {
  std::vector<std::uint8_t> flags(static_cast<std::size_t>(cells));
  for (std::uint8_t& f : flags)
    f = rng.uniform() < blocked ? NavGrid::kBlocked : rng.uniform() < costly ? NavGrid::kCostly : 0;
  return flags;
}

// A* finds a path exactly when Dijkstra does, of the same cost, on 150 random grids (1 x 1 to
// 40 x 40, 0 to 45% blocked, every other grid with 0 to 30% of its cells costly); every path is
// legal (passable cells, one step apart, no corner cut, from start to goal), and the same query
// gives the same path from a fresh search. The walk down a patrol point's distance field costs what
// Dijkstra says too.
TEST(Navigation, AStarAgainstDijkstraOnRandomGrids) {
  rc::Random rng(19);
  game::PathSearch search, fresh;
  std::vector<int> path, again;
  int found = 0, none = 0;
  for (int round = 0; round < 150; ++round) {
    const int w = 1 + static_cast<int>(rng.below(40)), h = 1 + static_cast<int>(rng.below(40));
    const float density = rng.uniform(0.0f, 0.45f);
    const float hurt = round % 2 == 1 ? rng.uniform(0.0f, 0.3f) : 0.0f;
    const NavGrid g = game::makeNavGrid(w, h, 0.5f, {}, randomFlags(rng, w * h, density, hurt));
    if (g.open.empty()) continue;
    for (int q = 0; q < 8; ++q) {
      const int a = g.open[rng.below(static_cast<std::uint32_t>(g.open.size()))];
      const int b = g.open[rng.below(static_cast<std::uint32_t>(g.open.size()))];
      const std::int32_t best = dijkstra(g, a, b);
      const bool ok = game::findPath(g, a, b, search, path);
      ASSERT_EQ(ok, best >= 0) << "round " << round;
      if (!ok) {
        ++none;
        EXPECT_TRUE(path.empty());
        continue;
      }
      ++found;
      ASSERT_EQ(game::pathCost(g, path), best) << "round " << round;
      ASSERT_EQ(path.front(), a);
      ASSERT_EQ(path.back(), b);
      for (std::size_t k = 0; k < path.size(); ++k) {
        ASSERT_TRUE(g.passable(path[k]));
        if (k == 0) continue;
        const int dx = g.x(path[k]) - g.x(path[k - 1]), dy = g.y(path[k]) - g.y(path[k - 1]);
        ASSERT_TRUE(std::abs(dx) <= 1 && std::abs(dy) <= 1 && (dx != 0 || dy != 0));
        if (dx != 0 && dy != 0) {
          ASSERT_TRUE(g.passable(path[k - 1] + dx));
          ASSERT_TRUE(g.passable(path[k - 1] + dy * g.width));
        }
      }
      ASSERT_TRUE(game::findPath(g, a, b, fresh, again));
      ASSERT_EQ(again, path);
      // Down a patrol point's distance field: as cheap as Dijkstra's too.
      const std::size_t point = rng.below(static_cast<std::uint32_t>(g.patrol.size()));
      const std::int32_t toPoint = dijkstra(g, a, g.patrol[point]);
      ASSERT_EQ(game::pathToPatrolPoint(g, a, point, search, again), toPoint >= 0);
      if (toPoint >= 0) {
        ASSERT_EQ(game::pathCost(g, again), toPoint);
        ASSERT_EQ(again.back(), g.patrol[point]);
      }
    }
  }
  EXPECT_GT(found, 800);
  EXPECT_GT(none, 20);
}

// Where a bot stands to look into a hurt zone (clearOfHurt), against a search of every cell on 60
// random grids with up to 95% of their cells costly, reaches of 1 to 3 cells: a point on a plain
// cell stays where it is; one on a costly cell goes to the centre of the nearest passable plain
// cell within reach, or, with none, stays.
TEST(Navigation, ClearOfHurtIsTheNearestPlainCell) {
  rc::Random rng(23);
  int moved = 0, stayed = 0, nowhere = 0;
  for (int round = 0; round < 60; ++round) {
    const int w = 1 + static_cast<int>(rng.below(30)), h = 1 + static_cast<int>(rng.below(30));
    const float density = rng.uniform(0.0f, 0.3f), hurt = rng.uniform(0.0f, 0.95f);
    const int reach = 1 + round % 3;
    const NavGrid g =
        game::makeNavGrid(w, h, 0.5f, {1, -2}, randomFlags(rng, w * h, density, hurt));
    for (int q = 0; q < 20; ++q) {
      const rc::Vec2 p{rng.uniform(0.5f, 1.5f + 0.5f * static_cast<float>(w)),
                       rng.uniform(-2.5f, -1.5f + 0.5f * static_cast<float>(h))};
      const int under = g.cellAt(p);
      const rc::Vec2 got = game::clearOfHurt(g, p, reach);
      if (!g.costly(under)) {
        ASSERT_EQ(got, p);
        ++stayed;
        continue;
      }
      float best = std::numeric_limits<float>::max();
      for (int c = 0; c < g.size(); ++c) {
        if (!g.passable(c) || g.costly(c) || std::abs(g.x(c) - g.x(under)) > reach ||
            std::abs(g.y(c) - g.y(under)) > reach)
          continue;
        best = std::min(best, rc::distanceSquared(g.center(c), p));
      }
      if (best == std::numeric_limits<float>::max()) {
        ASSERT_EQ(got, p);
        ++nowhere;
        continue;
      }
      const int at = g.cellAt(got);
      ASSERT_EQ(got, g.center(at));
      ASSERT_TRUE(g.passable(at) && !g.costly(at));
      ASSERT_EQ(rc::distanceSquared(got, p), best) << "round " << round;
      ++moved;
    }
  }
  EXPECT_GT(moved, 200);
  EXPECT_GT(stayed, 200);
  EXPECT_GT(nowhere, 3);
}

// A level's grid: cells whose centre is nearer a wall than the actor's radius plus the margin are
// blocked, those farther are free, and roomy from kNavSpan cells farther; a kill trigger's cells
// (and a margin round it) are hazards. A smoothed path round the trigger keeps to roomy cells.
TEST(Navigation, LevelGridFromWallsAndKillZones) {
  Level level = room({-15, -15}, {}, {{{5, 0}, {0.5f, 3}}});
  addTrigger(level, {-5, 5}, rc::makeBox(1, 1), {0, "kill"});
  Match m(level, config(0));
  const NavGrid& g = m.state().nav;
  EXPECT_EQ(g.width, 81);
  EXPECT_EQ(g.cell, 0.5f);
  const float clear = m.state().tuning.radius + game::kNavMargin;  // 0.4
  for (int c = 0; c < g.size(); ++c) {
    const Vec2 p = g.center(c);
    // Distance to the wall box [4.5, 5.5] x [-3, 3] and to the room's inside [-20, 20]^2.
    const float dx = std::max({4.5f - p.x, 0.0f, p.x - 5.5f});
    const float dy = std::max({-3.0f - p.y, 0.0f, p.y - 3.0f});
    const float toWall =
        std::min(std::hypot(dx, dy), 20.0f - std::max(std::fabs(p.x), std::fabs(p.y)));
    const std::uint8_t f = g.flags[static_cast<std::size_t>(c)];
    const bool blocked = (f & NavGrid::kBlocked) != 0, roomy = (f & NavGrid::kRoomy) != 0;
    if (toWall < clear - 1e-3f) {
      ASSERT_TRUE(blocked) << p.x << " " << p.y;
    }
    if (toWall > clear + 1e-3f) {
      ASSERT_FALSE(blocked) << p.x << " " << p.y;
    }
    // Roomy: clear by kNavSpan cells more (and no hazard).
    if (toWall < clear + game::kNavSpan * g.cell - 1e-3f) {
      ASSERT_FALSE(roomy) << p.x << " " << p.y;
    }
    if (toWall > clear + game::kNavSpan * g.cell + 1e-3f && (f & NavGrid::kHazard) == 0) {
      ASSERT_TRUE(roomy) << p.x << " " << p.y;
    }
  }
  EXPECT_NE(g.flags[static_cast<std::size_t>(g.cellAt({-5, 5}))] & NavGrid::kHazard, 0);
  EXPECT_NE(g.flags[static_cast<std::size_t>(g.cellAt({-5, 6.5f}))] & NavGrid::kHazard, 0);
  EXPECT_EQ(g.flags[static_cast<std::size_t>(g.cellAt({-5, 8}))], NavGrid::kRoomy);
  // One region: the whole room.
  EXPECT_EQ(g.region[static_cast<std::size_t>(g.cellAt({-15, -15}))],
            g.region[static_cast<std::size_t>(g.cellAt({15, 15}))]);
  // A smoothed path across the room avoids the pit: every leg is walkable, none crosses a hazard.
  game::PathSearch search;
  std::vector<int> cells;
  ASSERT_TRUE(game::findPath(g, g.cellAt({-9, 5}), g.cellAt({-1, 5}), search, cells));
  const std::vector<Vec2> points = game::smoothPath(g, {-9, 5}, cells, 24);
  Vec2 from{-9, 5};
  for (const Vec2 p : points) {
    EXPECT_TRUE(game::walkable(g, from, p) || (from == Vec2{-9, 5}));
    from = p;
  }
  EXPECT_LE(points.size(), 4u);  // round the pit, not cell by cell
}

// A hurt zone's cells: costly where the actor's disc kNavSpan cells wider would overlap it (a
// closed form: the distance from the cell's centre to the zone's box against the actor's radius,
// the margin and kNavSpan cells), never roomy, and still passable. A route past a short zone
// goes round it (no costly cell; its smoothed walk keeps the actor and its margin out); one
// across a zone from wall to wall crosses it straight, through as few costly cells as the zone
// and its margins are thick.
TEST(Navigation, HurtZonesCostMoreAndAreWalkedRound) {
  Level level = room({-15, -15}, {});
  addTrigger(level, {-8, 0}, rc::makeBox(1, 3), {0, "hurt"});  // short: a way round
  addTrigger(level, {8, 0}, rc::makeBox(1, 20), {0, "hurt"});  // from wall to wall
  Match m(level, config(0));
  const NavGrid& g = m.state().nav;
  const float clear = m.state().tuning.radius + game::kNavMargin;
  const float reach = clear + game::kNavSpan * g.cell;
  auto toBox = [](Vec2 p, Vec2 at, Vec2 half) {
    const float dx = std::max(std::fabs(p.x - at.x) - half.x, 0.0f);
    const float dy = std::max(std::fabs(p.y - at.y) - half.y, 0.0f);
    return std::hypot(dx, dy);
  };
  int costly = 0;
  for (int c = 0; c < g.size(); ++c) {
    const Vec2 p = g.center(c);
    const float d = std::min(toBox(p, {-8, 0}, {1, 3}), toBox(p, {8, 0}, {1, 20}));
    const std::uint8_t f = g.flags[static_cast<std::size_t>(c)];
    if ((f & NavGrid::kBlocked) != 0) continue;
    if (d < reach - 1e-3f) {
      ASSERT_NE(f & NavGrid::kCostly, 0) << p.x << " " << p.y;
      ASSERT_EQ(f & NavGrid::kRoomy, 0) << p.x << " " << p.y;
      ++costly;
    }
    if (d > reach + 1e-3f) {
      ASSERT_EQ(f & NavGrid::kCostly, 0) << p.x << " " << p.y;
    }
    ASSERT_TRUE(g.passable(c));
  }
  EXPECT_GT(costly, 500);
  for (const int c : g.patrol)
    EXPECT_FALSE(g.costly(c)) << g.center(c).x << " " << g.center(c).y;

  game::PathSearch search;
  std::vector<int> cells;
  auto costlyCells = [&g](const std::vector<int>& path) {
    return std::count_if(path.begin(), path.end(), [&g](int c) { return g.costly(c); });
  };
  // Past the short zone: round it, and the smoothed walk keeps clear of it.
  ASSERT_TRUE(game::findPath(g, g.cellAt({-12, 0}), g.cellAt({-4, 0}), search, cells));
  EXPECT_EQ(costlyCells(cells), 0);
  EXPECT_LT(game::pathCost(g, cells), 3 * game::octileDistance(g, cells.front(), cells.back()));
  Vec2 from{-12, 0};
  for (const Vec2 p : game::smoothPath(g, from, cells, 24)) {
    for (float t = 0.0f; t <= 1.0f; t += 1.0f / 64.0f)
      EXPECT_GT(toBox(from + t * (p - from), {-8, 0}, {1, 3}), clear - 1e-3f);
    from = p;
  }
  // Across the wall-to-wall zone: straight through it, through as few costly cells as there are
  // centres within the reach of it on a line across (seven: x = 6.5 to 9.5).
  ASSERT_TRUE(game::findPath(g, g.cellAt({3, 5}), g.cellAt({13, 5}), search, cells));
  int thick = 0;
  for (float x = 3.0f; x <= 13.0f; x += g.cell)
    thick += toBox({x, 5}, {8, 0}, {1, 20}) < reach;
  EXPECT_EQ(thick, 7);
  EXPECT_EQ(costlyCells(cells), thick);
  for (const int c : cells)
    EXPECT_NEAR(g.center(c).y, 5.0f, 1e-3f);
}

// The bundled arena's hurt zone, 16 bots for a minute in each of six matches (seeds 1-6): the
// actors inside it (the query the rules hurt them by) add up to at most a quarter of an
// actor-second a match. Before the grid knew hurt zones, seeds 1-3 spent 10-16 actor-seconds in
// it every three minutes. These six: 17 actor-ticks; 93 (58 in one match: two bots fighting at the
// zone's edge, one then taking cover there) before a fighting bot in its margin walked out of
// it; 153 before bots kept their steps off the grid and their stale routes out of it (strafing,
// a chase's end, a walk pushed off its route), 205 before a grenade's step back did.
TEST(Navigation, BotsKeepOutOfTheArenasHurtZone) {
  const game::Level arena = game::loadLevel(level_test::levelPath("arena.tmj"));
  std::int64_t inside = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    MatchConfig c = config(16);
    c.seed = seed;
    c.testHook = [&inside](MatchState& s) {
      std::vector<bool> in;
      for (const game::BuiltTrigger& t : s.built.triggers) {
        if (t.action != "hurt") continue;
        game::actorsInside(s, t.body, in);
        for (std::size_t i = 0; i < in.size(); ++i)
          inside += in[i] && s.actors[i].alive;
      }
    };
    Match m(arena, c);
    ASSERT_FALSE(m.state().built.triggers.empty());
    for (int t = 0; t < 60 * game::kTicksPerSecond; ++t)
      m.tick();
  }
  EXPECT_LE(inside, 6 * game::kTicksPerSecond / 4);
}

// The bundled maze: a bot sent from its spawn to the player's walks its path there, within 30%
// over the path's length at full speed, never stuck for long.
TEST(Navigation, BotCrossesTheMaze) {
  game::Level maze = game::loadLevel(level_test::levelPath("maze.tmj"));
  Vec2 goal{};
  for (const game::LevelSpawn& spawn : maze.spawns)
    if (spawn.kind == game::SpawnKind::player) goal = spawn.position;
  MatchConfig c = config(1);
  c.players = 0;
  Match m(std::move(maze), c);
  MatchState& s = m.state();
  std::vector<int> cells;
  game::PathSearch search;
  ASSERT_TRUE(game::findPath(s.nav, game::nearestPassable(s.nav, position(s, 0)),
                             game::nearestPassable(s.nav, goal), search, cells));
  const float metres =
      static_cast<float>(game::pathCost(s.nav, cells)) / game::kStraightCost * s.nav.cell;
  EXPECT_GT(metres, 40.0f);
  s.minds[0].goal = goal;
  s.minds[0].goalTick = 0;
  const int limit = static_cast<int>(1.3f * metres / 5.0f * game::kTicksPerSecond);
  int t = 0;
  int longestStuck = 0;
  while (rc::distance(position(s, 0), goal) > 0.75f && t < limit) {
    m.tick();
    longestStuck = std::max(longestStuck, s.minds[0].stuckTicks);
    ASSERT_EQ(s.minds[0].behaviour, Behaviour::patrol);
    ++t;
  }
  EXPECT_LT(rc::distance(position(s, 0), goal), 0.75f) << t << " ticks for " << metres << " m";
  EXPECT_LT(longestStuck, game::kTicksPerSecond / 2);
}

// On the bundled tile levels, the grid knows the inside of merged tile walls (blocked, and opaque
// away from their edges), every patrol point is in the main region, and the walls the grid
// proves are in the way are there: for 3000 random pairs of open cells, when pointInsideWall
// finds a point the ray between them meets a static body; and it answers most blocked pairs.
TEST(Navigation, TileInsidesAndTheSightShortcut) {
  for (const char* name : {"maze", "corridors"}) {
    game::Level level = game::loadLevel(level_test::levelPath(std::string(name) + ".tmj"));
    MatchConfig c = config(0);
    c.players = 0;
    Match m(std::move(level), c);
    const MatchState& s = m.state();
    const NavGrid& g = s.nav;
    int opaque = 0;
    for (int cell = 0; cell < g.size(); ++cell)
      opaque += (g.flags[static_cast<std::size_t>(cell)] & NavGrid::kOpaque) != 0;
    EXPECT_GT(opaque, g.size() / 10) << name;
    // The maze's outer wall: its tiles' centres are inside it.
    const int corner = g.cellAt(s.level.settings.bounds.lower + Vec2{0.5f, 0.5f});
    EXPECT_NE(g.flags[static_cast<std::size_t>(corner)] & NavGrid::kOpaque, 0) << name;
    const std::int32_t main = g.region[static_cast<std::size_t>(g.patrol.front())];
    for (const std::int32_t p : g.patrol) {
      EXPECT_EQ(g.region[static_cast<std::size_t>(p)], main) << name;
    }
    rc::Random rng(7);
    int blocked = 0, answered = 0;
    for (int k = 0; k < 3000; ++k) {
      const Vec2 a = g.center(g.open[rng.below(static_cast<std::uint32_t>(g.open.size()))]);
      const Vec2 b = g.center(g.open[rng.below(static_cast<std::uint32_t>(g.open.size()))]);
      const bool hits = s.world->castRay(a, b - a, game::staticSolids(*s.world)).has_value();
      const std::optional<Vec2> inside = game::pointInsideWall(g, a, b);
      blocked += hits;
      answered += inside.has_value();
      if (inside) {
        ASSERT_TRUE(hits) << name << " " << a.x << "," << a.y << " " << b.x << "," << b.y;
      }
    }
    EXPECT_GT(answered, blocked / 2) << name;
  }
}

// ---- State ----------------------------------------------------------------------------------

// Everything a bot keeps enters the match's hash: a memory entry, the route, the behaviour, the
// last tick's sounds.
TEST(Bots, MindsAndSoundsAreHashed) {
  Match m(room({-10, 0}, {{0, 0}}), config(1));
  m.tick();
  const std::uint64_t h = m.hash();
  game::BotMind& mind = m.state().minds[1];
  auto changes = [&](auto&& poke) {
    const game::BotMind saved = mind;
    const std::vector<game::Sound> sounds = m.state().sounds;
    poke();
    const bool changed = m.hash() != h;
    mind = saved;
    m.state().sounds = sounds;
    EXPECT_EQ(m.hash(), h);
    return changed;
  };
  EXPECT_TRUE(changes([&] { mind.memory[3].strength += 1; }));
  EXPECT_TRUE(changes([&] { mind.route.points[23].y += 1; }));
  EXPECT_TRUE(changes([&] { mind.behaviour = Behaviour::flee; }));
  EXPECT_TRUE(changes([&] { mind.stuckTicks += 1; }));
  EXPECT_TRUE(changes([&] { m.state().sounds.push_back({}); }));
}

}  // namespace bots_test
