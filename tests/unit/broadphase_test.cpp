// The quadtree broadphase (physics/broadphase.h) against its brute-force twin: seeded random
// scenes (uniform, clustered, straddling cell edges, huge, tiny, outside the world, moving for
// many steps with inserts and removes) must give exactly the same pair sets and query results,
// and validate() must hold after every step. Plus the degenerate scenes of the issue and the
// bad input it must reject.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "physics/broadphase.h"
#include "physics/random.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace broadphase_test {

using rc::AABB;
using rc::ProxyId;
using rc::Vec2;

const AABB kWorld{{-100, -100}, {100, 100}};

rc::ProxyDef moving(const AABB& box) {
  rc::ProxyDef def;
  def.aabb = box;
  return def;
}
rc::ProxyDef fixed(const AABB& box) {
  rc::ProxyDef def;
  def.aabb = box;
  def.isStatic = true;
  return def;
}

AABB boxAt(Vec2 c, Vec2 half) {
  return {c - half, c + half};
}

// The exact shape behind each proxy in these tests: the disc inscribed in its fat AABB (so
// some AABB candidates are misses), or the fat AABB itself (so a cell the traversal skips shows
// up even when only a corner of a proxy sticks into the cast), grown by the cast's radius.
rc::CastOutput exactCast(const rc::ProxyStore& bp, ProxyId id, const rc::RayCastInput& in,
                         float radius, bool disc) {
  const AABB& fat = bp.fatAABB(id);
  Vec2 e = fat.extents();
  if (disc) return rc::rayCast(rc::Circle{fat.center(), std::min(e.x, e.y) + radius}, in);
  return rc::rayCast(rc::Box{fat.center(), e + Vec2{radius, radius}}, in);
}

bool sameHit(const rc::ProxyHit& a, const rc::ProxyHit& b) {
  return a.id == b.id && a.out.hit == b.out.hit && a.out.fraction == b.out.fraction;
}

// Both broadphases driven by the same calls, and the pair set a contact manager would keep
// from updatePairs (new pairs added, pairs whose fat AABBs parted or whose proxy died dropped).
struct Twin {
  rc::Quadtree tree{kWorld, 8};
  rc::BruteForce brute;
  std::vector<ProxyId> live;
  std::vector<rc::ProxyPair> kept;

  ProxyId add(const rc::ProxyDef& def) {
    ProxyId a = tree.createProxy(def), b = brute.createProxy(def);
    EXPECT_EQ(a, b);
    live.push_back(a);
    return a;
  }
  void remove(std::size_t index) {
    ProxyId id = live[index];
    tree.destroyProxy(id);
    brute.destroyProxy(id);
    live.erase(live.begin() + static_cast<std::ptrdiff_t>(index));
    std::erase_if(kept, [&](const rc::ProxyPair& p) { return p.a == id || p.b == id; });
  }
  // Every hit of one cast through the tree and through brute force (exactCast's shapes): the
  // same hits in the same order. `hits` (if given) gets the tree's.
  ::testing::AssertionResult sameCastAll(const rc::RayCastInput& in, float radius, bool disc,
                                         rc::ProxyFilter filter = {},
                                         std::vector<rc::ProxyHit>* hits = nullptr) const {
    const auto a =
        rc::castAll(tree, in, radius, filter, [&](ProxyId id, const rc::RayCastInput& r) {
          return exactCast(tree, id, r, radius, disc);
        });
    const auto b =
        rc::castAll(brute, in, radius, filter, [&](ProxyId id, const rc::RayCastInput& r) {
          return exactCast(brute, id, r, radius, disc);
        });
    if (hits != nullptr) *hits = a;
    if (a.size() != b.size())
      return ::testing::AssertionFailure() << a.size() << " hits, brute force " << b.size();
    for (std::size_t k = 0; k < a.size(); ++k)
      if (!sameHit(a[k], b[k])) return ::testing::AssertionFailure() << "hit " << k << " differs";
    return ::testing::AssertionSuccess();
  }
  void move(ProxyId id, const AABB& box, Vec2 displacement = {}) {
    EXPECT_EQ(tree.moveProxy(id, box, displacement), brute.moveProxy(id, box, displacement));
  }
  // Pairs and a set of queries must agree exactly.
  void check(rc::Random& rng, const std::string& what) {
    ASSERT_NO_THROW(tree.validate()) << what;
    std::vector<rc::ProxyPair> pt, pb;
    tree.findPairs(pt);
    brute.findPairs(pb);
    ASSERT_EQ(pt.size(), pb.size()) << what;
    ASSERT_TRUE(pt == pb) << what;

    std::vector<rc::ProxyPair> nt, nb;
    tree.updatePairs(nt);
    brute.updatePairs(nb);
    ASSERT_TRUE(nt == nb) << what << ": new pairs differ";
    ASSERT_TRUE(std::is_sorted(nt.begin(), nt.end()));
    std::erase_if(kept, [&](const rc::ProxyPair& p) {
      return !rc::overlaps(tree.fatAABB(p.a), tree.fatAABB(p.b));
    });
    std::vector<rc::ProxyPair> merged;
    std::set_union(kept.begin(), kept.end(), nt.begin(), nt.end(), std::back_inserter(merged));
    kept = merged;
    ASSERT_TRUE(kept == pt) << what << ": kept " << kept.size() << " pairs, findPairs "
                            << pt.size();
    ASSERT_NO_THROW(tree.validate()) << what;

    for (int q = 0; q < 20; ++q) {
      Vec2 c = rng.inBox({-150, -150}, {150, 150});
      AABB box = boxAt(c, {rng.uniform(0, 8), rng.uniform(0, 8)});
      rc::ProxyFilter f{1u << rng.below(3), 0xFFFFFFFFu};
      ASSERT_EQ(tree.queryAABB(box, f), brute.queryAABB(box, f)) << what << " query " << q;
      ASSERT_EQ(tree.queryPoint(c), brute.queryPoint(c)) << what << " point " << q;
    }
    for (int q = 0; q < 40; ++q)
      checkCast(rng, what + " cast " + std::to_string(q));
  }

  void checkCast(rc::Random& rng, const std::string& what) {
    rc::RayCastInput in;
    in.origin = rng.inBox({-150, -150}, {150, 150});
    switch (rng.below(4)) {
      case 0:  // along a cell edge of the finest level, axis-aligned
        in.origin.x = -100.0f + 200.0f / 256.0f * static_cast<float>(rng.below(257));
        in.translation = {0, rng.uniform(-300, 300)};
        break;
      case 1:
        in.translation = {rng.uniform(-300, 300), 0};
        break;
      case 2:  // short
        in.translation = rng.inBox({-3, -3}, {3, 3});
        break;
      default:
        in.translation = rng.inBox({-300, -300}, {300, 300});
    }
    in.maxFraction = rng.below(2) == 0 ? 1.0f : rng.uniform(0, 1);
    const float radius = rng.below(2) == 0 ? 0.0f : rng.uniform(0, 3);
    rc::ProxyFilter f{1u << rng.below(3), 0xFFFFFFFFu};
    const bool disc = rng.below(2) == 0;
    auto exactTree = [&](ProxyId id, const rc::RayCastInput& r) {
      return exactCast(tree, id, r, radius, disc);
    };
    auto exactBrute = [&](ProxyId id, const rc::RayCastInput& r) {
      return exactCast(brute, id, r, radius, disc);
    };
    rc::ProxyHit ct = rc::castClosest(tree, in, radius, f, exactTree);
    rc::ProxyHit cb = rc::castClosest(brute, in, radius, f, exactBrute);
    ASSERT_TRUE(sameHit(ct, cb)) << what << ": closest " << ct.id << " at " << ct.out.fraction
                                 << ", brute force " << cb.id << " at " << cb.out.fraction;
    std::vector<rc::ProxyHit> at;
    ASSERT_TRUE(sameCastAll(in, radius, disc, f, &at)) << what;
    // And the brute force against a plain loop over the live proxies, no broadphase at all.
    rc::ProxyHit best;
    for (ProxyId id : live) {
      rc::CastOutput out = exactCast(brute, id, in, radius, disc);
      if (!rc::shouldCollide(f, brute.filter(id)) || !out.hit || out.fraction > in.maxFraction)
        continue;
      if (!best.out.hit || out.fraction < best.out.fraction ||
          (out.fraction == best.out.fraction && id < best.id))
        best = {id, out};
    }
    ASSERT_TRUE(sameHit(cb, best)) << what << ": brute force against the plain loop";
    ASSERT_TRUE(at.empty() || sameHit(at.front(), ct)) << what;
  }
};

enum class Layout { uniform, clustered, straddling, mixedSizes, outside };

Vec2 positionFor(rc::Random& rng, Layout layout) {
  switch (layout) {
    case Layout::uniform:
    case Layout::mixedSizes:
      return rng.inBox({-100, -100}, {100, 100});
    case Layout::clustered:
      return Vec2{20, -30} + rng.inBox({-2, -2}, {2, 2});
    case Layout::straddling: {
      // On the edges of cells at every level: multiples of 200 / 2^8 m, nudged by an ulp or so.
      float cell = 200.0f / 256.0f;
      auto snap = [&](float v) {
        return std::round(v / cell) * cell - 100.0f + rng.uniform(-1e-4f, 1e-4f);
      };
      return {snap(rng.uniform(0, 200)), snap(rng.uniform(0, 200))};
    }
    case Layout::outside:
      return rng.inBox({-400, -400}, {400, 400});
  }
  return {};
}

Vec2 sizeFor(rc::Random& rng, Layout layout) {
  if (layout == Layout::mixedSizes) {
    switch (rng.below(4)) {
      case 0:
        return {0, 0};  // zero-size (fat margin only)
      case 1:
        return {rng.uniform(0, 0.01f), rng.uniform(0, 0.01f)};
      case 2:
        return {rng.uniform(5, 60), rng.uniform(0.1f, 2)};  // walls
      default:
        return {rng.uniform(100, 300), rng.uniform(100, 300)};  // larger than the world
    }
  }
  return {rng.uniform(0.05f, 1.0f), rng.uniform(0.05f, 1.0f)};
}

void runScene(Layout layout, std::uint64_t seed, const char* name, int count = 400) {
  rc::Random rng(seed);
  Twin t;
  std::vector<Vec2> vel, pos, half;
  auto addOne = [&]() {
    rc::ProxyDef def;
    pos.push_back(positionFor(rng, layout));
    half.push_back(sizeFor(rng, layout));
    def.aabb = boxAt(pos.back(), half.back());
    def.isStatic = rng.below(4) == 0;
    def.filter.category = 1u << rng.below(3);
    def.filter.mask = rng.below(5) == 0 ? ~def.filter.category : 0xFFFFFFFFu;
    t.add(def);
    vel.push_back(def.isStatic ? Vec2{} : rng.inBox({-1, -1}, {1, 1}));
  };
  for (int i = 0; i < count; ++i)
    addOne();
  t.check(rng, std::string(name) + " initial");
  for (int step = 0; step < 60; ++step) {
    for (std::size_t i = 0; i < t.live.size(); ++i) {
      if (vel[i] == Vec2{}) continue;
      pos[i] += vel[i];
      // Half the movers report their displacement (fat AABBs stretched along the motion).
      t.move(t.live[i], boxAt(pos[i], half[i]), i % 2 == 0 ? vel[i] : Vec2{});
    }
    // Churn: remove and add a few every step.
    for (int k = 0; k < 5 && !t.live.empty(); ++k) {
      std::size_t index = rng.below(static_cast<std::uint32_t>(t.live.size()));
      t.remove(index);
      for (auto* v : {&vel, &pos, &half})
        v->erase(v->begin() + static_cast<std::ptrdiff_t>(index));
    }
    for (int k = 0; k < 5; ++k)
      addOne();
    if (step % 6 == 0) t.check(rng, std::string(name) + " step " + std::to_string(step));
  }
  t.check(rng, std::string(name) + " final");
}

TEST(Broadphase, ParityUniform) {
  runScene(Layout::uniform, 1, "uniform");
}
TEST(Broadphase, ParityClustered) {
  runScene(Layout::clustered, 2, "clustered");
}
TEST(Broadphase, ParityStraddlingCellEdges) {
  runScene(Layout::straddling, 3, "straddling");
}
TEST(Broadphase, ParityMixedSizes) {
  runScene(Layout::mixedSizes, 4, "mixed sizes");
}
TEST(Broadphase, ParityOutsideTheWorld) {
  runScene(Layout::outside, 5, "outside");
}
// Few proxies: below kBruteForceBelow the quadtree answers by brute force.
TEST(Broadphase, ParitySmallScenes) {
  static_assert(rc::Quadtree::kBruteForceBelow > 10);
  runScene(Layout::uniform, 7, "small uniform", 10);
  runScene(Layout::mixedSizes, 8, "small mixed", rc::Quadtree::kBruteForceBelow - 3);
}

// Closest-first traversal with early out: a closest-hit cast through a dense scene looks at a
// few dozen proxies, not all of them.
TEST(Broadphase, ClosestHitCastStopsEarly) {
  rc::Random rng(12);
  rc::Quadtree tree(AABB{{0, 0}, {256, 256}});
  std::vector<Vec2> centres;
  for (int i = 0; i < 8000; ++i) {  // one disc of radius 0.5 per 8 m^2
    centres.push_back(rng.inBox({0, 0}, {256, 256}));
    tree.createProxy(moving(boxAt(centres.back(), {0.5f, 0.5f})));
  }
  long candidates = 0, hits = 0;
  const int casts = 1000;
  for (int i = 0; i < casts; ++i) {
    rc::RayCastInput in{rng.inBox({0, 0}, {256, 256}), {}, 1};
    float angle = rng.uniform(0, 6.2831853f);
    in.translation = 50.0f * Vec2{std::cos(angle), std::sin(angle)};
    rc::ProxyHit h =
        rc::castClosest(tree, in, 0.0f, {}, [&](ProxyId id, const rc::RayCastInput& r) {
          ++candidates;
          return rc::rayCast(rc::Circle{centres[static_cast<std::size_t>(id)], 0.5f}, r);
        });
    hits += h.out.hit;
  }
  // Mean free path among these discs is 8 m, so nearly every 50 m ray hits; without clipping
  // at each hit each cast would test every proxy its 50 m pass touches (a band 1.2 m wide:
  // about 8 proxies), and in a random order about half of those. Measured: 1.6.
  EXPECT_GT(hits, casts * 95 / 100);
  EXPECT_LT(static_cast<double>(candidates) / casts, 2.5) << candidates;
}

TEST(Broadphase, UpdatePairsReportsOnlyPairsOfMovedProxies) {
  rc::Quadtree tree(kWorld);
  std::vector<rc::ProxyPair> pairs;
  ProxyId a = tree.createProxy(moving(boxAt({0, 0}, {1, 1})));
  ProxyId b = tree.createProxy(moving(boxAt({1.5f, 0}, {1, 1})));
  tree.updatePairs(pairs);
  ASSERT_EQ(pairs, (std::vector<rc::ProxyPair>{{a, b}}));
  tree.updatePairs(pairs);
  EXPECT_TRUE(pairs.empty());  // nothing moved
  // A wall added next to a resting mover pairs with it at once.
  ProxyId wall = tree.createProxy(fixed(boxAt({-1.5f, 0}, {0.5f, 5})));
  tree.updatePairs(pairs);
  EXPECT_EQ(pairs, (std::vector<rc::ProxyPair>{{a, wall}}));
  // A small move inside the fat AABB reports nothing; leaving it reports all its overlaps.
  EXPECT_FALSE(tree.moveProxy(b, boxAt({1.55f, 0}, {1, 1})));
  tree.updatePairs(pairs);
  EXPECT_TRUE(pairs.empty());
  EXPECT_TRUE(tree.moveProxy(b, boxAt({1.3f, 0}, {1, 1})));
  tree.updatePairs(pairs);
  EXPECT_EQ(pairs, (std::vector<rc::ProxyPair>{{a, b}}));
  tree.validate();
}

TEST(Broadphase, FatAABBFollowsTheMotionAndShrinksWhenItStops) {
  rc::Quadtree tree(kWorld);
  ProxyId id = tree.createProxy(moving(boxAt({0, 0}, {0.5f, 0.5f})));
  EXPECT_TRUE(tree.moveProxy(id, boxAt({0.5f, 0}, {0.5f, 0.5f}), {0.5f, 0}));
  AABB fat = tree.fatAABB(id);
  // Stretched by 3 x 0.5 m: kDisplacementMultiplier times the displacement would reach more
  // than kMaxPrediction beyond it.
  EXPECT_FLOAT_EQ(fat.upper.x, 1.0f + rc::kAabbMargin + rc::predictedStretch({0.5f, 0}).x);
  EXPECT_FLOAT_EQ(rc::predictedStretch({0.5f, 0}).x, 1.5f);
  EXPECT_FLOAT_EQ(rc::predictedStretch({0.05f, 0}).x, rc::kDisplacementMultiplier * 0.05f);
  EXPECT_FLOAT_EQ(fat.lower.x, -rc::kAabbMargin);
  // Moving on at the same speed stays inside for a few steps (with room for the next one).
  EXPECT_FALSE(tree.moveProxy(id, boxAt({1.0f, 0}, {0.5f, 0.5f}), {0.5f, 0}));
  EXPECT_FALSE(tree.moveProxy(id, boxAt({1.5f, 0}, {0.5f, 0.5f}), {0.5f, 0}));
  // At rest the stretched box is far larger than needed: it is refitted.
  EXPECT_TRUE(tree.moveProxy(id, boxAt({1.5f, 0}, {0.5f, 0.5f}), {0, 0}));
  EXPECT_EQ(tree.fatAABB(id), rc::inflate(boxAt({1.5f, 0}, {0.5f, 0.5f}), rc::kAabbMargin));
  tree.validate();
}

TEST(Broadphase, CastEdgeCases) {
  rc::Random rng(13);
  Twin t;
  for (int i = 0; i < 200; ++i)
    t.add(moving(boxAt(rng.inBox({-100, -100}, {100, 100}), {1, 1})));
  ProxyId target = t.add(moving(boxAt({0, 0}, {1, 1})));
  auto exact = [&](ProxyId id, const rc::RayCastInput& r) {
    return exactCast(t.tree, id, r, 0, false);
  };
  // Zero length: only what contains the origin, at fraction 0.
  rc::ProxyHit h = rc::castClosest(t.tree, {{0, 0}, {0, 0}, 1}, 0.0f, {}, exact);
  EXPECT_TRUE(h.out.hit);
  EXPECT_EQ(h.id, target);
  EXPECT_EQ(h.out.fraction, 0.0f);
  // From far outside the world, through it and out again.
  for (int q = 0; q < 50; ++q)
    t.checkCast(rng, "edge case " + std::to_string(q));
  rc::RayCastInput far{{-1e6f, 0.1f}, {2e6f, 0}, 1};
  EXPECT_TRUE(
      sameHit(rc::castClosest(t.tree, far, 0.0f, {}, exact),
              rc::castClosest(t.brute, far, 0.0f, {}, [&](ProxyId id, const rc::RayCastInput& r) {
                return exactCast(t.brute, id, r, 0, false);
              })));
  // Swept circles wider than the world (the walks' cell ranges clamped, not overflowing), and
  // casts allowed to run far past their translation.
  for (float radius : {150.0f, 1e6f}) {
    for (int q = 0; q < 10; ++q) {
      const rc::RayCastInput in{rng.inBox({-300, -300}, {300, 300}),
                                rng.inBox({-50, -50}, {50, 50}), q % 2 == 0 ? 1.0f : 1e30f};
      ASSERT_TRUE(t.sameCastAll(in, radius, true)) << "radius " << radius << " cast " << q;
    }
  }
  // Translations too small to invert (denormal: the inverse is infinite), run far past them.
  for (Vec2 tiny : {Vec2{1e-39f, 0}, Vec2{-1e-39f, 3e-39f}, Vec2{0, -2e-39f}}) {
    const rc::RayCastInput in{{0.25f, -0.5f}, tiny, 1e30f};
    ASSERT_TRUE(t.sameCastAll(in, 0.5f, true)) << tiny.x << ", " << tiny.y;
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto none = [](ProxyId, const rc::RayCastInput& r) { return r.maxFraction; };
  EXPECT_THROW(t.tree.cast({{nan, 0}, {1, 0}, 1}, 0.0f, {}, none), rc::InvalidProxy);
  EXPECT_THROW(t.tree.cast({{0, 0}, {1, 0}, nan}, 0.0f, {}, none), rc::InvalidProxy);
  EXPECT_THROW(t.tree.cast({{0, 0}, {1, 0}, 1}, -1.0f, {}, none), rc::InvalidProxy);
}

// A cast skips the levels where no proxy can pass its filter; a proxy whose filter changes
// in place (setFilter, no move) is still found under the new one.
TEST(Broadphase, CastsFollowAFilterChangedInPlace) {
  rc::Random rng(21);
  Twin t;
  for (int i = 0; i < 100; ++i)
    t.add(moving(boxAt(rng.inBox({-100, -100}, {100, 100}), {0.5f, 0.5f})));
  const ProxyId wall = t.add(fixed(boxAt({0, 0}, {20, 1})));  // alone on its level
  const ProxyId small = t.add(moving(boxAt({0, 10}, {0.5f, 0.5f})));
  auto closest = [&](const rc::ProxyStore& bp, Vec2 origin, rc::ProxyFilter f) {
    auto exact = [&](ProxyId id, const rc::RayCastInput& r) {
      return exactCast(bp, id, r, 0, false);
    };
    const rc::RayCastInput in{origin, {0, -40}, 1};
    return &bp == &t.tree ? rc::castClosest(t.tree, in, 0.0f, f, exact)
                          : rc::castClosest(t.brute, in, 0.0f, f, exact);
  };
  const rc::ProxyFilter seeks4{1, 4}, seeks8{1, 8};
  EXPECT_FALSE(closest(t.tree, {0, 20}, seeks4).out.hit);
  for (ProxyId id : {wall, small}) {
    t.tree.setFilter(id, {4, 0xFFFFFFFFu});
    t.brute.setFilter(id, {4, 0xFFFFFFFFu});
  }
  t.tree.validate();
  for (Vec2 origin : {Vec2{0, 20}, Vec2{0, 5}, Vec2{15, 5}}) {
    const rc::ProxyHit h = closest(t.tree, origin, seeks4);
    EXPECT_TRUE(h.out.hit) << origin.x << ", " << origin.y;
    EXPECT_EQ(h.id, origin.y > 10 && origin.x == 0 ? small : wall);
    EXPECT_TRUE(sameHit(h, closest(t.brute, origin, seeks4)));
    EXPECT_FALSE(closest(t.tree, origin, seeks8).out.hit);
  }
}

// Proxies as large as their cells, centred near a cell corner, stick out of their cell by
// almost half a cell: rays that only touch that part must still find them (a traversal that
// grows cells by less than half a cell fails here).
TEST(Broadphase, CastsFindProxiesStickingOutOfTheirCells) {
  rc::Random rng(11);
  Twin t;
  const float cell = 200.0f / 256.0f;  // finest level of kWorld at depth 8
  std::vector<AABB> tight;
  for (int i = 0; i < 300; ++i) {
    Vec2 corner{-100.0f + cell * static_cast<float>(1 + rng.below(254)),
                -100.0f + cell * static_cast<float>(1 + rng.below(254))};
    Vec2 c = corner + Vec2{rng.uniform(0, 0.01f), rng.uniform(0, 0.01f)} * cell;
    if (rng.below(2)) c = corner - Vec2{rng.uniform(0, 0.01f), rng.uniform(0, 0.01f)} * cell;
    float half = 0.5f * cell - rc::kAabbMargin;  // fat span = one cell: the finest level
    tight.push_back(boxAt(c, {half, half}));
    t.add(moving(tight.back()));
  }
  t.tree.validate();
  int hits = 0;
  for (std::size_t i = 0; i < t.live.size(); ++i) {
    const AABB& fat = t.tree.fatAABB(t.live[i]);
    // Grazing the fat box's far sides, along and across the axes.
    const rc::RayCastInput rays[] = {
        {{fat.lower.x + 1e-3f, fat.center().y - 3}, {0, 6}, 1},
        {{fat.upper.x - 1e-3f, fat.center().y + 3}, {0, -6}, 1},
        {{fat.center().x - 3, fat.lower.y + 1e-3f}, {6, 0}, 1},
        {{fat.center().x + 3, fat.upper.y - 1e-3f}, {-6, 0}, 1},
        {{fat.lower.x - 2, fat.lower.y + 2.002f}, {4, -4}, 1},  // across the corner
    };
    for (const rc::RayCastInput& in : rays) {
      std::vector<rc::ProxyHit> found;
      ASSERT_TRUE(t.sameCastAll(in, 0.0f, false, {}, &found)) << "proxy " << i;
      hits += static_cast<int>(found.size());
    }
  }
  EXPECT_GE(hits, 5 * 300);  // every ray hits at least the proxy it was aimed at
}

TEST(Broadphase, ThousandProxiesAtOnePoint) {
  rc::Random rng(6);
  Twin t;
  for (int i = 0; i < 1000; ++i)
    t.add(i % 10 == 0 ? fixed(boxAt({3, 4}, {0.5f, 0.5f})) : moving(boxAt({3, 4}, {0.5f, 0.5f})));
  t.check(rng, "same point");
  std::vector<rc::ProxyPair> pairs;
  t.tree.findPairs(pairs);
  // 900 movers pair with each other (900 * 899 / 2) and with the 100 statics (90,000).
  EXPECT_EQ(pairs.size(), 900u * 899u / 2u + 900u * 100u);
}

// A static proxy of a denormal size (a circle of radius 1e-39 m, which a scene file may give:
// the scene fuzzer's find) sits at the deepest level, and pairs like any other; the level was
// an infinite log2 cast to int before (undefined behaviour, caught by UBSan's
// float-cast-overflow).
TEST(Broadphase, ProxiesSmallerThanAnyCell) {
  rc::Quadtree tree(kWorld);
  const ProxyId speck = tree.createProxy(fixed(boxAt({3, 4}, {1e-39f, 1e-39f})));
  const ProxyId point = tree.createProxy(fixed(boxAt({-3, 4}, {0, 0})));
  const ProxyId mover = tree.createProxy(moving(boxAt({3, 4}, {0.5f, 0.5f})));
  const ProxyId other = tree.createProxy(moving(boxAt({-3, 4}, {0.5f, 0.5f})));
  tree.validate();
  std::vector<rc::ProxyPair> pairs;
  tree.findPairs(pairs);
  ASSERT_EQ(pairs.size(), 2u);
  auto has = [&](ProxyId a, ProxyId b) {
    return std::any_of(pairs.begin(), pairs.end(), [&](const rc::ProxyPair& p) {
      return (p.a == a && p.b == b) || (p.a == b && p.b == a);
    });
  };
  EXPECT_TRUE(has(speck, mover));
  EXPECT_TRUE(has(point, other));
}

TEST(Broadphase, FatAABBsSpareTheTree) {
  rc::Quadtree tree(kWorld);
  ProxyId id = tree.createProxy(moving(boxAt({0, 0}, {0.5f, 0.5f})));
  EXPECT_FALSE(tree.moveProxy(id, boxAt({0.05f, 0}, {0.5f, 0.5f})));  // within the margin
  EXPECT_TRUE(tree.moveProxy(id, boxAt({0.2f, 0}, {0.5f, 0.5f})));
  EXPECT_TRUE(tree.fatAABB(id).contains(boxAt({0.2f, 0}, {0.5f, 0.5f})));
  tree.validate();
}

TEST(Broadphase, StaticPairsNeverReported) {
  rc::Quadtree tree(kWorld);
  tree.createProxy(fixed(boxAt({0, 0}, {1, 1})));
  tree.createProxy(fixed(boxAt({0.5f, 0}, {1, 1})));
  std::vector<rc::ProxyPair> pairs;
  tree.findPairs(pairs);
  EXPECT_TRUE(pairs.empty());
  ProxyId mover = tree.createProxy(moving(boxAt({0.2f, 0}, {1, 1})));
  tree.findPairs(pairs);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], (rc::ProxyPair{0, mover}));
  EXPECT_EQ(pairs[1], (rc::ProxyPair{1, mover}));
}

TEST(Broadphase, BadInputRejected) {
  rc::Quadtree tree(kWorld);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_THROW(tree.createProxy(moving(AABB{{nan, 0}, {1, 1}})), rc::InvalidProxy);
  EXPECT_THROW(tree.createProxy(moving(AABB{{0, 0}, {inf, 1}})), rc::InvalidProxy);
  EXPECT_THROW(tree.createProxy(moving(AABB{{1, 0}, {0, 1}})), rc::InvalidProxy);  // inverted
  ProxyId id = tree.createProxy(moving(boxAt({0, 0}, {1, 1})));
  EXPECT_THROW(tree.moveProxy(id, AABB{{0, nan}, {1, 1}}), rc::InvalidProxy);
  EXPECT_THROW(tree.queryAABB(AABB{{nan, 0}, {1, 1}}), rc::InvalidProxy);
  EXPECT_THROW(tree.destroyProxy(id + 1), rc::InvalidProxy);
  tree.destroyProxy(id);
  EXPECT_THROW(tree.destroyProxy(id), rc::InvalidProxy);  // twice
  EXPECT_THROW(rc::Quadtree(AABB{{0, 0}, {0, 0}}), rc::InvalidProxy);
  EXPECT_THROW(rc::Quadtree(AABB{{0, nan}, {1, 1}}), rc::InvalidProxy);
  tree.validate();
}

}  // namespace broadphase_test
