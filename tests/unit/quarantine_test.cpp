// A body whose state becomes unusable inside a step (a force field's NaN, finite forces large
// enough to overflow, an absurd speed) is quarantined: disabled where it began the step, reported
// with its cause, and its neighbours are left with finite, calm states. And force fields: what
// they see of sleeping bodies, and a stale id in one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/world.h"
#include "support/world_scenes.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace quarantine_test {

using rc::BodyId;
using rc::Vec2;

using rc::testing::kStep;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A 3-wide, 4-high stack of boxes on the ground, settled, with the body in the middle of the
// second row returned as the one that goes wrong.
struct Pile {
  rc::World world;
  std::vector<BodyId> boxes;
  BodyId culprit;
  Pile() {
    const BodyId ground = world.createBody({});
    world.createShape(ground, rc::makeBox(10, 0.5f, {0, -0.5f}));
    for (int row = 0; row < 4; ++row)
      for (int col = -1; col <= 1; ++col) {
        rc::BodyDef d;
        d.type = rc::BodyType::dynamicBody;
        d.position = {1.02f * static_cast<float>(col), 0.5f + static_cast<float>(row)};
        d.userData = 100 + boxes.size();
        boxes.push_back(world.createBody(d));
        world.createShape(boxes.back(), rc::makeBox(0.5f, 0.5f));
      }
    culprit = boxes[4];
    for (int k = 0; k < 30; ++k)
      world.step(kStep);
  }
  // Every other box: finite, and no faster than the push-out speed.
  void expectNeighboursCalm() const {
    for (BodyId b : boxes) {
      if (b == culprit) continue;
      const Vec2 v = world.linearVelocity(b);
      const Vec2 p = world.position(b);
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(world.angle(b)));
      ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y));
      EXPECT_LT(rc::length(v), world.def().maxPushoutSpeed + 1.0f);
    }
  }
  void expectQuarantined(rc::QuarantineCause cause, Vec2 where) const {
    ASSERT_EQ(world.quarantineEvents().size(), 1u);
    const rc::QuarantineEvent& e = world.quarantineEvents()[0];
    EXPECT_EQ(e.body, culprit);
    EXPECT_EQ(e.userData, 104u);
    EXPECT_EQ(e.cause, cause) << rc::quarantineCauseName(e.cause);
    EXPECT_FALSE(world.isEnabled(culprit));
    // Back where it began the step, at rest.
    EXPECT_NEAR(world.position(culprit).x, where.x, 1e-6f);
    EXPECT_NEAR(world.position(culprit).y, where.y, 1e-6f);
    EXPECT_EQ(world.linearVelocity(culprit), Vec2{});
  }
};

TEST(Quarantine, ForceFieldNaN) {
  Pile pile;
  const Vec2 before = pile.world.position(pile.culprit);
  const BodyId culprit = pile.culprit;
  pile.world.addForceField([culprit](rc::ForceStage& s) { s.addForce(culprit, {kNaN, 0}); });
  pile.world.step(kStep);
  pile.expectQuarantined(rc::QuarantineCause::forceField, before);
  for (int k = 0; k < 60; ++k)
    pile.world.step(kStep);
  pile.expectNeighboursCalm();
  EXPECT_TRUE(pile.world.quarantineEvents().empty());  // reported once
}

// Finite forces that overflow: 1e38 N on a 1 kg box is 1e38 m/s^2, 4e35 m/s after a substep.
TEST(Quarantine, FiniteForceThatOverflows) {
  Pile pile;
  const Vec2 before = pile.world.position(pile.culprit);
  pile.world.applyForceToCenter(pile.culprit, {0, 1e38f});
  pile.world.step(kStep);
  pile.expectQuarantined(rc::QuarantineCause::motion, before);
  pile.expectNeighboursCalm();
}

// A body at 1e30 m/s (finite: impulses add up) meeting the pile: stopped before it moves.
TEST(Quarantine, AbsurdSpeedMeetingOthers) {
  Pile pile;
  const Vec2 before = pile.world.position(pile.culprit);
  pile.world.applyLinearImpulse(pile.culprit, {1e30f, 0}, pile.world.worldCenter(pile.culprit));
  pile.world.step(kStep);
  pile.expectQuarantined(rc::QuarantineCause::motion, before);
  for (int k = 0; k < 60; ++k)
    pile.world.step(kStep);
  pile.expectNeighboursCalm();
}

// A quarantined body can be put back: at rest where it was, it rejoins the pile.
TEST(Quarantine, ReEnabledBodyRejoins) {
  Pile pile;
  pile.world.applyForceToCenter(pile.culprit, {0, 1e38f});
  pile.world.step(kStep);
  ASSERT_FALSE(pile.world.isEnabled(pile.culprit));
  pile.world.setEnabled(pile.culprit, true);
  for (int k = 0; k < 60; ++k)
    pile.world.step(kStep);
  EXPECT_TRUE(pile.world.quarantineEvents().empty());
  EXPECT_NEAR(pile.world.position(pile.culprit).y, 1.5f, 0.05f);
  pile.expectNeighboursCalm();
}

// A field acting on a sleeping body: it sees the body at rest (not past its arrays: ASan), and
// the body wakes after the step and is pulled from the next one on.
TEST(ForceField, WakesSleepingBodiesAfterTheStep) {
  rc::World w;
  w.createShape(w.createBody({}), rc::makeBox(10, 0.5f, {0, -0.5f}));
  rc::BodyDef d;
  d.type = rc::BodyType::dynamicBody;
  d.position = {0, 0.5f};
  const BodyId box = w.createBody(d);
  w.createShape(box, rc::makeBox(0.5f, 0.5f));
  for (int k = 0; k < 120 && w.isAwake(box); ++k)
    w.step(kStep);
  ASSERT_FALSE(w.isAwake(box));
  bool on = false;
  Vec2 seen{};
  w.addForceField([&](rc::ForceStage& s) {
    seen = s.center(box);
    if (on) {
      s.addForce(box, {0, 100});  // lifts it: 100 N against 10 N of weight
    } else {
      EXPECT_EQ(s.velocity(box), Vec2{});  // asleep: at rest
    }
  });
  w.step(kStep);
  EXPECT_NEAR(seen.y, 0.5f, 0.01f);
  on = true;
  w.step(kStep);
  EXPECT_TRUE(w.isAwake(box));  // woken after the step it was pushed in
  const float y = w.position(box).y;
  w.step(kStep);
  EXPECT_GT(w.position(box).y, y);  // and lifted in the next
}

// A field naming a destroyed body: the step completes without it (the other body moves exactly
// as in a world without the field) and then throws, naming the body.
TEST(ForceField, StaleIdThrowsAfterAWholeStep) {
  auto make = [](rc::World& w) {
    rc::BodyDef d;
    d.type = rc::BodyType::dynamicBody;
    const BodyId gone = w.createBody(d);
    d.position = {3, 0};
    const BodyId stays = w.createBody(d);
    w.createShape(stays, rc::makeCircle({}, 0.5f));
    w.destroyBody(gone);
    return std::pair{gone, stays};
  };
  rc::World plain, fielded;
  make(plain);
  const auto [gone, stays] = make(fielded);
  fielded.addForceField([gone = gone](rc::ForceStage& s) { s.addForce(gone, {1, 0}); });
  plain.step(kStep);
  try {
    fielded.step(kStep);
    FAIL() << "no error for a stale id";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 0 (generation 1)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(fielded.time(), plain.time());
  EXPECT_EQ(fielded.precisePosition(stays), plain.precisePosition(stays));
  plain.step(kStep);
  EXPECT_THROW(fielded.step(kStep), std::invalid_argument);  // every step, until the field is fixed
  EXPECT_EQ(fielded.precisePosition(stays), plain.precisePosition(stays));
}

}  // namespace quarantine_test
