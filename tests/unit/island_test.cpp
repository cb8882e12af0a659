// Islands and sleep (physics/island.cpp): sleeping islands wake on contact, forces and the
// queries that ask; the rest stay asleep.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "physics/random.h"
#include "physics/world.h"
#include "support/world_scenes.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace island_test {

using rc::BodyId;
using rc::Vec2;
using rc::testing::dynamicAt;
using rc::testing::finiteState;
using rc::testing::ground;
using rc::testing::restingRow;
using rc::testing::stepWatchingEnergy;

// Sleeping bodies cost no step time and keep their state; a body dropped on them wakes them.
TEST(World, SleepingIslandsWakeOnContact) {
  rc::World w;
  const std::vector<BodyId> row = restingRow(w, 5, 2.0f);
  EXPECT_EQ(w.awakeBodyCount(), 0);  // five islands of one, all asleep
  auto positions = [&] {
    std::vector<double> out;
    for (BodyId body : row)
      for (double x : w.precisePosition(body))
        out.push_back(x);
    return out;
  };
  const std::vector<double> asleep = positions();
  for (int i = 0; i < 30; ++i)
    w.step(1.0f / 60.0f);
  EXPECT_EQ(positions(), asleep);  // nothing moved
  // A ball dropped on box 2 wakes box 2 only.
  BodyId ball = w.createBody(dynamicAt({4.0f, 3.0f}));
  w.createShape(ball, rc::makeCircle({}, 0.25f));
  bool woke = false;
  for (int i = 0; i < 60 && !woke; ++i) {
    w.step(1.0f / 60.0f);
    woke = w.isAwake(row[2]);
  }
  EXPECT_TRUE(woke);
  EXPECT_FALSE(w.isAwake(row[0]));
  EXPECT_FALSE(w.isAwake(row[4]));
}

// What wakes a sleeping island besides a contact: a force or torque (also on the next step),
// a query that asks (Wake::yes), and not a query that does not, nor a force rejected as NaN.
TEST(World, ForcesAndAskingQueriesWakeSleepers) {
  rc::World w;
  const std::vector<BodyId> row = restingRow(w, 4, 3.0f);
  ASSERT_EQ(w.awakeBodyCount(), 0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(w.applyForceToCenter(row[0], {nan, 0}), rc::InvalidDefinition);
  EXPECT_THROW(w.applyTorque(row[0], nan), rc::InvalidDefinition);
  EXPECT_EQ(w.awakeBodyCount(), 0);  // a rejected call changes nothing
  // A force wakes the body it pushes, and it moves in the next step.
  w.applyForceToCenter(row[0], {200, 0});
  EXPECT_TRUE(w.isAwake(row[0]));
  EXPECT_EQ(w.awakeBodyCount(), 1);
  const float x0 = w.position(row[0]).x;
  w.step(1.0f / 60.0f);
  EXPECT_GT(w.position(row[0]).x, x0);
  w.applyTorque(row[1], 5.0f);
  EXPECT_TRUE(w.isAwake(row[1]));
  // Queries: the plain ones leave sleepers asleep, the asking ones wake what they report only.
  const rc::AABB around2{{5.5f, 0.2f}, {6.5f, 0.8f}};  // box 2 spans x 5.5..6.5
  EXPECT_EQ(w.overlapAABB(around2).size(), 1u);        // box 2 (the ground's top is y = 0)
  EXPECT_FALSE(w.isAwake(row[2]));
  EXPECT_EQ(w.overlapAABB(around2, {}, rc::World::Wake::yes).size(), 1u);
  EXPECT_TRUE(w.isAwake(row[2]));
  EXPECT_FALSE(w.isAwake(row[3]));
  ASSERT_TRUE(w.castRay({9, 5}, {0, -10}).has_value());
  EXPECT_FALSE(w.isAwake(row[3]));
  const auto hit = w.castRay({9, 5}, {0, -10}, {}, rc::World::Wake::yes);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, row[3]);
  EXPECT_TRUE(w.isAwake(row[3]));
}

// Bodies created inside each other do not fall asleep there. A crowd born at one point is
// pushed apart slower than the sleep tolerance when each body is in hundreds of overlaps; here
// the tolerance is raised to 2 m/s so that thirty circles are "still" from the first step, and
// they must still be awake while any contact is deeper than a quarter of a circle's diameter
// (island.cpp's bound), and asleep once apart. Before the bound they slept at step 30 fully on
// top of each other (0.5 m deep).
TEST(World, BodiesInsideEachOtherStayAwakeUntilPushedOut) {
  rc::WorldDef def;
  def.gravity = {0, 0};
  def.linearSleepTolerance = 2.0f;
  def.angularSleepTolerance = 10.0f;
  rc::World w(def);
  for (int i = 0; i < 30; ++i)
    w.createShape(w.createBody(dynamicAt({0, 0})), rc::makeCircle({}, 0.25f));
  auto deepest = [&] {
    float d = 0.0f;
    for (const rc::World::ContactPointView& p : w.contactPoints())
      d = std::max(d, -p.separation);
    return d;
  };
  int asleepAt = -1;
  for (int k = 1; k <= 600 && asleepAt < 0; ++k) {
    w.step(1.0f / 60.0f);
    if (w.awakeBodyCount() == 0) {
      asleepAt = k;  // the contacts are as the step's sleep test saw them
      EXPECT_LE(deepest(), 0.25f * 0.5f) << "asleep at step " << k;
    }
  }
  EXPECT_GT(asleepAt, 30);  // not at the first chance (timeToSleep: 0.5 s)
  EXPECT_GT(asleepAt, 0) << "never slept";
}

// Bodies drifting at constant speed (no gravity) fall asleep after timeToSleep (0.5 s, 30
// steps) while under the tolerances, after a third of it (10 steps) while under a tenth of both,
// and never above them. Counted exactly: still time adds dt or 3 dt a step, in float.
TEST(World, StillerBodiesSleepSooner) {
  rc::WorldDef def;
  def.gravity = {0, 0};
  rc::World w(def);
  const float lin = def.linearSleepTolerance, ang = def.angularSleepTolerance;
  struct Drift {
    Vec2 v;
    float w;
    int sleepsAt;  // -1: never
  };
  auto stepsFor = [&](float perStep) {  // the first step whose still time reaches timeToSleep
    float t = 0;
    int k = 0;
    while (t < def.timeToSleep)
      t += perStep, ++k;
    return k;
  };
  const float dt = 1.0f / 60.0f;
  const int quick = stepsFor(3.0f * dt), slow = stepsFor(dt);
  EXPECT_EQ(quick, 10);
  EXPECT_EQ(slow, 30);
  const std::vector<Drift> drifts = {
      {{0, 0}, 0, quick},            // still
      {{0.09f * lin, 0}, 0, quick},  // under a tenth
      {{0, -0.06f * lin}, 0.09f * ang, quick},
      {{0.11f * lin, 0}, 0, slow},  // over a tenth, under the tolerance
      {{0, 0}, 0.11f * ang, slow},
      {{0.05f * lin, 0.05f * lin}, 0.5f * ang, slow},
      {{0.99f * lin, 0}, 0, slow},
      {{1.01f * lin, 0}, 0, -1},  // over it
      {{0, 0}, 1.01f * ang, -1},
  };
  std::vector<BodyId> bodies;
  for (std::size_t i = 0; i < drifts.size(); ++i) {
    bodies.push_back(w.createBody(dynamicAt({10.0f * static_cast<float>(i), 0})));
    w.createShape(bodies.back(), rc::makeBox(0.5f, 0.5f));
    w.setLinearVelocity(bodies.back(), drifts[i].v);
    w.setAngularVelocity(bodies.back(), drifts[i].w);
  }
  std::vector<int> asleepAt(drifts.size(), -1);
  for (int k = 1; k <= 120; ++k) {
    w.step(dt);
    for (std::size_t i = 0; i < drifts.size(); ++i)
      if (asleepAt[i] < 0 && !w.isAwake(bodies[i])) asleepAt[i] = k;
  }
  for (std::size_t i = 0; i < drifts.size(); ++i)
    EXPECT_EQ(asleepAt[i], drifts[i].sleepsAt) << "body " << i;
}

}  // namespace island_test
