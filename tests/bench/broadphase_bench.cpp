// The broadphase race: our loose quadtree (physics/broadphase.h) against Box2D 2.4.1's
// b2BroadPhase / b2DynamicTree doing the same work on the same seeded scenes, in the same run.
// Not part of ctest; run
//   ./build/release/tests/broadphase_bench [--benchmark_filter=...] [--table=FILE.md]
//
// Scenes (the issue's): circles of radius 0.5 m, one per 8 m^2, in a square arena walled by
// four static boxes (200 m square for 5,000 circles; the side grows with N).
//   pairs/N     one step of pair update at 60 Hz with every circle moving at 5 m/s (bouncing
//               off the walls): every proxy moved with its displacement, then the new pairs
//               collected (b2BroadPhase::UpdatePairs; our updatePairs). Time per step, averaged
//               over one simulated second from the same start.
//   raycast     10,000 closest-hit casts of 50 m among 1,000 (and 65,536) circles, from points
//               outside every circle, each engine with its own exact circle ray cast in the
//               callback. Time per cast.
//   raycast world  the same 1,000-circle casts through each engine's world (World::castRay;
//               b2World::RayCast with a closest-hit callback): each circle a static body, the
//               walls static boxes in a category the rays skip. What a game pays per shot.
//   query       10,000 AABB queries of 5 m boxes, counting the proxies found. Time per query.
//   crossover   our quadtree (never falling back) against our brute force on small scenes:
//               pair update per step, 50 m ray casts, 5 m AABB queries. Where the tree starts
//               to pay (Quadtree::kBruteForceBelow).
// Counters report what each engine found (pairs per step, hits, proxies per query), so that a
// reader can see the work was the same.
#include <benchmark/benchmark.h>
#include <box2d/b2_broad_phase.h>
#include <box2d/b2_circle_shape.h>
#include <box2d/b2_dynamic_tree.h>
#include <box2d/b2_fixture.h>
#include <box2d/b2_polygon_shape.h>
#include <box2d/b2_world.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench/broadphase_arena.h"
#include "bench/ratio_table.h"
#include "physics/broadphase.h"
#include "physics/random.h"
#include "physics/world.h"

namespace {

using rc::AABB;
using rc::Vec2;

using rc::bench::circleBox;
using rc::bench::kDt;
using rc::bench::kRadius;
using rc::bench::kSpeed;
using rc::bench::toB2;
constexpr int kSteps = 60;

// The arena and one simulated second of motion, precomputed so that both engines see exactly
// the same positions and neither pays for the integration.
struct Arena {
  float side = 0;
  std::vector<AABB> walls;
  std::vector<std::vector<Vec2>> positions;  // [step][circle], step 0 the start
};

Arena makeArena(int n, std::uint64_t seed, int steps) {
  Arena a;
  a.side = std::sqrt(8.0f * static_cast<float>(n));
  const float s = a.side;
  a.walls = {
      {{-1, -1}, {0, s + 1}}, {{s, -1}, {s + 1, s + 1}}, {{0, -1}, {s, 0}}, {{0, s}, {s, s + 1}}};
  rc::Random rng(seed);
  std::vector<Vec2> p(static_cast<std::size_t>(n)), v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    p[static_cast<std::size_t>(i)] = rng.inBox({kRadius, kRadius}, {s - kRadius, s - kRadius});
    const float angle = rng.uniform(0.0f, 6.2831853f);
    v[static_cast<std::size_t>(i)] = kSpeed * Vec2{std::cos(angle), std::sin(angle)};
  }
  a.positions.push_back(p);
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      p[i] += kDt * v[i];
      // Bounce off the walls.
      if (p[i].x < kRadius || p[i].x > s - kRadius) v[i].x = -v[i].x;
      if (p[i].y < kRadius || p[i].y > s - kRadius) v[i].y = -v[i].y;
      p[i] = rc::max(Vec2{kRadius, kRadius}, rc::min(Vec2{s - kRadius, s - kRadius}, p[i]));
    }
    a.positions.push_back(p);
  }
  return a;
}

// ------------------------------------------------------------------------------- pair update

// Our pair update on either broadphase; make() builds an empty one.
template <class Make>
void pairsOurs(benchmark::State& state, const Arena& a, Make make) {
  std::vector<rc::ProxyPair> pairs;
  double reported = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto bp = make();
    for (const AABB& w : a.walls)
      bp.createProxy({w, {}, true, 0});
    std::vector<rc::ProxyId> ids;
    for (Vec2 p : a.positions[0])
      ids.push_back(bp.createProxy({circleBox(p), {}, false, 0}));
    bp.updatePairs(pairs);
    state.ResumeTiming();
    for (int step = 1; step <= kSteps; ++step) {
      const auto& now = a.positions[static_cast<std::size_t>(step)];
      const auto& before = a.positions[static_cast<std::size_t>(step - 1)];
      for (std::size_t i = 0; i < ids.size(); ++i)
        bp.moveProxy(ids[i], circleBox(now[i]), now[i] - before[i]);
      bp.updatePairs(pairs);
      reported += static_cast<double>(pairs.size());
    }
  }
  state.SetItemsProcessed(state.iterations() * kSteps);
  state.counters["new_pairs_per_step"] =
      reported / static_cast<double>(state.iterations() * kSteps);
}

// The quadtree over the arena; with alwaysTree it never falls back to brute force.
auto treeFor(const Arena& a, bool alwaysTree) {
  return [&a, alwaysTree] {
    rc::Quadtree tree(AABB{{-1, -1}, {a.side + 1, a.side + 1}});
    if (alwaysTree) tree.setBruteForceBelow(0);
    return tree;
  };
}

// The least a linear (Morton) quadtree rebuilt every step must do before it finds a single
// pair: a Morton key per proxy from its centre, then a sort. Measured beside our whole pair
// update to see whether that variant could win (see physics/broadphase.h, "Why").
void mortonSortOnly(benchmark::State& state, const Arena& a) {
  auto spread = [](std::uint32_t v) {  // 16 bits to the even bits of 32
    v &= 0xFFFFu;
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    v = (v | (v << 1)) & 0x55555555u;
    return v;
  };
  const float scale = 65535.0f / (a.side + 2.0f);
  std::vector<std::uint64_t> keys(a.positions[0].size());
  for (auto _ : state) {
    for (int step = 1; step <= kSteps; ++step) {
      const auto& now = a.positions[static_cast<std::size_t>(step)];
      for (std::size_t i = 0; i < now.size(); ++i) {
        const auto x = static_cast<std::uint32_t>((now[i].x + 1.0f) * scale);
        const auto y = static_cast<std::uint32_t>((now[i].y + 1.0f) * scale);
        keys[i] = (static_cast<std::uint64_t>(spread(x) | (spread(y) << 1)) << 32) | i;
      }
      std::sort(keys.begin(), keys.end());
      benchmark::DoNotOptimize(keys.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * kSteps);
}

struct PairCollector {
  std::vector<std::pair<void*, void*>> pairs;
  void AddPair(void* a, void* b) { pairs.emplace_back(a, b); }
};

void pairsBox2D(benchmark::State& state, const Arena& a) {
  PairCollector collector;
  double reported = 0;
  // User data: the index plus one (Box2D hands the pointers back, never reads them).
  auto tag = [](std::size_t i) { return reinterpret_cast<void*>(i + 1); };
  for (auto _ : state) {
    state.PauseTiming();
    b2BroadPhase bp;
    for (std::size_t w = 0; w < a.walls.size(); ++w)
      bp.CreateProxy(toB2(a.walls[w]), tag(1000000 + w));
    std::vector<int32> ids;
    for (std::size_t i = 0; i < a.positions[0].size(); ++i)
      ids.push_back(bp.CreateProxy(toB2(circleBox(a.positions[0][i])), tag(i)));
    bp.UpdatePairs(&collector);
    state.ResumeTiming();
    for (int step = 1; step <= kSteps; ++step) {
      const auto& now = a.positions[static_cast<std::size_t>(step)];
      const auto& before = a.positions[static_cast<std::size_t>(step - 1)];
      collector.pairs.clear();
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const Vec2 d = now[i] - before[i];
        bp.MoveProxy(ids[i], toB2(circleBox(now[i])), b2Vec2(d.x, d.y));
      }
      bp.UpdatePairs(&collector);
      reported += static_cast<double>(collector.pairs.size());
    }
  }
  state.SetItemsProcessed(state.iterations() * kSteps);
  state.counters["new_pairs_per_step"] =
      reported / static_cast<double>(state.iterations() * kSteps);
}

// --------------------------------------------------------------------------- ray casts, queries

struct QueryScene {
  Arena arena;
  std::vector<rc::RayCastInput> rays;
  std::vector<AABB> boxes;
};

QueryScene makeQueryScene(int n, int rays, float rayLength, std::uint64_t seed) {
  QueryScene q;
  q.arena = makeArena(n, seed, 0);
  rc::Random rng(seed + 1);
  const float s = q.arena.side;
  // Rays start outside every circle: Box2D reports no hit for a ray that starts inside a
  // circle and we report one at fraction 0, and the race should be about the same answers.
  rc::Quadtree index(AABB{{0, 0}, {s, s}});
  const auto& centres = q.arena.positions[0];
  for (Vec2 c : centres)
    index.createProxy({circleBox(c), {}, false, 0});
  auto insideACircle = [&](Vec2 p) {
    for (rc::ProxyId id : index.queryPoint(p))
      if (rc::distanceSquared(p, centres[static_cast<std::size_t>(id)]) <= kRadius * kRadius)
        return true;
    return false;
  };
  for (int i = 0; i < rays; ++i) {
    const float angle = rng.uniform(0.0f, 6.2831853f);
    Vec2 origin = rng.inBox({0, 0}, {s, s});
    while (insideACircle(origin))
      origin = rng.inBox({0, 0}, {s, s});
    q.rays.push_back({origin, rayLength * Vec2{std::cos(angle), std::sin(angle)}, 1.0f});
    Vec2 c = rng.inBox({0, 0}, {s, s});
    q.boxes.push_back({c - Vec2{2.5f, 2.5f}, c + Vec2{2.5f, 2.5f}});
  }
  return q;
}

template <class Broadphase>
void fillOurs(Broadphase& bp, const Arena& a) {
  for (const AABB& w : a.walls)
    bp.createProxy({w, {}, true, 0});
  for (Vec2 p : a.positions[0])
    bp.createProxy({circleBox(p), {}, false, 0});
}

// Proxy ids 0..3 are the walls (not hit by the exact test), then the circles in order.
// Every ray of the scene through cast(in), which returns whether it hit: time per cast, and
// the hit rate as a counter.
template <class Cast>
void castEach(benchmark::State& state, const QueryScene& q, Cast&& cast) {
  double hits = 0;
  for (auto _ : state)
    for (const rc::RayCastInput& in : q.rays)
      hits += cast(in);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.rays.size()));
  state.counters["hit_rate"] =
      hits / static_cast<double>(state.iterations() * static_cast<std::int64_t>(q.rays.size()));
}

template <class Broadphase>
void raysOurs(benchmark::State& state, const QueryScene& q, const Broadphase& bp) {
  const auto& centres = q.arena.positions[0];
  const std::size_t walls = q.arena.walls.size();
  auto exact = [&](rc::ProxyId id, const rc::RayCastInput& in) {
    if (static_cast<std::size_t>(id) < walls) return rc::CastOutput{};
    return rc::rayCast(rc::Circle{centres[static_cast<std::size_t>(id) - walls], kRadius}, in);
  };
  castEach(state, q, [&](const rc::RayCastInput& in) {
    rc::ProxyHit h = rc::castClosest(bp, in, 0.0f, {}, exact);
    benchmark::DoNotOptimize(h);
    return h.out.hit;
  });
}

struct Box2DTreeScene {
  b2DynamicTree tree;
  std::vector<b2CircleShape> circles;
  std::vector<int32> ids;
};

// Box2D's tree with the same proxies; user data points at the circle (null for the walls).
void fillBox2D(Box2DTreeScene& s, const Arena& a) {
  s.circles.resize(a.positions[0].size());
  for (const AABB& w : a.walls)
    s.tree.CreateProxy(toB2(w), nullptr);
  for (std::size_t i = 0; i < s.circles.size(); ++i) {
    s.circles[i].m_p.Set(a.positions[0][i].x, a.positions[0][i].y);
    s.circles[i].m_radius = kRadius;
    s.ids.push_back(s.tree.CreateProxy(toB2(circleBox(a.positions[0][i])), &s.circles[i]));
  }
}

struct Box2DClosest {
  const b2DynamicTree* tree;
  b2Transform identity;
  float best = 1.0f;
  bool hit = false;
  float RayCastCallback(const b2RayCastInput& input, int32 proxyId) {
    auto* circle = static_cast<const b2CircleShape*>(tree->GetUserData(proxyId));
    if (circle == nullptr) return input.maxFraction;
    b2RayCastOutput out;
    if (!circle->RayCast(&out, input, identity, 0)) return input.maxFraction;
    hit = true;
    best = out.fraction;
    return out.fraction;
  }
};

void raysBox2D(benchmark::State& state, const QueryScene& q, const Box2DTreeScene& s) {
  castEach(state, q, [&](const rc::RayCastInput& in) {
    Box2DClosest cb{&s.tree, b2Transform(), 1.0f, false};
    cb.identity.SetIdentity();
    b2RayCastInput input;
    input.p1.Set(in.origin.x, in.origin.y);
    input.p2.Set(in.origin.x + in.translation.x, in.origin.y + in.translation.y);
    input.maxFraction = 1.0f;
    s.tree.RayCast(&cb, input);
    benchmark::DoNotOptimize(cb.best);
    return cb.hit;
  });
}

// The query scene as worlds: each circle a static body, the walls static boxes in category 2,
// which the casts' filter skips (in the tree-only rows the exact test skips them).
constexpr std::uint32_t kWallCategory = 2;

std::unique_ptr<rc::World> worldOurs(const QueryScene& q) {
  auto w = std::make_unique<rc::World>();
  rc::ShapeDef wall;
  wall.filter.category = kWallCategory;
  const rc::BodyId walls = w->createBody({});
  for (const AABB& b : q.arena.walls)
    w->createShape(walls, rc::makeBox(b.extents().x, b.extents().y, b.center()), wall);
  for (Vec2 c : q.arena.positions[0]) {
    rc::BodyDef bd;
    bd.position = c;
    w->createShape(w->createBody(bd), rc::makeCircle({}, kRadius), {});
  }
  return w;
}

void raysWorldOurs(benchmark::State& state, const QueryScene& q, const rc::World& w) {
  const rc::QueryFilter filter(rc::ProxyFilter{1, ~kWallCategory});
  castEach(state, q, [&](const rc::RayCastInput& in) {
    const auto h = w.castRay(in.origin, in.translation, filter);
    benchmark::DoNotOptimize(h);
    return h.has_value();
  });
}

std::unique_ptr<b2World> worldBox2D(const QueryScene& q) {
  auto w = std::make_unique<b2World>(b2Vec2(0, 0));
  b2BodyDef gd;
  b2Body* walls = w->CreateBody(&gd);
  for (const AABB& b : q.arena.walls) {
    b2PolygonShape box;
    box.SetAsBox(b.extents().x, b.extents().y, b2Vec2(b.center().x, b.center().y), 0.0f);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.filter.categoryBits = kWallCategory;
    walls->CreateFixture(&fd);
  }
  for (Vec2 c : q.arena.positions[0]) {
    b2BodyDef bd;
    bd.position.Set(c.x, c.y);
    b2CircleShape circle;
    circle.m_radius = kRadius;
    w->CreateBody(&bd)->CreateFixture(&circle, 0.0f);
  }
  return w;
}

// Closest hit: each hit clips the ray; a wall is skipped (-1), as the filter does in ours.
struct Box2DWorldClosest : b2RayCastCallback {
  bool hit = false;
  float best = 1.0f;
  float ReportFixture(b2Fixture* f, const b2Vec2&, const b2Vec2&, float fraction) override {
    if (f->GetFilterData().categoryBits == kWallCategory) return -1.0f;
    hit = true;
    best = fraction;
    return fraction;
  }
};

void raysWorldBox2D(benchmark::State& state, const QueryScene& q, const b2World& w) {
  castEach(state, q, [&](const rc::RayCastInput& in) {
    Box2DWorldClosest cb;
    w.RayCast(&cb, b2Vec2(in.origin.x, in.origin.y),
              b2Vec2(in.origin.x + in.translation.x, in.origin.y + in.translation.y));
    benchmark::DoNotOptimize(cb.best);
    return cb.hit;
  });
}

template <class Broadphase>
void queriesOurs(benchmark::State& state, const QueryScene& q, const Broadphase& tree) {
  double found = 0;
  for (auto _ : state) {
    for (const AABB& box : q.boxes) {
      int n = 0;
      tree.queryAABB(box, {}, [&](rc::ProxyId) {
        ++n;
        return true;
      });
      found += n;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.boxes.size()));
  state.counters["found_per_query"] =
      found / static_cast<double>(state.iterations() * static_cast<std::int64_t>(q.boxes.size()));
}

struct Box2DCounter {
  int n = 0;
  bool QueryCallback(int32) {
    ++n;
    return true;
  }
};

void queriesBox2D(benchmark::State& state, const QueryScene& q, const Box2DTreeScene& s) {
  double found = 0;
  for (auto _ : state) {
    for (const AABB& box : q.boxes) {
      Box2DCounter cb;
      s.tree.Query(&cb, toB2(box));
      found += cb.n;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(q.boxes.size()));
  state.counters["found_per_query"] =
      found / static_cast<double>(state.iterations() * static_cast<std::int64_t>(q.boxes.size()));
}

// ---------------------------------------------------------------------------------- register

void registerAll() {
  // Scenes live for the whole run: the benchmarks keep pointers to them.
  static std::vector<std::unique_ptr<Arena>> arenas;
  for (int n : {1024, 4096, 16384, 65536}) {
    arenas.push_back(
        std::make_unique<Arena>(makeArena(n, 100 + static_cast<std::uint64_t>(n), kSteps)));
    const Arena* a = arenas.back().get();
    const std::string name = "pairs/N=" + std::to_string(n);
    benchmark::RegisterBenchmark((name + "/ours").c_str(), [a](benchmark::State& s) {
      pairsOurs(s, *a, treeFor(*a, false));
    })->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((name + "/box2d").c_str(), [a](benchmark::State& s) {
      pairsBox2D(s, *a);
    })->Unit(benchmark::kMicrosecond);
    const std::string variant = "variant: pairs vs Morton keys + sort/N=" + std::to_string(n);
    benchmark::RegisterBenchmark((variant + "/ours").c_str(), [a](benchmark::State& s) {
      pairsOurs(s, *a, treeFor(*a, false));
    })->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((variant + "/morton sort only").c_str(), [a](benchmark::State& s) {
      mortonSortOnly(s, *a);
    })->Unit(benchmark::kMicrosecond);
  }

  static std::vector<std::unique_ptr<QueryScene>> scenes;
  static std::vector<std::unique_ptr<rc::Quadtree>> trees;
  static std::vector<std::unique_ptr<Box2DTreeScene>> b2trees;
  auto addScene = [](int n, int rays, float length) {
    scenes.push_back(std::make_unique<QueryScene>(
        makeQueryScene(n, rays, length, 7 + static_cast<std::uint64_t>(n))));
    const QueryScene* q = scenes.back().get();
    const float s = q->arena.side;
    trees.push_back(std::make_unique<rc::Quadtree>(AABB{{-1, -1}, {s + 1, s + 1}}));
    fillOurs(*trees.back(), q->arena);
    b2trees.push_back(std::make_unique<Box2DTreeScene>());
    fillBox2D(*b2trees.back(), q->arena);
  };
  for (int n : {1000, 65536}) {
    addScene(n, 10000, 50.0f);
    const QueryScene* q = scenes.back().get();
    const rc::Quadtree* t = trees.back().get();
    const Box2DTreeScene* b = b2trees.back().get();
    const std::string among = " among " + std::to_string(n);
    benchmark::RegisterBenchmark(("raycast/50m" + among + "/ours").c_str(),
                                 [q, t](benchmark::State& s) { raysOurs(s, *q, *t); });
    benchmark::RegisterBenchmark(("raycast/50m" + among + "/box2d").c_str(),
                                 [q, b](benchmark::State& s) { raysBox2D(s, *q, *b); });
    if (n == 1000) {
      static std::unique_ptr<rc::World> ourWorld = worldOurs(*q);
      static std::unique_ptr<b2World> box2dWorld = worldBox2D(*q);
      benchmark::RegisterBenchmark(("raycast world/50m" + among + "/ours").c_str(),
                                   [q](benchmark::State& s) { raysWorldOurs(s, *q, *ourWorld); });
      benchmark::RegisterBenchmark(
          ("raycast world/50m" + among + "/box2d").c_str(),
          [q](benchmark::State& s) { raysWorldBox2D(s, *q, *box2dWorld); });
    }
    benchmark::RegisterBenchmark(("query/5m box" + among + "/ours").c_str(),
                                 [q, t](benchmark::State& s) { queriesOurs(s, *q, *t); });
    benchmark::RegisterBenchmark(("query/5m box" + among + "/box2d").c_str(),
                                 [q, b](benchmark::State& s) { queriesBox2D(s, *q, *b); });
  }

  // Crossover: the quadtree (never falling back) against brute force on small scenes.
  static std::vector<std::unique_ptr<rc::BruteForce>> brutes;
  for (int n : {8, 16, 32, 40, 48, 56, 64, 128, 256}) {
    arenas.push_back(
        std::make_unique<Arena>(makeArena(n, 200 + static_cast<std::uint64_t>(n), kSteps)));
    const Arena* a = arenas.back().get();
    const std::string name = "crossover pairs/N=" + std::to_string(n);
    benchmark::RegisterBenchmark((name + "/ours").c_str(),
                                 [a](benchmark::State& s) { pairsOurs(s, *a, treeFor(*a, true)); });
    benchmark::RegisterBenchmark((name + "/brute").c_str(), [a](benchmark::State& s) {
      pairsOurs(s, *a, [] { return rc::BruteForce(); });
    });
    addScene(n, 1000, 50.0f);
    const QueryScene* q = scenes.back().get();
    trees.back()->setBruteForceBelow(0);
    const rc::Quadtree* t = trees.back().get();
    brutes.push_back(std::make_unique<rc::BruteForce>());
    fillOurs(*brutes.back(), q->arena);
    const rc::BruteForce* bf = brutes.back().get();
    const std::string rays = "crossover rays/N=" + std::to_string(n);
    benchmark::RegisterBenchmark((rays + "/ours").c_str(),
                                 [q, t](benchmark::State& s) { raysOurs(s, *q, *t); });
    benchmark::RegisterBenchmark((rays + "/brute").c_str(),
                                 [q, bf](benchmark::State& s) { raysOurs(s, *q, *bf); });
    const std::string boxes = "crossover query/N=" + std::to_string(n);
    benchmark::RegisterBenchmark((boxes + "/ours").c_str(),
                                 [q, t](benchmark::State& s) { queriesOurs(s, *q, *t); });
    benchmark::RegisterBenchmark((boxes + "/brute").c_str(),
                                 [q, bf](benchmark::State& s) { queriesOurs(s, *q, *bf); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  return rc::bench::runWithRatioTable(argc, argv, "broadphase_bench", registerAll);
}
