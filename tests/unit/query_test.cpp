// The world's queries (physics/query.cpp) against brute force: every query on a random scene of
// a few hundred mixed shapes compared, for 1,000 random queries each, with the exact geometry
// function run over every shape of the scene (rc::rayCast, rc::shapeCast, rc::testOverlap,
// rc::containsPoint, rc::computeAABB). The world and the brute force call the same exact
// function with the same input, so they must agree bit for bit: what is tested is that the
// broadphase, the filters and the bookkeeping lose nothing, add nothing and order as documented
// (closest hit, ties to the lower shape id; all hits by fraction, then shape id; overlaps by
// shape id).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <vector>

#include "physics/collide.h"
#include "physics/distance.h"
#include "physics/random.h"
#include "physics/raycast.h"
#include "physics/toi.h"
#include "physics/world.h"
#include "support/random_shapes.h"
#include "support/world_scenes.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace query_test {

using rc::BodyId;
using rc::BodyType;
using rc::ShapeId;
using rc::Vec2;
using rc::testing::dynamicAt;
using rc::testing::ground;
using rc::testing::Kind;

constexpr int kQueries = 1000;
constexpr float kHalf = 25.0f;  // the scene fills [-25, 25]^2

std::uint64_t bodyData(std::int32_t index) {
  return 0xB0D1000000000000ull + static_cast<std::uint64_t>(index) * 7919u;
}
std::uint64_t shapeData(std::int32_t index) {
  return 0x5A9E000000000000ull + static_cast<std::uint64_t>(index) * 104729u;
}

// A random scene: ~300 shapes on dynamic and kinematic bodies (circles, boxes, oriented boxes,
// capsules, polygons sharp and rounded; one body in six carries two), static segments and chain
// links, a few sensors, three categories of filter. Bodies are destroyed, disabled and enabled
// again, and new ones made, so that slots are reused and the broadphase's proxy ids are no
// longer in shape order; then the world is stepped (no gravity, random velocities) so proxies
// move. Disabled bodies stay in it: queries must not find them.
struct Scene {
  rc::World w;
  std::vector<BodyId> disabled;
};

Scene makeScene(std::uint64_t seed) {
  rc::WorldDef def;
  def.gravity = {0, 0};
  Scene scene{rc::World(def), {}};
  rc::World& w = scene.w;
  rc::Random rng(seed);
  const Kind solids[] = {Kind::circle,  Kind::box,     Kind::orientedBox,
                         Kind::capsule, Kind::polygon, Kind::roundedPolygon};
  auto shapeDef = [&](bool sensor) {
    rc::ShapeDef sd;
    sd.isSensor = sensor;
    sd.filter.category = 1u << rng.below(3);
    sd.filter.mask = rng.below(4) == 0 ? (0xFFFFFFFFu & ~(1u << rng.below(3))) : 0xFFFFFFFFu;
    return sd;
  };
  auto addBody = [&] {
    const Vec2 p = rng.inBox({-kHalf, -kHalf}, {kHalf, kHalf});
    if (rng.below(8) == 0) {
      // Static: segments and chain links.
      BodyId b = w.createBody(rc::testing::bodyAt(BodyType::staticBody, p, rng.uniform(-3, 3)));
      const int n = 1 + static_cast<int>(rng.below(3));
      for (int k = 0; k < n; ++k) {
        const Kind kind = rng.below(2) ? Kind::segment : Kind::chainLink;
        w.createShape(b, rc::testing::randomShape(rng, kind), shapeDef(false));
      }
      return b;
    }
    rc::BodyDef bd = rc::testing::bodyAt(
        rng.below(6) == 0 ? BodyType::kinematicBody : BodyType::dynamicBody, p, rng.uniform(-3, 3));
    bd.linearVelocity = rng.inBox({-5, -5}, {5, 5});
    bd.angularVelocity = rng.uniform(-2, 2);
    BodyId b = w.createBody(bd);
    const int n = rng.below(6) == 0 ? 2 : 1;
    for (int k = 0; k < n; ++k)
      w.createShape(b, rc::testing::randomShape(rng, solids[rng.below(6)]),
                    shapeDef(rng.below(20) == 0));
    return b;
  };
  std::vector<BodyId> bodies;
  for (int i = 0; i < 260; ++i)
    bodies.push_back(addBody());
  // Slots freed and taken again, proxies recreated in another order.
  for (int i = 0; i < 20; ++i) {
    const std::size_t k = rng.below(static_cast<std::uint32_t>(bodies.size()));
    if (!w.isValid(bodies[k])) continue;
    w.destroyBody(bodies[k]);
  }
  std::vector<BodyId> toggled;
  for (int i = 0; i < 30; ++i) {
    const BodyId b = bodies[rng.below(static_cast<std::uint32_t>(bodies.size()))];
    if (!w.isValid(b) || !w.isEnabled(b)) continue;
    w.setEnabled(b, false);
    toggled.push_back(b);
  }
  for (int i = 0; i < 20; ++i)
    bodies.push_back(addBody());
  for (std::size_t i = 0; i < toggled.size(); ++i) {
    if (i % 3 == 0)
      scene.disabled.push_back(toggled[i]);  // stays disabled
    else
      w.setEnabled(toggled[i], true);
  }
  rc::testing::stepN(w, 10);
  // User data from the ids, so that a ShapeRef can be checked against its names.
  for (BodyId b : w.bodies()) {
    w.setUserData(b, bodyData(b.index));
    for (ShapeId s : w.shapesOf(b))
      w.setUserData(s, shapeData(s.index));
  }
  return scene;
}

// Every shape a query may consider: of enabled bodies, with its placement.
struct Candidate {
  ShapeId shape;
  BodyId body;
  rc::Transform xf;
};
std::vector<Candidate> candidates(const rc::World& w) {
  std::vector<Candidate> out;
  for (BodyId b : w.bodies()) {
    if (!w.isEnabled(b)) continue;
    for (ShapeId s : w.shapesOf(b))
      out.push_back({s, b, w.transform(b)});
  }
  std::sort(out.begin(), out.end(),
            [](const Candidate& a, const Candidate& b) { return a.shape.index < b.shape.index; });
  return out;
}

bool passes(const rc::World& w, const rc::QueryFilter& filter, const Candidate& c) {
  return rc::shouldCollide(filter.bits, w.filter(c.shape)) &&
         (!filter.accept || filter.accept(w.ref(c.shape)));
}

// Brute force of a cast: every solid, accepted shape's exact result; sorted by fraction, then
// shape id (the first is the closest hit, ties to the lower shape id).
struct BruteHit {
  ShapeId shape;
  rc::CastOutput out;
};
std::vector<BruteHit> bruteCast(const rc::World& w, const std::vector<Candidate>& all,
                                const rc::QueryFilter& filter,
                                const std::function<rc::CastOutput(const Candidate&)>& exact) {
  std::vector<BruteHit> hits;
  for (const Candidate& c : all) {
    if (w.isSensor(c.shape) || !passes(w, filter, c)) continue;
    const rc::CastOutput out = exact(c);
    if (out.hit) hits.push_back({c.shape, out});
  }
  std::stable_sort(hits.begin(), hits.end(), [](const BruteHit& a, const BruteHit& b) {
    return a.out.fraction < b.out.fraction;
  });
  return hits;
}

std::vector<ShapeId> bruteOverlap(const rc::World& w, const std::vector<Candidate>& all,
                                  const rc::QueryFilter& filter,
                                  const std::function<bool(const Candidate&)>& exact) {
  std::vector<ShapeId> out;
  for (const Candidate& c : all)
    if (passes(w, filter, c) && exact(c)) out.push_back(c.shape);
  return out;
}

// A ShapeRef names the shape, its body and both user data as they are.
::testing::AssertionResult namesRightly(const rc::World& w, const rc::ShapeRef& r) {
  if (!w.isValid(r.shape) || !w.isValid(r.body))
    return ::testing::AssertionFailure() << "stale shape " << r.shape.index;
  if (!(w.bodyOf(r.shape) == r.body))
    return ::testing::AssertionFailure()
           << "shape " << r.shape.index << " named with body " << r.body.index << ", not its own";
  if (r.shapeUserData != w.userData(r.shape) || r.bodyUserData != w.userData(r.body) ||
      r.shapeUserData != shapeData(r.shape.index) || r.bodyUserData != bodyData(r.body.index))
    return ::testing::AssertionFailure() << "shape " << r.shape.index << ": wrong user data";
  if (!w.isEnabled(r.body))
    return ::testing::AssertionFailure() << "shape " << r.shape.index << " of a disabled body";
  return ::testing::AssertionSuccess();
}

// A random filter: none (half the queries), a bitmask, ignoring one body, or a callback that
// refuses every other shape (odd shape indices).
rc::QueryFilter randomFilter(rc::Random& rng, const std::vector<Candidate>& all) {
  switch (rng.below(6)) {
    case 0:
      return rc::ProxyFilter{1u << rng.below(3), 0xFFFFFFFFu & ~(1u << rng.below(3))};
    case 1:
      return rc::QueryFilter::ignoring(all[rng.below(static_cast<std::uint32_t>(all.size()))].body);
    case 2:
      return rc::QueryFilter({}, [](const rc::ShapeRef& s) { return s.shape.index % 2 == 0; });
    default:
      return {};
  }
}

// A cast's start: anywhere in the scene, or (one time in four) inside a random shape's reach.
Vec2 randomStart(rc::Random& rng, const std::vector<Candidate>& all) {
  if (rng.below(4) == 0)
    return all[rng.below(static_cast<std::uint32_t>(all.size()))].xf.p +
           rng.inBox({-0.3f, -0.3f}, {0.3f, 0.3f});
  return rng.inBox({-kHalf - 5, -kHalf - 5}, {kHalf + 5, kHalf + 5});
}
// 0.05 to 60 m (log-uniform) in any direction; one in fifty of length zero.
Vec2 randomTranslation(rc::Random& rng) {
  if (rng.below(50) == 0) return {0, 0};
  const float length = 0.05f * std::pow(1200.0f, rng.uniform());
  const float angle = rng.uniform(-3.14159f, 3.14159f);
  return {length * std::cos(angle), length * std::sin(angle)};
}

// A solid query shape about its origin (segments have no overlap test with segments).
rc::Shape randomQueryShape(rc::Random& rng) {
  const Kind kinds[] = {Kind::circle,  Kind::box,     Kind::orientedBox,
                        Kind::capsule, Kind::polygon, Kind::roundedPolygon};
  return rc::testing::randomShape(rng, kinds[rng.below(6)]);
}

::testing::AssertionResult sameHit(const rc::World& w, const std::optional<rc::WorldHit>& got,
                                   const std::vector<BruteHit>& brute) {
  if (!got.has_value() && brute.empty()) return ::testing::AssertionSuccess();
  if (got.has_value() != !brute.empty())
    return ::testing::AssertionFailure()
           << (got ? "world hit shape " + std::to_string(got->shape.index) + ", brute force none"
                   : "world none, brute force shape " + std::to_string(brute[0].shape.index) +
                         " at " + std::to_string(brute[0].out.fraction));
  const BruteHit& b = brute[0];
  if (!(got->shape == b.shape) || got->fraction != b.out.fraction || got->point != b.out.point ||
      got->normal != b.out.normal)
    return ::testing::AssertionFailure()
           << "world shape " << got->shape.index << " at " << got->fraction
           << ", brute force shape " << b.shape.index << " at " << b.out.fraction;
  return namesRightly(w, *got);
}

struct Tally {
  int queries = 0, hit = 0, found = 0;
};

class Queries : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(makeScene(2024));
    all_ = new std::vector<Candidate>(candidates(scene_->w));
  }
  static void TearDownTestSuite() {
    delete all_;
    delete scene_;
    all_ = nullptr;
    scene_ = nullptr;
  }
  static Scene* scene_;
  static std::vector<Candidate>* all_;
};
Scene* Queries::scene_ = nullptr;
std::vector<Candidate>* Queries::all_ = nullptr;

TEST_F(Queries, SceneIsWhatItShouldBe) {
  const rc::World& w = scene_->w;
  int sensors = 0, segments = 0, compound = 0;
  for (const Candidate& c : *all_) {
    sensors += w.isSensor(c.shape);
    segments += !w.shape(c.shape).isSolid();
  }
  for (BodyId b : w.bodies())
    compound += w.shapesOf(b).size() > 1;
  std::printf(
      "%zu shapes on %d bodies (%zu disabled): %d sensors, %d segments and links, %d "
      "bodies of two shapes\n",
      all_->size(), w.bodyCount(), scene_->disabled.size(), sensors, segments, compound);
  EXPECT_GT(all_->size(), 250u);
  EXPECT_GT(sensors, 3);
  EXPECT_GT(segments, 20);
  EXPECT_GT(compound, 20);
  EXPECT_GE(scene_->disabled.size(), 5u);
}

TEST_F(Queries, CastRayMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(1);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const Vec2 origin = randomStart(rng, *all_), translation = randomTranslation(rng);
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const rc::RayCastInput in{origin, translation, 1.0f};
    const auto brute = bruteCast(w, *all_, filter, [&](const Candidate& c) {
      return rc::rayCast(w.shape(c.shape), c.xf, in);
    });
    const auto got = w.castRay(origin, translation, filter);
    ASSERT_TRUE(sameHit(w, got, brute)) << "ray " << q;
    t.hit += got.has_value();
  }
  std::printf("%d of %d rays hit\n", t.hit, kQueries);
  EXPECT_GT(t.hit, kQueries / 4);
}

TEST_F(Queries, CastRayAllMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(2);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const Vec2 origin = randomStart(rng, *all_), translation = randomTranslation(rng);
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const rc::RayCastInput in{origin, translation, 1.0f};
    const auto brute = bruteCast(w, *all_, filter, [&](const Candidate& c) {
      return rc::rayCast(w.shape(c.shape), c.xf, in);
    });
    const auto got = w.castRayAll(origin, translation, filter);
    ASSERT_EQ(got.size(), brute.size()) << "ray " << q;
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].shape, brute[k].shape) << "ray " << q << " hit " << k;
      ASSERT_EQ(got[k].fraction, brute[k].out.fraction) << "ray " << q << " hit " << k;
      ASSERT_EQ(got[k].point, brute[k].out.point) << "ray " << q << " hit " << k;
      ASSERT_TRUE(namesRightly(w, got[k])) << "ray " << q;
    }
    t.found += static_cast<int>(got.size());
  }
  std::printf("%d hits of %d rays\n", t.found, kQueries);
  EXPECT_GT(t.found, kQueries / 2);
}

TEST_F(Queries, CastCircleMatchesBruteForceAndCastShape) {
  const rc::World& w = scene_->w;
  rc::Random rng(3);
  Tally t;
  float worstGap = 0;
  for (int q = 0; q < kQueries; ++q) {
    const Vec2 centre = randomStart(rng, *all_), translation = randomTranslation(rng);
    const float radius = rng.uniform(0.02f, 1.0f);
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const rc::ShapeProxy disc = rc::makeProxy(&centre, 1, radius);
    const auto brute = bruteCast(w, *all_, filter, [&](const Candidate& c) {
      return rc::shapeCast(disc, rc::Transform{}, translation, rc::makeProxy(w.shape(c.shape)),
                           c.xf);
    });
    const auto got = w.castCircle(centre, radius, translation, filter);
    ASSERT_TRUE(sameHit(w, got, brute)) << "circle " << q;
    t.hit += got.has_value();
    // The same circle as a shape placed at the centre: the same cast in another frame, so the
    // same shape (or a tie within the cast's tolerance) at the same distance within it.
    const auto asShape =
        w.castShape(rc::makeCircle({}, radius), {centre, rc::Rot{}}, translation, filter);
    ASSERT_EQ(asShape.has_value(), got.has_value()) << "circle " << q;
    if (!got) continue;
    const float gap = std::abs(asShape->fraction - got->fraction) * rc::length(translation);
    worstGap = std::max(worstGap, gap);
    ASSERT_LE(gap, 0.25f * rc::kLinearSlop) << "circle " << q;
    if (!(asShape->shape == got->shape)) {
      // Another shape only if the brute force has it within the tolerance too.
      const auto other = std::find_if(brute.begin(), brute.end(),
                                      [&](const BruteHit& b) { return b.shape == asShape->shape; });
      ASSERT_NE(other, brute.end()) << "circle " << q;
      ASSERT_LE((other->out.fraction - got->fraction) * rc::length(translation),
                0.25f * rc::kLinearSlop)
          << "circle " << q;
    }
  }
  std::printf("%d of %d circles hit; castShape within %.2e m of castCircle\n", t.hit, kQueries,
              worstGap);
  EXPECT_GT(t.hit, kQueries / 4);
}

TEST_F(Queries, CastShapeMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(4);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const rc::Shape shape = randomQueryShape(rng);
    const rc::Transform start{randomStart(rng, *all_), rc::Rot::fromAngle(rng.uniform(-3, 3))};
    const Vec2 translation = randomTranslation(rng);
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const rc::ShapeProxy mover = rc::makeProxy(shape);
    const auto brute = bruteCast(w, *all_, filter, [&](const Candidate& c) {
      return rc::shapeCast(mover, start, translation, rc::makeProxy(w.shape(c.shape)), c.xf);
    });
    const auto got = w.castShape(shape, start, translation, filter);
    ASSERT_TRUE(sameHit(w, got, brute))
        << "cast " << q << " of a " << rc::shapeTypeName(shape.type);
    t.hit += got.has_value();
  }
  std::printf("%d of %d shape casts hit\n", t.hit, kQueries);
  EXPECT_GT(t.hit, kQueries / 4);
}

TEST_F(Queries, OverlapAABBMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(5);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const Vec2 lo = randomStart(rng, *all_);
    const rc::AABB box{lo, lo + rng.inBox({0, 0}, {6, 6})};
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const auto brute = bruteOverlap(w, *all_, filter, [&](const Candidate& c) {
      return rc::overlaps(rc::computeAABB(w.shape(c.shape), c.xf), box);
    });
    const auto got = w.overlapAABB(box, filter);
    ASSERT_EQ(got.size(), brute.size()) << "box " << q;
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].shape, brute[k]) << "box " << q;
      ASSERT_TRUE(namesRightly(w, got[k])) << "box " << q;
    }
    t.found += static_cast<int>(got.size());
  }
  std::printf("%d shapes in %d boxes\n", t.found, kQueries);
  EXPECT_GT(t.found, kQueries);
}

TEST_F(Queries, OverlapPointMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(6);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const Vec2 p = randomStart(rng, *all_);
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const auto brute = bruteOverlap(w, *all_, filter, [&](const Candidate& c) {
      return rc::containsPoint(w.shape(c.shape), c.xf, p);
    });
    const auto got = w.overlapPoint(p, filter);
    ASSERT_EQ(got.size(), brute.size()) << "point " << q;
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].shape, brute[k]) << "point " << q;
      ASSERT_TRUE(namesRightly(w, got[k])) << "point " << q;
    }
    t.found += static_cast<int>(got.size());
  }
  std::printf("%d shapes contain %d points\n", t.found, kQueries);
  EXPECT_GT(t.found, kQueries / 10);
}

TEST_F(Queries, OverlapShapeMatchesBruteForce) {
  const rc::World& w = scene_->w;
  rc::Random rng(7);
  Tally t;
  for (int q = 0; q < kQueries; ++q) {
    const rc::Shape shape = randomQueryShape(rng);
    const rc::Transform where{randomStart(rng, *all_), rc::Rot::fromAngle(rng.uniform(-3, 3))};
    const rc::QueryFilter filter = randomFilter(rng, *all_);
    const auto brute = bruteOverlap(w, *all_, filter, [&](const Candidate& c) {
      return rc::testOverlap(shape, where, w.shape(c.shape), c.xf);
    });
    const auto got = w.overlapShape(shape, where, filter);
    ASSERT_EQ(got.size(), brute.size()) << "shape " << q;
    for (std::size_t k = 0; k < got.size(); ++k) {
      ASSERT_EQ(got[k].shape, brute[k]) << "shape " << q;
      ASSERT_TRUE(namesRightly(w, got[k])) << "shape " << q;
    }
    t.found += static_cast<int>(got.size());
  }
  std::printf("%d shapes overlap %d query shapes\n", t.found, kQueries);
  EXPECT_GT(t.found, kQueries / 2);
}

// QueryFilter::ignoring: rays fired from inside a body's shape (the shooter's muzzle) outward
// never name the shooter, and find what the brute force finds without it; without the filter
// the shooter is hit at once (fraction 0): the filter is what keeps it out. A callback refusing
// every other shape refuses exactly those.
TEST_F(Queries, FiltersKeepTheShooterOut) {
  const rc::World& w = scene_->w;
  rc::Random rng(8);
  // Every category, every mask: the default query (category 1) misses shapes whose masks refuse
  // category 1.
  const rc::ProxyFilter seeAll{0xFFFFFFFFu, 0xFFFFFFFFu};
  int shooters = 0, otherHits = 0;
  for (const Candidate& c : *all_) {
    if (w.isSensor(c.shape) || !w.shape(c.shape).isSolid()) continue;
    const rc::BoundingCircle bound = rc::computeBoundingCircle(w.shape(c.shape));
    const Vec2 muzzle = rc::apply(c.xf, bound.center);
    if (!rc::containsPoint(w.shape(c.shape), c.xf, muzzle)) continue;
    ++shooters;
    for (int k = 0; k < 4; ++k) {
      const float a = rng.uniform(-3.14159f, 3.14159f);
      const Vec2 shot = 30.0f * Vec2{std::cos(a), std::sin(a)};
      const auto plain = w.castRay(muzzle, shot, seeAll);
      ASSERT_TRUE(plain.has_value());
      ASSERT_EQ(plain->fraction, 0.0f);
      const rc::QueryFilter notMe = rc::QueryFilter::ignoring(c.body, seeAll);
      const auto got = w.castRay(muzzle, shot, notMe);
      if (got) {
        ASSERT_FALSE(got->body == c.body);
        ++otherHits;
      }
      const rc::RayCastInput in{muzzle, shot, 1.0f};
      const auto brute = bruteCast(w, *all_, notMe, [&](const Candidate& o) {
        return o.body == c.body ? rc::CastOutput{} : rc::rayCast(w.shape(o.shape), o.xf, in);
      });
      ASSERT_TRUE(sameHit(w, got, brute));
      for (const rc::WorldHit& h : w.castRayAll(muzzle, shot, notMe))
        ASSERT_FALSE(h.body == c.body);
      for (const rc::ShapeRef& r :
           w.overlapShape(rc::makeCircle({}, 0.5f), {muzzle, rc::Rot{}}, notMe))
        ASSERT_FALSE(r.body == c.body);
    }
  }
  std::printf("%d shooters, %d shots hit something else\n", shooters, otherHits);
  EXPECT_GT(shooters, 100);
  EXPECT_GT(otherHits, 50);

  // Refusing every other shape: none of them in any result, and all of the others.
  const rc::QueryFilter evenOnly(seeAll,
                                 [](const rc::ShapeRef& s) { return s.shape.index % 2 == 0; });
  const rc::AABB everything{{-60, -60}, {60, 60}};
  const auto found = w.overlapAABB(everything, evenOnly);
  std::size_t even = 0;
  for (const Candidate& c : *all_)
    even += c.shape.index % 2 == 0;
  EXPECT_EQ(found.size(), even);
  for (const rc::ShapeRef& r : found)
    ASSERT_EQ(r.shape.index % 2, 0);
}

// Ties: two boxes overlapping, a ray starting inside both (both hit at fraction 0) and a cast
// that meets both faces at once. The closest hit is the lower shape id, and castRayAll lists
// the lower first, whatever order their broadphase proxies are in: the two bodies are disabled
// and enabled so that their proxies' ids come back swapped (the broadphase reuses ids last freed
// first).
TEST(Query, TiesGoToTheLowerShapeId) {
  for (bool swapped : {false, true}) {
    rc::World w;
    BodyId a = w.createBody({});
    ShapeId sa = w.createShape(a, rc::makeBox(1, 1, {0, 0}));
    BodyId b = w.createBody({});
    ShapeId sb = w.createShape(b, rc::makeBox(1, 1, {0.5f, 0}));
    ASSERT_LT(sa.index, sb.index);
    if (swapped) {
      w.setEnabled(a, false);
      w.setEnabled(b, false);
      w.setEnabled(a, true);  // takes b's proxy id, the last freed
      w.setEnabled(b, true);
    }
    const auto inside = w.castRay({0.2f, 0}, {5, 0});
    ASSERT_TRUE(inside.has_value());
    EXPECT_EQ(inside->fraction, 0.0f);
    EXPECT_EQ(inside->shape, sa) << (swapped ? "proxies swapped" : "proxies in order");
    const auto all = w.castRayAll({0.2f, 0}, {5, 0});
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0].shape, sa) << (swapped ? "proxies swapped" : "proxies in order");
    // From above, both top faces (y = 1) at the same fraction.
    const auto down = w.castRay({0.25f, 5}, {0, -10});
    ASSERT_TRUE(down.has_value());
    EXPECT_EQ(down->shape, sa) << (swapped ? "proxies swapped" : "proxies in order");
    const auto circle = w.castCircle({0.25f, 5}, 0.1f, {0, -10});
    ASSERT_TRUE(circle.has_value());
    EXPECT_EQ(circle->shape, sa) << (swapped ? "proxies swapped" : "proxies in order");
  }
}

TEST(World, QueriesFindWhatTheyShould) {
  rc::World w;
  BodyId g = ground(w);  // top face at y = 0
  BodyId low = w.createBody(dynamicAt({0, 1}));
  rc::ShapeId lowShape = w.createShape(low, rc::makeBox(0.5f, 0.5f));
  BodyId high = w.createBody(dynamicAt({0, 4}));
  rc::ShapeDef ghost;
  ghost.filter = {4, 0xFFFFFFFFu};
  rc::ShapeId highShape = w.createShape(high, rc::makeCircle({}, 0.5f), ghost);
  // Straight down from 10 m: the circle's top at 4.5 m first, then the box's top at 1.5 m.
  auto hit = w.castRay({0, 10}, {0, -20});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->shape, highShape);
  EXPECT_EQ(hit->body, high);
  EXPECT_NEAR(hit->point.y, 4.5f, 1e-5f);
  EXPECT_NEAR(hit->fraction, 5.5f / 20.0f, 1e-6f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-6f);
  // Filtered: the circle's category is not in the mask.
  hit = w.castRay({0, 10}, {0, -20}, rc::ProxyFilter{1, 1});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->shape, lowShape);
  EXPECT_NEAR(hit->point.y, 1.5f, 1e-5f);
  auto all = w.castRayAll({0, 10}, {0, -20});
  ASSERT_EQ(all.size(), 3u);  // circle, box, ground
  EXPECT_EQ(all[0].shape, highShape);
  EXPECT_EQ(all[1].shape, lowShape);
  EXPECT_EQ(all[2].body, g);
  EXPECT_TRUE(all[0].fraction < all[1].fraction && all[1].fraction < all[2].fraction);
  // A circle of radius 0.25 swept down beside the ball hits the box's top edge earlier by its
  // radius: at y = 1.75 m for its centre.
  auto swept = w.castCircle({0.3f, 3.0f}, 0.25f, {0, -3});
  ASSERT_TRUE(swept.has_value());
  EXPECT_EQ(swept->shape, lowShape);
  EXPECT_NEAR(3.0f - 3.0f * swept->fraction, 1.75f, 0.002f);  // within the cast's tolerance
  EXPECT_NEAR(swept->normal.y, 1.0f, 1e-4f);
  EXPECT_FALSE(w.castRay({5, 10}, {0, 5}).has_value());  // going up, nothing there
  // Point and box overlaps.
  const std::vector<rc::ShapeRef> inBox = w.overlapPoint({0.2f, 1.2f});
  ASSERT_EQ(inBox.size(), 1u);
  EXPECT_EQ(inBox[0].shape, lowShape);
  EXPECT_EQ(inBox[0].body, low);
  EXPECT_EQ(w.overlapPoint({0.45f, 4.45f}).size(), 0u);  // in the ball's box, not in the ball
  EXPECT_EQ(w.overlapAABB({{-0.1f, 0.9f}, {0.1f, 4.1f}}).size(), 2u);
  EXPECT_THROW(w.castRay({0, std::numeric_limits<float>::quiet_NaN()}, {0, 1}),
               rc::InvalidDefinition);
}

}  // namespace query_test
