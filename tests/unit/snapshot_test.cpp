// World::snapshot and World::restore: a restored world continues bit for bit as the original
// (the hash covers everything that decides the next step), rollback and synctest work, and a
// snapshot that is truncated, corrupt, of another format or of another world is refused with the
// world left as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/random.h"
#include "physics/world.h"
#include "support/world_scenes.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace snapshot_test {

using rc::BodyId;
using rc::Vec2;

using rc::testing::dynamicAt;
using rc::testing::kStep;
using rc::testing::pyramidOfBoxes;

// A world that has everything a snapshot must carry: a settling pile (contacts with warm
// starts), bouncing balls, a sleeping pile far off, a kinematic mover, a sensor zone, a bullet,
// a body with damping, shapes destroyed and their slots reused, a destroyed body, a disabled
// body, and a force field (a spring to a point) that the restoring world installs the same way.
struct RichScene {
  rc::World world;
  BodyId mover, sprung, disabled;
  explicit RichScene(std::uint64_t seed) {
    rc::World& w = world;
    rc::BodyDef groundDef;
    const BodyId ground = w.createBody(groundDef);
    w.createShape(ground, rc::makeBox(30, 0.5f, {0, -0.5f}));
    w.createShape(ground, rc::makeBox(0.5f, 10, {-30, 10}));
    w.createShape(ground, rc::makeBox(0.5f, 10, {30, 10}));
    rc::Random rng(seed);
    for (int i = 0; i < 40; ++i) {
      const BodyId b = w.createBody(dynamicAt(
          {rng.uniform(-10, 10), 0.6f + 0.9f * static_cast<float>(i)}, rng.uniform(-1, 1)));
      rc::ShapeDef sd;
      sd.restitution = i % 4 == 0 ? 0.6f : 0.0f;
      sd.friction = rng.uniform(0.2f, 0.9f);
      if (i % 3 == 0) {
        w.createShape(b, rc::makeCircle({}, rng.uniform(0.2f, 0.5f)), sd);
      } else if (i % 3 == 1) {
        w.createShape(b, rc::makeBox(rng.uniform(0.2f, 0.5f), rng.uniform(0.2f, 0.5f)), sd);
      } else {
        w.createShape(b, rc::makeCapsule({-0.3f, 0}, {0.3f, 0}, 0.2f), sd);
      }
    }
    // A pile far off that falls asleep while the rest moves.
    for (int i = 0; i < 4; ++i) {
      const BodyId b = w.createBody(dynamicAt({20, 0.5f + 1.0f * static_cast<float>(i)}));
      w.createShape(b, rc::makeBox(0.5f, 0.5f));
    }
    rc::BodyDef moverDef;
    moverDef.type = rc::BodyType::kinematicBody;
    moverDef.position = {-20, 1};
    moverDef.linearVelocity = {2, 0};
    mover = w.createBody(moverDef);
    w.createShape(mover, rc::makeBox(1, 0.25f));
    rc::ShapeDef zone;
    zone.isSensor = true;
    w.createShape(w.createBody(groundDef), rc::makeBox(3, 3, {0, 3}), zone);
    rc::BodyDef bulletDef = dynamicAt({-25, 8});
    bulletDef.bullet = true;
    bulletDef.linearVelocity = {300, -20};
    w.createShape(w.createBody(bulletDef), rc::makeCircle({}, 0.05f));
    rc::BodyDef dampedDef = dynamicAt({5, 12});
    dampedDef.linearDamping = 0.5f;
    dampedDef.angularDamping = 0.3f;
    dampedDef.angularVelocity = 3;
    sprung = w.createBody(dampedDef);
    w.createShape(sprung, rc::makeBox(0.3f, 0.3f));
    // Slots reused: a body destroyed, shapes destroyed and made again.
    const BodyId gone = w.createBody(dynamicAt({0, 30}));
    const rc::ShapeId extra = w.createShape(sprung, rc::makeCircle({0.4f, 0}, 0.1f));
    w.destroyBody(gone);
    w.destroyShape(extra);
    w.createShape(sprung, rc::makeCircle({-0.4f, 0}, 0.1f));
    disabled = w.createBody(dynamicAt({-5, 2}));
    w.createShape(disabled, rc::makeBox(0.5f, 0.5f));
    w.setEnabled(disabled, false);
    installField(w);
  }
  // The restoring world must have the same fields: they are code, not state.
  void installField(rc::World& w) const {
    const BodyId body = sprung;
    w.addForceField([body](rc::ForceStage& s) {
      const Vec2 d = Vec2{5, 8} - s.center(body);
      s.addForce(body, 40.0f * d - 2.0f * s.velocity(body));
    });
  }
  // Things a game does between steps, at chosen steps.
  void act(rc::World& w, int step) const {
    if (step % 50 == 25)
      w.setTargetTransform(mover, {-20.0f + 0.1f * static_cast<float>(step), 1}, 0, kStep);
    if (step == 70) w.setEnabled(disabled, true);
  }
};

std::vector<std::uint64_t> run(rc::World& w, const RichScene& scene, int from, int to) {
  std::vector<std::uint64_t> hashes;
  for (int k = from; k < to; ++k) {
    scene.act(w, k);
    w.step(kStep);
    hashes.push_back(w.stateHash());
  }
  return hashes;
}

// Snapshotted at step 60 and restored into a new world, the scene goes on exactly as the
// original: every step's hash equal up to step 240 (the hash covers contacts, warm starts, sleep
// timers, the broadphase: a restore that missed any of them would drift within a few steps).
TEST(Snapshot, RestoredWorldContinuesBitForBit) {
  RichScene original(7);
  run(original.world, original, 0, 60);
  const rc::WorldSnapshot snap = original.world.snapshot();
  const std::vector<std::uint64_t> expected = run(original.world, original, 60, 240);

  RichScene other(7);  // the same definition and field; its bodies are overwritten
  rc::World& copy = other.world;
  copy.restore(snap);
  EXPECT_EQ(copy.snapshot(), snap);
  const std::vector<std::uint64_t> got = run(copy, original, 60, 240);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k)
    ASSERT_EQ(got[k], expected[k]) << "first different at step " << 61 + k;
  EXPECT_EQ(copy.snapshot(), original.world.snapshot());
  EXPECT_GT(copy.awakeBodyCount(), 0);
  EXPECT_LT(copy.awakeBodyCount(), copy.bodyCount());  // the far pile slept: islands carried
}

// Rollback: restoring an earlier snapshot into the same world and stepping again replays the
// same steps.
TEST(Snapshot, RollbackReplaysTheSameSteps) {
  RichScene scene(11);
  run(scene.world, scene, 0, 30);
  const rc::WorldSnapshot at30 = scene.world.snapshot();
  const std::vector<std::uint64_t> first = run(scene.world, scene, 30, 90);
  scene.world.restore(at30);
  EXPECT_EQ(run(scene.world, scene, 30, 90), first);
}

// GGPO's synctest: every step is taken twice, the second time from a restored snapshot; any
// state a snapshot missed shows as a different hash at once.
TEST(Snapshot, Synctest) {
  RichScene scene(3);
  rc::World& w = scene.world;
  for (int k = 0; k < 150; ++k) {
    const rc::WorldSnapshot before = w.snapshot();
    scene.act(w, k);
    w.step(kStep);
    const std::uint64_t once = w.stateHash();
    w.restore(before);
    scene.act(w, k);
    w.step(kStep);
    ASSERT_EQ(w.stateHash(), once) << "step " << k + 1;
  }
}

// A resting pile's constraints are the same step after step, and the solver keeps their colouring
// and lanes instead of laying them out again, a recycled manifold's lane rewritten only where it
// changes: every step must give the bits a solver laying them out anew gives (a new world
// restored from the step before's snapshot). The pile is one the stack solve corrects as it is
// let go (WorldDef::stackSolveDepth), whose piles, rows and factor are found and made again in
// the new world, and whose bounds for the next correction are in the snapshot. While it rests,
// what a lane is made from changes under it: a box's friction, a box's mass and centre of mass
// (a shape added inside it, touching nothing), the substeps (the impulses scaled).
TEST(Snapshot, KeptSolverLayoutGivesTheBitsOfANewOne) {
  rc::WorldDef def;
  def.enableSleep = false;
  auto pyramid = [&def](std::vector<BodyId>* boxes = nullptr) {
    auto w = std::make_unique<rc::World>(def);
    w->createShape(w->createBody({}), rc::makeBox(20, 0.5f, {0, -0.5f}));
    std::vector<BodyId> made = pyramidOfBoxes(*w, 8);
    if (boxes != nullptr) *boxes = std::move(made);
    return w;
  };
  std::vector<BodyId> boxes;
  const std::unique_ptr<rc::World> kept = pyramid(&boxes);
  int keptSteps = 0, keptLanes = 0, corrections = 0, whole = 0;
  int substeps = def.substeps;
  for (int k = 0; k < 240; ++k) {
    // Every box (some of their constraints are in batches with an empty lane, set every step).
    if (k == 120) {
      rc::ShapeDef heavy;
      heavy.density = 8.0f;
      // Within each box's bounds: no contact made (which would lay the lanes out anew).
      for (const BodyId box : boxes)
        kept->createShape(box, rc::makeCircle({0.1f, 0.1f}, 0.05f), heavy);
    }
    if (k == 150) {
      substeps = 6;
      kept->setStepping(substeps, def.integrator);
    }
    if (k == 200) {
      // Low enough to bind: friction within its cone does not depend on the coefficient.
      for (const BodyId box : boxes)
        kept->setFriction(kept->shapesOf(box)[0], 0.01f);
    }
    const rc::WorldSnapshot before = kept->snapshot();
    kept->step(kStep);
    keptSteps += kept->profile().layoutKept;
    keptLanes += kept->profile().lanesKept;
    whole += kept->profile().pileBodies == 36;  // every box of the base-8 pyramid
    corrections += kept->profile().pileCorrections;
    const std::unique_ptr<rc::World> fresh = pyramid();
    if (substeps != def.substeps) fresh->setStepping(substeps, def.integrator);
    fresh->restore(before);
    fresh->step(kStep);
    ASSERT_FALSE(fresh->profile().layoutKept);
    ASSERT_EQ(fresh->stateHash(), kept->stateHash()) << "step " << k + 1;
  }
  EXPECT_GT(keptSteps, 200);  // the pile settles within the first second
  // Most of its constraints (64 of its 92; the others are in batches with an empty lane).
  EXPECT_GT(keptLanes, 200 * 60);
  EXPECT_GT(corrections, 0);
  EXPECT_GT(whole, 230);  // a box or two not touching in a step as the pile is let go
}

// The narrowphase, the constraints' preparation and the islands walk a list of the contacts with
// something awake, kept from step to step while the awake set stays as it is: contacts made are
// added, destroyed ones taken out, and a destroy that would mend it in the middle has it made
// again. Every step must give the bits of a world that makes the list anew (restored from the
// step before's snapshot): piles falling asleep and woken by falling shots, shots destroyed
// while still touching and after they passed sleeping boxes without touching them, sleeping
// boxes destroyed, new piles made after older ones slept.
TEST(Snapshot, ListOfAwakeContactsGivesTheBitsOfANewOne) {
  rc::WorldDef def;
  const auto kept = std::make_unique<rc::World>(def);
  kept->createShape(kept->createBody({}), rc::makeBox(40, 0.5f, {0, -0.5f}));
  auto pile = [&](float x, int boxes) {
    std::vector<BodyId> made;
    for (int i = 0; i < boxes; ++i) {
      made.push_back(kept->createBody(dynamicAt({x, 0.5f + static_cast<float>(i)})));
      kept->createShape(made.back(), rc::makeBox(0.5f, 0.5f));
    }
    return made;
  };
  std::vector<BodyId> boxes;
  for (int p = 0; p < 12; ++p) {
    const std::vector<BodyId> made = pile(-22.0f + 4.0f * static_cast<float>(p), 3);
    boxes.insert(boxes.end(), made.begin(), made.end());
  }
  rc::Random rng(5);
  struct Shot {
    BodyId body;
    int born;
  };
  std::vector<Shot> shots;
  int asleepSteps = 0, destroyedShots = 0;
  for (int k = 0; k < 600; ++k) {
    if (k % 3 == 0) {
      // Falling onto a pile (waking it), or without gravity past one, 0.5-0.9 m beside it, onto
      // the ground.
      const float x = -22.0f + 4.0f * static_cast<float>(rng.below(12));
      const bool past = rng.below(2) == 0;
      rc::BodyDef shot = dynamicAt(
          {x + (past ? rng.uniform(1.1f, 1.5f) : rng.uniform(-0.4f, 0.4f)), rng.uniform(4, 8)});
      shot.linearVelocity = {0, -rng.uniform(2, 15)};
      shot.gravityScale = past ? 0.0f : 1.0f;
      shots.push_back({kept->createBody(shot), k});
      kept->createShape(shots.back().body, rc::makeCircle({}, 0.1f));
    }
    // Shots go after 40 steps (touching what they fell on, or long past it), in the order
    // the rng picks.
    for (std::size_t i = shots.size(); i-- > 0;) {
      if (k - shots[i].born < 40 || rng.below(2) == 0) continue;
      kept->destroyBody(shots[i].body);
      shots.erase(shots.begin() + static_cast<std::ptrdiff_t>(i));
      ++destroyedShots;
    }
    if (k % 50 == 49 && !boxes.empty()) {
      const std::size_t i = rng.below(static_cast<std::uint32_t>(boxes.size()));
      kept->destroyBody(boxes[i]);
      boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(i));
    }
    if (k % 37 == 36) {
      const std::vector<BodyId> made = pile(rng.uniform(-24, 24), 2);
      boxes.insert(boxes.end(), made.begin(), made.end());
    }
    const rc::WorldSnapshot before = kept->snapshot();
    kept->step(kStep);
    asleepSteps += kept->awakeBodyCount() < kept->bodyCount() - 1;
    rc::World fresh(def);
    fresh.restore(before);
    fresh.step(kStep);
    ASSERT_EQ(fresh.stateHash(), kept->stateHash()) << "step " << k + 1;
  }
  EXPECT_GT(asleepSteps, 400);  // most steps have sleeping piles beside awake shots
  EXPECT_GT(destroyedShots, 150);
}

// The one destroy the list cannot mend in place: a contact with nothing awake (two sleeping
// boxes 0.1 m apart, whose fat AABBs overlap) refused by a filter while the last contact made
// (a ball's, about to hit a wall) is awake and nothing wakes. The last one's entry would have
// to move into the middle; the list is made again instead, and the steps after give the bits
// of a world that made it anew.
TEST(Snapshot, ListOfAwakeContactsMadeAgainAfterASleepingContactIsRefused) {
  rc::WorldDef def;
  rc::World kept(def);
  const BodyId ground = kept.createBody({});
  kept.createShape(ground, rc::makeBox(20, 0.5f, {0, -0.5f}));
  kept.createShape(ground, rc::makeBox(0.5f, 5, {0, 10}));
  const rc::ShapeId first =
      kept.createShape(kept.createBody(dynamicAt({-10, 0.5f})), rc::makeBox(0.5f, 0.5f));
  rc::ShapeDef secondDef;
  secondDef.filter.category = 2;
  kept.createShape(kept.createBody(dynamicAt({-8.9f, 0.5f})), rc::makeBox(0.5f, 0.5f), secondDef);
  for (int k = 0; k < 120; ++k)
    kept.step(kStep);
  ASSERT_EQ(kept.awakeBodyCount(), 0);
  rc::BodyDef ballDef = dynamicAt({-0.8f, 14});
  ballDef.gravityScale = 0;
  ballDef.linearVelocity = {1, 0};
  kept.createShape(kept.createBody(ballDef), rc::makeCircle({}, 0.2f));
  kept.step(kStep);  // the ball's contact with the wall is made: the last, awake; it hits the
                     // wall 0.1 m on, a few steps after the refusal
  ASSERT_EQ(kept.awakeBodyCount(), 1);
  kept.setFilter(first, {1, ~2u});
  ASSERT_FALSE(kept.isAwake(kept.bodyOf(first)));
  for (int k = 0; k < 30; ++k) {
    const rc::WorldSnapshot before = kept.snapshot();
    kept.step(kStep);
    rc::World fresh(def);
    fresh.restore(before);
    fresh.step(kStep);
    ASSERT_EQ(fresh.stateHash(), kept.stateHash()) << "step " << k + 1;
  }
}

// Events are state the game reads after a restore, and ends made by destroying between steps
// are delivered by the next step whether or not a restore came between.
TEST(Snapshot, CarriesPublishedAndPendingEvents) {
  rc::World w;
  const BodyId ground = w.createBody({});
  w.createShape(ground, rc::makeBox(5, 0.5f, {0, -0.5f}));
  const BodyId box = w.createBody(dynamicAt({0, 0.5f}));
  w.createShape(box, rc::makeBox(0.5f, 0.5f));
  w.step(kStep);
  ASSERT_EQ(w.contactEvents().begin.size(), 1u);
  const rc::WorldSnapshot touching = w.snapshot();
  w.destroyBody(box);
  const rc::WorldSnapshot pending = w.snapshot();

  rc::World other;
  other.restore(touching);
  EXPECT_EQ(other.contactEvents().begin.size(), 1u);
  other.restore(pending);
  EXPECT_FALSE(other.isValid(box));
  other.step(kStep);
  ASSERT_EQ(other.contactEvents().end.size(), 1u);
  EXPECT_TRUE(other.contactEvents().end[0].destroyed);
}

// Every truncation of a snapshot is refused with a message naming the snapshot, and the world
// is left as it was.
TEST(Snapshot, TruncatedIsRefusedAndTheWorldUnchanged) {
  RichScene scene(5);
  run(scene.world, scene, 0, 20);
  const rc::WorldSnapshot snap = scene.world.snapshot();
  RichScene target(5);
  const std::uint64_t before = target.world.stateHash();
  for (std::size_t n = 0; n < snap.size(); n += 1 + n / 64) {
    const std::span<const std::uint8_t> cut(snap.data(), n);
    try {
      target.world.restore(cut);
      ADD_FAILURE() << "a snapshot cut to " << n << " of " << snap.size() << " bytes was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("snapshot", 0), 0u) << e.what();
    }
    ASSERT_EQ(target.world.stateHash(), before) << "cut at " << n;
  }
}

// Random corruption: each flipped byte is either refused (std::invalid_argument) or makes a
// world that steps without crashing (a flipped position or velocity is still a number; the
// quarantine takes care of an absurd one). Run under ASan+UBSan in CI.
TEST(Snapshot, CorruptBytesAreRefusedOrHarmless) {
  RichScene scene(9);
  run(scene.world, scene, 0, 40);
  const rc::WorldSnapshot snap = scene.world.snapshot();
  rc::Random rng(0xc0ffee);
  RichScene target(9);
  int refused = 0, taken = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    rc::WorldSnapshot bad = snap;
    const auto at =
        static_cast<std::size_t>(rng.uniform(0.0f, 1.0f) * static_cast<float>(bad.size() - 1));
    bad[at] = static_cast<std::uint8_t>(bad[at] ^ (1u << (trial % 8)));
    try {
      target.world.restore(bad);
    } catch (const std::invalid_argument&) {
      ++refused;
      continue;
    }
    ++taken;
    try {
      for (int k = 0; k < 5; ++k)
        target.world.step(kStep);
    } catch (const std::exception& e) {
      // A flipped generation can make the scene's force field name a body that is no more: a
      // clear error after a whole step (ForceField.StaleIdThrowsAfterAWholeStep). Anything else
      // thrown by a step would be a hole in restore's checks.
      if (std::string(e.what()).find("a force field named body") == std::string::npos)
        ADD_FAILURE() << "byte " << at << " flipped: " << e.what();
    }
    target.world.restore(snap);  // (a world per trial would cost its quadtree's 11 MB each)
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(taken, 0);
}

// A contact keeps the rotations its manifold was made at (copies of its bodies' then, unit as a
// body's must be): a snapshot whose copy is off unit length (finite, 1.5 times as long) is
// refused naming the contact, as one whose body's rotation is off is refused naming the body.
// A ball resting on a static slab tilted by 0.3 rad, after one step: one touching contact.
struct TiltedSlab {
  rc::World world;
  BodyId slab;
  TiltedSlab() {
    rc::BodyDef def;
    def.angle = 0.3f;
    slab = world.createBody(def);
    world.createShape(slab, rc::makeBox(5, 0.5f));
    world.createShape(world.createBody(dynamicAt({0, 1.05f})), rc::makeCircle({}, 0.5f));
    world.step(kStep);
  }
};

// Every place in `snap` holding the floats (x, y), each changed alone to 1.5 times them and
// restored: what restore() said ("" where it took the snapshot).
std::vector<std::string> lengthenedRestores(const rc::WorldSnapshot& snap, float x, float y) {
  std::uint8_t pattern[8];
  std::memcpy(pattern, &x, 4);
  std::memcpy(pattern + 4, &y, 4);
  const float longer[2] = {1.5f * x, 1.5f * y};
  std::vector<std::string> said;
  for (std::size_t at = 0; at + 8 <= snap.size(); ++at) {
    if (std::memcmp(&snap[at], pattern, 8) != 0) continue;
    rc::WorldSnapshot bad = snap;
    std::memcpy(&bad[at], longer, 8);
    rc::World target;
    try {
      target.restore(bad);
      said.emplace_back();
    } catch (const std::invalid_argument& e) {
      said.emplace_back(e.what());
    }
  }
  return said;
}

int mentioning(const std::vector<std::string>& said, const std::string& what) {
  return static_cast<int>(std::count_if(said.begin(), said.end(), [&](const std::string& m) {
    return m.find(what) != std::string::npos;
  }));
}

// The rotation of a tilted static slab is in the snapshot as its body's and as the contact's
// copy: each place is found by its bytes and changed alone, and every change is refused.
TEST(Snapshot, ContactRotationsOffUnitAreRefused) {
  TiltedSlab t;
  ASSERT_EQ(t.world.contactCount(), 1);
  const rc::Rot q = t.world.transform(t.slab).q;
  const std::vector<std::string> said = lengthenedRestores(t.world.snapshot(), q.c, q.s);
  for (const std::string& m : said)
    EXPECT_FALSE(m.empty()) << "a rotation 1.5 times as long was taken";
  EXPECT_GE(mentioning(said, "a contact"), 1);
  EXPECT_GE(mentioning(said, "a body"), 1);
}

// A touching contact's normal off unit length (1.5 times as long) is refused too: the solver's
// tangent and effective masses assume a unit normal.
TEST(Snapshot, ContactNormalsOffUnitAreRefused) {
  TiltedSlab t;
  ASSERT_EQ(t.world.touchingContactCount(), 1);
  const rc::WorldSnapshot snap = t.world.snapshot();
  const rc::Vec2 n = t.world.contactPoints().at(0).normal;
  EXPECT_EQ(mentioning(lengthenedRestores(snap, n.x, n.y), "a contact"), 1);
  rc::World same;
  EXPECT_NO_THROW(same.restore(snap));
}

// The narrowphase reads a contact's two proxies unchecked, so restore() refuses a contact one of
// whose shapes has none (a disabled body's): a box resting on the ground, its contact's first
// shape changed in the bytes to a disabled body's shape. Forty shapes made first give the
// contact's pair of indices bytes found once.
TEST(Snapshot, ContactOfADisabledBodysShapeIsRefused) {
  rc::World w;
  const BodyId filler = w.createBody({});
  for (int i = 0; i < 40; ++i)
    w.createShape(filler, rc::makeBox(0.1f, 0.1f, {100.0f + static_cast<float>(i), 100}));
  const rc::ShapeId ground = w.createShape(w.createBody({}), rc::makeBox(5, 0.5f, {0, -0.5f}));
  const BodyId off = w.createBody(dynamicAt({-3, 3}));
  const rc::ShapeId offShape = w.createShape(off, rc::makeBox(0.5f, 0.5f));
  w.setEnabled(off, false);
  const rc::ShapeId box =
      w.createShape(w.createBody(dynamicAt({0, 0.5f})), rc::makeBox(0.5f, 0.5f));
  w.step(kStep);
  ASSERT_EQ(w.touchingContactCount(), 1);
  ASSERT_LT(offShape.index, box.index);
  const rc::WorldSnapshot snap = w.snapshot();
  const std::int32_t pair[2] = {ground.index, box.index};
  std::vector<std::size_t> found;
  for (std::size_t at = 0; at + sizeof pair <= snap.size(); ++at)
    if (std::memcmp(&snap[at], pair, sizeof pair) == 0) found.push_back(at);
  ASSERT_EQ(found.size(), 1u);
  rc::WorldSnapshot bad = snap;
  std::memcpy(&bad[found[0]], &offShape.index, sizeof offShape.index);
  rc::World target;
  target.restore(snap);  // the bytes as they were are taken
  const std::uint64_t before = target.stateHash();
  try {
    target.restore(bad);
    ADD_FAILURE() << "a contact of a disabled body's shape was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a contact of a disabled body's shape"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(target.stateHash(), before);
}

TEST(Snapshot, OtherFormatsAndWorldsAreRefused) {
  rc::World w;
  w.createShape(w.createBody(dynamicAt({0, 1})), rc::makeCircle({}, 0.5f));
  rc::WorldSnapshot snap = w.snapshot();
  auto message = [](rc::World& target, std::span<const std::uint8_t> bytes) {
    try {
      target.restore(bytes);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("taken");
  };
  rc::World same;
  EXPECT_EQ(message(same, snap), "taken");
  rc::WorldSnapshot notOne = snap;
  notOne[0] ^= 0xFF;
  EXPECT_NE(message(same, notOne).find("not a world snapshot"), std::string::npos);
  rc::WorldSnapshot future = snap;
  future[4] = 99;
  EXPECT_NE(message(same, future).find("format 99"), std::string::npos);
  rc::WorldDef moon;
  moon.gravity = {0, -1.62f};
  rc::World elsewhere(moon);
  const std::string m = message(elsewhere, snap);
  EXPECT_NE(m.find("gravity.y is -10"), std::string::npos) << m;
  // The solver's width is not part of it: either width gives the same bits.
  rc::WorldDef narrow;
  narrow.maxSolverLanes = 4;
  rc::World four(narrow);
  EXPECT_EQ(message(four, snap), "taken");
  rc::WorldSnapshot longer = snap;
  longer.push_back(0);
  EXPECT_NE(message(same, longer).find("bytes after the end"), std::string::npos);
}

}  // namespace snapshot_test
