// The contact solver (physics/solver.cpp, physics/contact_solver.cpp) in scenes where several
// contacts act at once, against closed forms: rows of touching balls struck by others keep
// their momentum and never gain energy; a lone pair bounces as Newton's law says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "physics/random.h"
#include "physics/world.h"

namespace {

using rc::BodyId;
using rc::Vec2;

// Kinetic energy (linear and rotational) and linear momentum of some bodies, in double.
struct Motion {
  double energy = 0, px = 0, py = 0;
};
Motion motionOf(const rc::World& w, const std::vector<BodyId>& bodies) {
  Motion m;
  for (BodyId b : bodies) {
    const Vec2 v = w.linearVelocity(b);
    const double mass = w.mass(b), spin = w.angularVelocity(b);
    m.energy += 0.5 * mass * (static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y) +
                0.5 * static_cast<double>(w.rotationalInertia(b)) * spin * spin;
    m.px += mass * v.x;
    m.py += mass * v.y;
  }
  return m;
}

// A row of `length` touching balls of radius 0.5 m from x = 0 along x, struck by `strikers`
// touching balls coming from the left at `speed`, the front one `gap` from the row (0: born
// touching it). No gravity, no friction, no sleeping. Masses 1 each (density 1 / pi), or with
// `mixed` every other ball of the row three times heavier.
struct RowScene {
  int length = 2, strikers = 1;
  bool mixed = false;
  float restitution = 1, speed = 3, gap = 0.3f;
};
struct Row {
  rc::World world;
  std::vector<BodyId> balls;  // strikers first, left to right
};
Row makeRow(const RowScene& s) {
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.enableSleep = false;
  Row row{rc::World(def), {}};
  auto ball = [&](float x, float speed, float density) {
    rc::BodyDef bd;
    bd.type = rc::BodyType::dynamicBody;
    bd.position = {x, 0};
    bd.linearVelocity = {speed, 0};
    const BodyId b = row.world.createBody(bd);
    rc::ShapeDef sd;
    sd.friction = 0;
    sd.restitution = s.restitution;
    sd.density = density * 4.0f / rc::kPi;  // a ball of radius 0.5 weighs `density` kg
    row.world.createShape(b, rc::makeCircle({}, 0.5f), sd);
    row.balls.push_back(b);
  };
  for (int i = 0; i < s.strikers; ++i)
    ball(-s.gap - static_cast<float>(s.strikers - i), s.speed, 1.0f);
  for (int i = 0; i < s.length; ++i)
    ball(static_cast<float>(i), 0.0f, s.mixed && i % 2 == 1 ? 3.0f : 1.0f);
  return row;
}

std::string describe(const RowScene& s) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "row %d, %d striker(s), %s masses, e %.1f, %s", s.length,
                s.strikers, s.mixed ? "mixed" : "unit", static_cast<double>(s.restitution),
                s.gap == 0 ? "born touching" : "0.3 m away");
  return buf;
}

// Rows of 2 to 8 touching balls struck by one ball and by two (themselves touching), of equal
// masses and of masses 1 and 3, restitution 1, 0.5 and 0, the strikers born touching the row or
// 0.3 m away, at 3 m/s: over 4 s, momentum as it went in and kinetic energy never above it.
// The tolerances are float rounding: energy within 1e-6 of the input (velocities are floats,
// each square good to about 1e-7), momentum within 1e-5 (ten floats summed).
TEST(Restitution, StruckRowKeepsMomentumAndNeverGainsEnergy) {
  double worstRise = 0, endSum = 0;
  int runs = 0;
  for (int length = 2; length <= 8; ++length) {
    for (int strikers : {1, 2}) {
      for (bool mixed : {false, true}) {
        for (float e : {1.0f, 0.5f, 0.0f}) {
          for (float gap : {0.0f, 0.3f}) {
            const RowScene scene{length, strikers, mixed, e, 3.0f, gap};
            Row row = makeRow(scene);
            const Motion in = motionOf(row.world, row.balls);
            double highest = in.energy;
            for (int i = 0; i < 240; ++i) {
              row.world.step(1.0f / 60.0f);
              highest = std::max(highest, motionOf(row.world, row.balls).energy);
            }
            const Motion out = motionOf(row.world, row.balls);
            const std::string what = describe(scene);
            EXPECT_LE(highest, in.energy * (1.0 + 1e-6)) << what;
            EXPECT_NEAR(out.px, in.px, 1e-5 * in.px) << what;
            EXPECT_NEAR(out.py, 0.0, 1e-5 * in.px) << what;
            worstRise = std::max(worstRise, highest / in.energy - 1.0);
            endSum += out.energy / in.energy;
            ++runs;
          }
        }
      }
    }
  }
  std::printf("%d rows: energy at most %.3g above the input, on average %.3f of it at the end\n",
              runs, worstRise, endSum / runs);
}

// A ball struck into a row of two equal touching balls at restitution 1 comes out as a
// Newton's cradle: the first two stop and the last leaves at the striker's speed. Not so when
// the striker is born touching the row (-0.61, 1.22 and 2.39 m/s, 0.84 of the energy), nor for
// longer rows (the test above: momentum kept, energy lost): within one substep the solve passes
// an impact down touching balls as one inelastic collision, and restitution reverses only the
// contacts that were approaching when the step began, here the striker's alone.
TEST(Restitution, BallStruckIntoARowOfTwoIsANewtonsCradle) {
  Row row = makeRow({2, 1, false, 1.0f, 3.0f, 0.3f});
  for (int i = 0; i < 120; ++i)
    row.world.step(1.0f / 60.0f);
  const float expected[] = {0, 0, 3};
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(row.world.linearVelocity(row.balls[k]).x, expected[k], 1e-4f) << "ball " << k;
}

// A lone pair, head on: Newton's law in closed form, m1 at v into m2 at rest,
// v1 = (m1 - e m2) v / (m1 + m2), v2 = (1 + e) m1 v / (m1 + m2). Restitution's energy budget
// (a group gives back at most e^2 of what its contacts took out) never cuts a lone pair's
// bounce. The tolerance: float rounding of velocities of a few m/s.
TEST(Restitution, LonePairBouncesAsNewtonsLawSays) {
  for (bool mixed : {false, true}) {
    for (float e : {0.0f, 0.5f, 0.8f, 1.0f}) {
      // The striker and a row of one; with `mixed` the row's ball is the striker's mass (the
      // first of a mixed row is light), so a heavier target is built by hand.
      Row row = makeRow({1, 1, false, e, 3.0f, 0.3f});
      float m2 = 1.0f;
      if (mixed) {
        rc::World& w = row.world;
        w.destroyBody(row.balls[1]);
        rc::BodyDef bd;
        bd.type = rc::BodyType::dynamicBody;
        const BodyId heavy = w.createBody(bd);
        rc::ShapeDef sd;
        sd.friction = 0;
        sd.restitution = e;
        sd.density = 3.0f * 4.0f / rc::kPi;
        w.createShape(heavy, rc::makeCircle({}, 0.5f), sd);
        row.balls[1] = heavy;
        m2 = 3.0f;
      }
      for (int i = 0; i < 120; ++i)
        row.world.step(1.0f / 60.0f);
      const float v = 3.0f, m1 = 1.0f;
      const float v1 = (m1 - e * m2) * v / (m1 + m2), v2 = (1 + e) * m1 * v / (m1 + m2);
      const std::string what = "e " + std::to_string(e) + (mixed ? ", target 3x" : "");
      EXPECT_NEAR(row.world.linearVelocity(row.balls[0]).x, v1, 1e-4f) << what;
      EXPECT_NEAR(row.world.linearVelocity(row.balls[1]).x, v2, 1e-4f) << what;
    }
  }
}

// Bodies born touching in two dimensions: a hexagonal cluster of touching balls or a grid of
// touching boxes (friction 0 or up to 1, densities 0.5 to 3, some moving and spinning at birth),
// struck by one or two balls at 2 to 15 m/s, restitution 1 or 0.5, no gravity, for 5 s: the
// kinetic energy at its highest, over the input, and at the end.
struct ClusterRun {
  bool boxes = false;
  float restitution = 0;
  double highest = 0, end = 0;
};
ClusterRun strikeCluster(std::uint64_t seed) {
  rc::Random rng(seed);
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.enableSleep = false;
  rc::World w(def);
  ClusterRun run;
  run.restitution = rng.below(2) ? 1.0f : 0.5f;
  run.boxes = rng.below(3) == 0;
  const int nx = 2 + static_cast<int>(rng.below(5));
  const int ny = 1 + static_cast<int>(rng.below(4));
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      rc::BodyDef bd;
      bd.type = rc::BodyType::dynamicBody;
      const auto x = static_cast<float>(i), y = static_cast<float>(j);
      bd.position =
          run.boxes ? Vec2{x, y} : Vec2{x + 0.5f * static_cast<float>(j % 2), 0.8660254f * y};
      if (rng.below(3) == 0) bd.linearVelocity = rng.inBox({-6, -6}, {6, 6});
      if (run.boxes && rng.below(3) == 0) bd.angularVelocity = rng.uniform(-5, 5);
      const BodyId b = w.createBody(bd);
      rc::ShapeDef sd;
      sd.friction = rng.below(2) ? 0.0f : rng.uniform(0, 1);
      sd.restitution = run.restitution;
      sd.density = rng.uniform(0.5f, 3.0f);
      if (run.boxes)
        w.createShape(b, rc::makeBox(0.5f, 0.5f), sd);
      else
        w.createShape(b, rc::makeCircle({}, 0.5f), sd);
    }
  }
  const int strikers = 1 + static_cast<int>(rng.below(2));
  for (int k = 0; k < strikers; ++k) {
    rc::BodyDef bd;
    bd.type = rc::BodyType::dynamicBody;
    bd.position = {-2.0f - static_cast<float>(k),
                   rng.uniform(-0.5f, 0.8f * static_cast<float>(ny))};
    bd.linearVelocity = {rng.uniform(2, 15), rng.uniform(-1, 1)};
    const BodyId b = w.createBody(bd);
    rc::ShapeDef sd;
    sd.friction = 0;
    sd.restitution = run.restitution;
    w.createShape(b, rc::makeCircle({}, 0.5f), sd);
  }
  const double start = w.energy();
  run.highest = start;
  for (int i = 0; i < 300; ++i) {
    w.step(1.0f / 60.0f);
    run.highest = std::max(run.highest, w.energy());
  }
  run.highest /= start;
  run.end = w.energy() / start;
  return run;
}

// Struck clusters never gain energy, over 200 seeds (a third of them boxes). The tolerance as
// for the rows (a cluster has up to 22 bodies).
TEST(Restitution, StruckClustersNeverGainEnergy) {
  double highest = 0, endSum = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const ClusterRun run = strikeCluster(seed);
    EXPECT_LE(run.highest, 1.0 + 1e-6)
        << "seed " << seed << (run.boxes ? ", boxes" : ", balls") << ", e " << run.restitution;
    highest = std::max(highest, run.highest);
    endSum += run.end;
  }
  std::printf("200 clusters: energy at most %.7f of the input, on average %.3f of it at the end\n",
              highest, endSum / 200.0);
}

}  // namespace

// ------------------------------------------------------------------ bodies born overlapping

// A pile of `count` 1 m circles or boxes born at one point (or within `spread` of it), floating
// or on a ground whose top is at y = 0, stepped for `steps` steps: the fastest any body moved,
// the highest any centre rose, when every contact first came within the slop (-1: never), and
// the first step at which a body was asleep while a contact was deeper than the slop (-1:
// never). The push-out speed is WorldDef's default, 3 m/s.
struct PileRun {
  float fastest = 0, top = -1e9f;
  int withinSlop = -1, asleepOverlapping = -1;
};
PileRun pushApart(int count, bool boxes, float spread, bool onGround, int steps) {
  rc::WorldDef def;
  if (!onGround) def.gravity = {0, 0};
  rc::World w(def);
  if (onGround) w.createShape(w.createBody({}), rc::makeBox(500, 10, {0, -10}));
  rc::Random rng(7);
  std::vector<BodyId> pile;
  for (int i = 0; i < count; ++i) {
    rc::BodyDef bd;
    bd.type = rc::BodyType::dynamicBody;
    bd.position = Vec2{0, onGround ? 0.5f : 0.0f} + rng.inBox({-spread, -spread}, {spread, spread});
    pile.push_back(w.createBody(bd));
    if (boxes)
      w.createShape(pile.back(), rc::makeBox(0.5f, 0.5f));
    else
      w.createShape(pile.back(), rc::makeCircle({}, 0.5f));
  }
  PileRun run;
  for (int i = 0; i < steps; ++i) {
    w.step(1.0f / 60.0f);
    bool asleep = false;
    for (BodyId b : pile) {
      run.fastest = std::max(run.fastest, rc::length(w.linearVelocity(b)));
      run.top = std::max(run.top, w.position(b).y);
      asleep = asleep || !w.isAwake(b);
    }
    float deepest = 0;
    for (const rc::World::ContactPointView& p : w.contactPoints())
      deepest = std::min(deepest, p.separation);
    if (run.withinSlop < 0 && deepest >= -rc::kLinearSlop) run.withinSlop = i;
    if (run.asleepOverlapping < 0 && asleep && deepest < -rc::kLinearSlop)
      run.asleepOverlapping = i;
  }
  return run;
}

std::string describe(int count, bool boxes, float spread, bool onGround) {
  return std::to_string(count) + (boxes ? " boxes" : " circles") +
         (spread == 0 ? " at one point" : " within 1 mm") + (onGround ? " on the ground" : "");
}

// Two circles or boxes born at one point are pushed apart no faster than the push-out speed
// (their centres part at 2.83 m/s at most: the soft contact's bias, capped at 3 m/s), come apart
// within 2 s, and do not fall asleep while still overlapping past the slop (the push-out moves
// them by their positions, and at rest at the end of every step they look still). On the
// ground the one pushed up may fall off the other: up to the cap plus a fall of 1 m.
TEST(OverlapRecovery, CoincidentPairSeparatesAtThePushOutSpeed) {
  const float cap = rc::WorldDef{}.maxPushoutSpeed;
  for (bool boxes : {false, true}) {
    for (bool onGround : {false, true}) {
      const PileRun run = pushApart(2, boxes, 0.0f, onGround, 600);
      const std::string what = describe(2, boxes, 0.0f, onGround);
      EXPECT_LE(run.fastest, onGround ? cap + std::sqrt(2.0f * 10.0f * 1.0f) : cap) << what;
      EXPECT_GE(run.withinSlop, 0) << what;
      EXPECT_LT(run.withinSlop, 120) << what;
      EXPECT_EQ(run.asleepOverlapping, -1) << what;
    }
  }
}

// Piles of 10 and 50 circles or boxes born at one point or within 1 mm of it, floating: no body
// moves faster than the push-out speed (3 m/s), within 30 s every contact is within the slop,
// and no body falls asleep before. A body overlapping k others is pushed out of each at 1/k of
// the speed, and shapes born at one point are pushed apart as if each were a fraction of a
// millimetre from it in a direction of its own; 50 bodies take about 11 s to come apart.
TEST(OverlapRecovery, FloatingPilesSpreadNoFasterThanThePushOut) {
  const float cap = rc::WorldDef{}.maxPushoutSpeed;
  for (int count : {10, 50}) {
    for (bool boxes : {false, true}) {
      for (float spread : {0.0f, 0.001f}) {
        const PileRun run = pushApart(count, boxes, spread, false, 1800);
        const std::string what = describe(count, boxes, spread, false);
        std::printf("%s: fastest %.2f m/s, within the slop after %d steps\n", what.c_str(),
                    static_cast<double>(run.fastest), run.withinSlop);
        EXPECT_LE(run.fastest, cap) << what;
        EXPECT_GE(run.withinSlop, 0) << what;
        EXPECT_EQ(run.asleepOverlapping, -1) << what;
      }
    }
  }
}

// The same piles on the ground. Bodies pushed up onto the pile may fall back down, so the bound
// is the push-out speed plus a fall from the highest point any centre reached, and the pile
// rises no higher than a pyramid of its bodies (10 rows for 50). The circles do not sleep
// overlapping past the slop. (Boxes at rest under the pile carry it on soft contacts 6 to 16 mm
// deep, where such a load settles (see World.HeavyBoxOnTwoLightBoxesHolds), and sleep there, as
// a tall pyramid does.)
TEST(OverlapRecovery, PilesOnTheGroundSpreadNoFasterThanThePushOutAndAFall) {
  const float cap = rc::WorldDef{}.maxPushoutSpeed;
  for (int count : {10, 50}) {
    int rows = 1;
    while (rows * (rows + 1) / 2 < count)
      ++rows;
    for (bool boxes : {false, true}) {
      for (float spread : {0.0f, 0.001f}) {
        const PileRun run = pushApart(count, boxes, spread, true, 1800);
        const std::string what = describe(count, boxes, spread, true);
        const float fall = std::sqrt(2.0f * 10.0f * std::max(run.top - 0.5f, 0.0f));
        std::printf("%s: fastest %.2f m/s, highest centre %.2f m\n", what.c_str(),
                    static_cast<double>(run.fastest), static_cast<double>(run.top));
        EXPECT_LE(run.top, static_cast<float>(rows) - 0.5f) << what;
        EXPECT_LE(run.fastest, cap + fall) << what;
        if (!boxes) {
          EXPECT_EQ(run.asleepOverlapping, -1) << what;
        }
      }
    }
  }
}
