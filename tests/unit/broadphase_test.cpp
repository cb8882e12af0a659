// The quadtree broadphase (physics/broadphase.h) against its brute-force twin: seeded random
// scenes (uniform, clustered, straddling cell edges, huge, tiny, outside the world, moving for
// many steps with inserts and removes) must give exactly the same pair sets and query results,
// and validate() must hold after every step. Plus the degenerate scenes of the issue and the
// bad input it must reject.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "physics/broadphase.h"
#include "physics/random.h"

namespace {

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

// Both broadphases driven by the same calls.
struct Twin {
  rc::Quadtree tree{kWorld, 8};
  rc::BruteForce brute;
  std::vector<ProxyId> live;

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
  }
  void move(ProxyId id, const AABB& box) {
    EXPECT_EQ(tree.moveProxy(id, box), brute.moveProxy(id, box));
  }
  // Pairs and a set of queries must agree exactly.
  void check(rc::Random& rng, const std::string& what) {
    ASSERT_NO_THROW(tree.validate()) << what;
    std::vector<rc::ProxyPair> pt, pb;
    tree.findPairs(pt);
    brute.findPairs(pb);
    ASSERT_EQ(pt.size(), pb.size()) << what;
    ASSERT_TRUE(pt == pb) << what;
    for (int q = 0; q < 20; ++q) {
      Vec2 c = rng.inBox({-150, -150}, {150, 150});
      AABB box = boxAt(c, {rng.uniform(0, 8), rng.uniform(0, 8)});
      rc::ProxyFilter f{1u << rng.below(3), 0xFFFFFFFFu};
      ASSERT_EQ(tree.queryAABB(box, f), brute.queryAABB(box, f)) << what << " query " << q;
      ASSERT_EQ(tree.queryPoint(c), brute.queryPoint(c)) << what << " point " << q;
    }
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

void runScene(Layout layout, std::uint64_t seed, const char* name) {
  rc::Random rng(seed);
  Twin t;
  std::vector<Vec2> vel;
  auto addOne = [&]() {
    rc::ProxyDef def;
    def.aabb = boxAt(positionFor(rng, layout), sizeFor(rng, layout));
    def.isStatic = rng.below(4) == 0;
    def.filter.category = 1u << rng.below(3);
    def.filter.mask = rng.below(5) == 0 ? ~def.filter.category : 0xFFFFFFFFu;
    t.add(def);
    vel.push_back(def.isStatic ? Vec2{} : rng.inBox({-1, -1}, {1, 1}));
  };
  for (int i = 0; i < 400; ++i)
    addOne();
  t.check(rng, std::string(name) + " initial");
  for (int step = 0; step < 60; ++step) {
    for (std::size_t i = 0; i < t.live.size(); ++i) {
      if (vel[i] == Vec2{}) continue;
      AABB fat = t.tree.fatAABB(t.live[i]);
      Vec2 c = fat.center() + vel[i];
      Vec2 e = rc::max(fat.extents() - Vec2{rc::kAabbMargin, rc::kAabbMargin}, Vec2{0, 0});
      t.move(t.live[i], boxAt(c, e));
    }
    // Churn: remove and add a few every step.
    for (int k = 0; k < 5 && !t.live.empty(); ++k) {
      std::size_t index = rng.below(static_cast<std::uint32_t>(t.live.size()));
      t.remove(index);
      vel.erase(vel.begin() + static_cast<std::ptrdiff_t>(index));
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

}  // namespace
