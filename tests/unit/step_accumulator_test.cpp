// StepAccumulator (physics/step_accumulator.h): whole fixed steps from wall-clock time, the cap
// on a long frame, bad input.
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
namespace step_accumulator_test {

using rc::BodyId;
using rc::Vec2;
using rc::testing::dynamicAt;
using rc::testing::finiteState;
using rc::testing::ground;
using rc::testing::restingRow;
using rc::testing::stepWatchingEnergy;

// The accumulator turns wall-clock frames into fixed steps: frames of any length add up to the
// same steps and so the same state as stepping by hand; alpha is what is banked.
TEST(StepAccumulator, IrregularFramesGiveTheFixedStepState) {
  auto scene = [](rc::World& w) {
    ground(w);
    BodyId b = w.createBody(dynamicAt({0.3f, 4.0f}, 0.4f));
    w.createShape(b, rc::makeBox(0.5f, 0.25f));
    BodyId c = w.createBody(dynamicAt({0.0f, 2.0f}));
    w.createShape(c, rc::makeCircle({}, 0.4f));
    return b;
  };
  const float dt = 1.0f / 60.0f;
  rc::World byHand, byClock;
  scene(byHand);
  scene(byClock);
  rc::StepAccumulator acc(dt);
  rc::Random rng(77);
  double clock = 0.0;
  int frames = 0;
  while (acc.steps() < 150) {
    const double frame = rng.uniform(0.0f, 0.05f);  // 0 to 50 ms, mostly several steps' worth
    clock += frame;
    const int taken = acc.advance(byClock, frame);
    EXPECT_LE(taken, 8);
    ++frames;
    EXPECT_GE(acc.alpha(), 0.0);
    EXPECT_LT(acc.alpha(), 1.0);
  }
  for (long long i = 0; i < acc.steps(); ++i)
    byHand.step(dt);
  EXPECT_EQ(byClock.stateHash(), byHand.stateHash());
  EXPECT_EQ(acc.droppedSeconds(), 0.0);
  // Time is conserved: what was stepped plus what is banked is what elapsed.
  EXPECT_NEAR(static_cast<double>(acc.steps()) * dt + acc.alpha() * dt, clock, 1e-9);
  EXPECT_GT(frames, 100);
}

// A frame of one second with the cap at 8 steps takes 8 and drops the rest, keeping the part
// of a step that was banked; the next frame goes on normally.
TEST(StepAccumulator, ALongFrameIsCapped) {
  const float dt = 1.0f / 60.0f;
  rc::World w;
  ground(w);
  rc::StepAccumulator acc(dt, 8);
  EXPECT_EQ(acc.advance(w, 0.5 * dt), 0);
  EXPECT_NEAR(acc.alpha(), 0.5, 1e-9);
  EXPECT_EQ(acc.advance(w, 1.0), 8);
  EXPECT_EQ(acc.steps(), 8);
  // 60.5 steps banked in all: 8 taken, the other 52 whole steps dropped, the half step kept.
  const double elapsed = 0.5 * dt + 1.0;
  const double whole = std::floor(elapsed / dt);
  EXPECT_NEAR(acc.droppedSeconds(), (whole - 8.0) * dt, 1e-9);
  EXPECT_NEAR(acc.alpha(), elapsed / dt - whole, 1e-6);
  EXPECT_EQ(acc.advance(w, dt), 1);
}

TEST(StepAccumulator, RejectsBadInput) {
  rc::World w;
  EXPECT_THROW(rc::StepAccumulator(0.0f), rc::InvalidDefinition);
  EXPECT_THROW(rc::StepAccumulator(-1.0f / 60.0f), rc::InvalidDefinition);
  EXPECT_THROW(rc::StepAccumulator(std::numeric_limits<float>::infinity()), rc::InvalidDefinition);
  EXPECT_THROW(rc::StepAccumulator(1.0f / 60.0f, 0), rc::InvalidDefinition);
  rc::StepAccumulator acc;
  EXPECT_THROW(acc.advance(w, -0.01), rc::InvalidDefinition);
  EXPECT_THROW(acc.advance(w, std::numeric_limits<double>::quiet_NaN()), rc::InvalidDefinition);
  EXPECT_THROW(acc.advance(w, std::numeric_limits<double>::infinity()), rc::InvalidDefinition);
  EXPECT_EQ(acc.steps(), 0);
  EXPECT_EQ(acc.alpha(), 0.0);
}

}  // namespace step_accumulator_test
