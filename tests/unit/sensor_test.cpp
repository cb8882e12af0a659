// Sensors (physics/sensor.cpp): begin and end events as a visitor enters and leaves, and a
// visitor that passes right through within one step.
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
namespace sensor_test {

using rc::BodyId;
using rc::Vec2;
using rc::testing::dynamicAt;
using rc::testing::finiteState;
using rc::testing::ground;
using rc::testing::restingRow;
using rc::testing::stepWatchingEnergy;

// A ball falls through a sensor box: one begin when it enters, one end when it leaves, and the
// sensor does not stop it. A bullet through a 1 cm trip line within one step reports both.
TEST(World, SensorEvents) {
  rc::WorldDef def;
  rc::World w(def);
  rc::BodyDef sensorDef;
  BodyId zone = w.createBody(sensorDef);
  rc::ShapeDef sensor;
  sensor.isSensor = true;
  rc::ShapeId zoneShape = w.createShape(zone, rc::makeBox(2, 1, {0, 5}), sensor);  // y 4..6
  BodyId ball = w.createBody(dynamicAt({0, 8}));
  rc::ShapeId ballShape = w.createShape(ball, rc::makeCircle({}, 0.25f));
  int begins = 0, ends = 0;
  float enteredAt = 0, leftAt = 0;
  for (int i = 0; i < 120; ++i) {
    w.step(1.0f / 60.0f);
    for (const rc::SensorEvent& e : w.sensorEvents().begin) {
      EXPECT_EQ(e.sensor.shape, zoneShape);
      EXPECT_EQ(e.visitor.shape, ballShape);
      EXPECT_EQ(e.visitor.body, ball);
      ++begins;
      enteredAt = w.position(ball).y;
    }
    for (const rc::SensorEvent& e : w.sensorEvents().end) {
      EXPECT_EQ(e.visitor.shape, ballShape);
      ++ends;
      leftAt = w.position(ball).y;
    }
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 1);
  // Entered when its bottom reached 6 m, left when its top passed 4 m (within a step of fall).
  EXPECT_NEAR(enteredAt, 6.25f, 0.3f);
  EXPECT_NEAR(leftAt, 3.75f, 0.3f);
  EXPECT_LT(w.position(ball).y, 0.0f);                       // not stopped
  EXPECT_TRUE(w.castRay({0, 10}, {0, -5}) == std::nullopt);  // rays ignore sensors

  // The trip line.
  rc::World fast(def);
  BodyId lineBody = fast.createBody(sensorDef);
  fast.createShape(lineBody, rc::makeBox(0.005f, 2), sensor);
  rc::BodyDef bulletDef = dynamicAt({-3, 0});
  bulletDef.linearVelocity = {500, 0};
  bulletDef.gravityScale = 0;
  BodyId bullet = fast.createBody(bulletDef);
  fast.createShape(bullet, rc::makeCircle({}, 0.02f));
  int sameStep = 0;
  for (int i = 0; i < 3; ++i) {
    fast.step(1.0f / 60.0f);
    if (fast.sensorEvents().begin.size() == 1 && fast.sensorEvents().end.size() == 1) ++sameStep;
  }
  EXPECT_EQ(sameStep, 1);
  EXPECT_GT(fast.position(bullet).x, 3.0f);
}

}  // namespace sensor_test
