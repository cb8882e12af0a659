// Geometry micro-benchmarks: every query of every shape pair, ours beside Box2D 2.4.1 on the
// same seeded cases in the same run. Not part of ctest; run
//   ./build/release/tests/geometry_bench [--benchmark_min_time=0.2] [--table=FILE.md]
// At the end it prints a table of nanoseconds per query and the speed ratio (Box2D time over
// ours: above 1 means we are faster).
#include <benchmark/benchmark.h>
#include <box2d/b2_time_of_impact.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/ratio_table.h"
#include "physics/collide.h"
#include "physics/raycast.h"
#include "physics/toi.h"
#include "support/box2d_adapter.h"
#include "support/random_shapes.h"

namespace {

using rc::Vec2;
using rc::testing::Box2DProxy;
using rc::testing::Box2DShape;
using rc::testing::Kind;

constexpr int kCases = 1024;

struct PairCase {
  rc::Shape a = rc::makeCircle({}, 1), b = rc::makeCircle({}, 1);
  rc::Transform xa, xb;
  rc::ShapeProxy pa, pb;
  Box2DShape oa, ob;
  b2Transform ba, bb;
  Box2DProxy qa, qb;
  rc::Sweep sa, sb;
  b2Sweep wa, wb;
};

// Cases are heap-allocated once and never moved: the Box2D proxies point into them.
std::vector<std::unique_ptr<PairCase>> makeCases(Kind ka, Kind kb, uint64_t seed) {
  rc::Random rng(seed);
  std::vector<std::unique_ptr<PairCase>> cases;
  for (int i = 0; i < kCases; ++i) {
    auto c = std::make_unique<PairCase>();
    c->a = rc::testing::randomShape(rng, ka);
    c->b = rc::testing::randomShape(rng, kb);
    c->xa = rc::testing::randomTransform(rng, {}, 0.8f, ka != Kind::box);
    c->xb = rc::testing::randomTransform(rng, {}, 0.8f, kb != Kind::box);
    c->pa = rc::makeProxy(c->a);
    c->pb = rc::makeProxy(c->b);
    rc::testing::toB2(c->a, &c->oa);
    rc::testing::toB2(c->b, &c->ob);
    c->ba = rc::testing::toB2(c->xa);
    c->bb = rc::testing::toB2(c->xb);
    c->qa.set(c->pa);
    c->qb.set(c->pb);
    // A sweep that closes a 3 m gap with up to a radian of spin: most cases hit.
    c->sa = {{}, {-3, 0}, {0.5f, 0}, 0.0f, rng.uniform(-1, 1)};
    c->sb = {{}, {3, rng.uniform(-0.5f, 0.5f)}, {0, 0}, 0.0f, rng.uniform(-1, 1)};
    c->wa = rc::testing::toB2(c->sa);
    c->wb = rc::testing::toB2(c->sb);
    cases.push_back(std::move(c));
  }
  return cases;
}

template <typename F>
void registerPair(const std::string& name, const std::vector<std::unique_ptr<PairCase>>* cases,
                  F f) {
  benchmark::RegisterBenchmark(name.c_str(), [cases, f](benchmark::State& state) {
    for (auto _ : state) {
      for (const auto& c : *cases)
        f(*c);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cases->size()));
  });
}

struct PairKind {
  Kind a, b;
};

std::string pairName(PairKind p) {
  std::string n = std::string(rc::testing::kindName(p.a)) + "-" + rc::testing::kindName(p.b);
  for (char& ch : n)
    if (ch == ' ') ch = '_';
  return n;
}

std::vector<std::vector<std::unique_ptr<PairCase>>> storage;

void registerAll() {
  const PairKind oraclePairs[] = {
      {Kind::circle, Kind::circle},   {Kind::box, Kind::circle},
      {Kind::polygon, Kind::circle},  {Kind::orientedBox, Kind::circle},
      {Kind::box, Kind::box},         {Kind::box, Kind::polygon},
      {Kind::polygon, Kind::polygon}, {Kind::orientedBox, Kind::polygon},
      {Kind::segment, Kind::circle},  {Kind::segment, Kind::polygon},
      {Kind::segment, Kind::box}};
  storage.reserve(64);
  uint64_t seed = 500;
  for (PairKind p : oraclePairs) {
    storage.push_back(makeCases(p.a, p.b, seed++));
    const auto* cases = &storage.back();
    std::string n = pairName(p);
    registerPair("manifold/" + n + "/ours", cases, [](const PairCase& c) {
      benchmark::DoNotOptimize(rc::collide(c.a, c.xa, c.b, c.xb));
    });
    registerPair("manifold/" + n + "/box2d", cases, [](const PairCase& c) {
      b2Manifold m;
      m.pointCount = 0;
      const b2Shape* sa = c.oa.get();
      const b2Shape* sb = c.ob.get();
      if (c.oa.type == b2Shape::e_circle)
        b2CollideCircles(&m, &c.oa.circle, c.ba, &c.ob.circle, c.bb);
      else if (c.oa.type == b2Shape::e_polygon && c.ob.type == b2Shape::e_circle)
        b2CollidePolygonAndCircle(&m, &c.oa.polygon, c.ba, &c.ob.circle, c.bb);
      else if (c.oa.type == b2Shape::e_polygon)
        b2CollidePolygons(&m, &c.oa.polygon, c.ba, &c.ob.polygon, c.bb);
      else if (c.ob.type == b2Shape::e_circle)
        b2CollideEdgeAndCircle(&m, &c.oa.edge, c.ba, &c.ob.circle, c.bb);
      else
        b2CollideEdgeAndPolygon(&m, &c.oa.edge, c.ba, &c.ob.polygon, c.bb);
      // Our manifold is in world space (points, separations, anchors); Box2D's b2Manifold is
      // local and b2WorldManifold::Initialize makes the world version: time both.
      b2WorldManifold wm;
      wm.Initialize(&m, c.ba, sa->m_radius, c.bb, sb->m_radius);
      benchmark::DoNotOptimize(wm);
    });
    registerPair("overlap/" + n + "/ours", cases, [](const PairCase& c) {
      benchmark::DoNotOptimize(rc::testOverlap(c.a, c.xa, c.b, c.xb));
    });
    registerPair("overlap/" + n + "/box2d", cases, [](const PairCase& c) {
      benchmark::DoNotOptimize(b2TestOverlap(c.oa.get(), 0, c.ob.get(), 0, c.ba, c.bb));
    });
  }

  // Distance and time of impact work on proxies: capsules and rounded polygons too.
  const PairKind proxyPairs[] = {{Kind::circle, Kind::circle},   {Kind::box, Kind::circle},
                                 {Kind::polygon, Kind::polygon}, {Kind::capsule, Kind::capsule},
                                 {Kind::capsule, Kind::polygon}, {Kind::roundedPolygon, Kind::box}};
  for (PairKind p : proxyPairs) {
    storage.push_back(makeCases(p.a, p.b, seed++));
    const auto* cases = &storage.back();
    std::string n = pairName(p);
    registerPair("distance/" + n + "/ours", cases, [](const PairCase& c) {
      benchmark::DoNotOptimize(rc::shapeDistance(c.pa, c.xa, c.pb, c.xb));
    });
    registerPair("distance/" + n + "/box2d", cases, [](const PairCase& c) {
      b2DistanceInput in;
      in.proxyA = c.qa.proxy;
      in.proxyB = c.qb.proxy;
      in.transformA = c.ba;
      in.transformB = c.bb;
      in.useRadii = true;
      b2SimplexCache cache;
      cache.count = 0;
      b2DistanceOutput out;
      b2Distance(&out, &cache, &in);
      benchmark::DoNotOptimize(out);
    });
    registerPair("toi/" + n + "/ours", cases, [](const PairCase& c) {
      // Box2D's target: the cores stop max(slop, rA + rB - 3 slop) apart; the same here.
      float radii = c.pa.radius + c.pb.radius;
      float target = std::max(rc::kLinearSlop, radii - 3.0f * rc::kLinearSlop) - radii;
      benchmark::DoNotOptimize(rc::timeOfImpact(c.pa, c.sa, c.pb, c.sb, 1.0f, target));
    });
    registerPair("toi/" + n + "/box2d", cases, [](const PairCase& c) {
      b2TOIInput in;
      in.proxyA = c.qa.proxy;
      in.proxyB = c.qb.proxy;
      in.sweepA = c.wa;
      in.sweepB = c.wb;
      in.tMax = 1.0f;
      b2TOIOutput out;
      b2TimeOfImpact(&out, &in);
      benchmark::DoNotOptimize(out);
    });
  }

  // Ray casts: a ray of 4 m from a random point 2 m around the shape towards it.
  const Kind rayKinds[] = {Kind::circle, Kind::box, Kind::polygon, Kind::orientedBox,
                           Kind::segment};
  for (Kind k : rayKinds) {
    storage.push_back(makeCases(k, Kind::circle, seed++));
    const auto* cases = &storage.back();
    std::string n = rc::testing::kindName(k);
    for (char& ch : n)
      if (ch == ' ') ch = '_';
    registerPair("raycast/" + n + "/ours", cases, [](const PairCase& c) {
      Vec2 from = c.xb.p + Vec2{2.0f * c.xb.q.c, 2.0f * c.xb.q.s};
      rc::RayCastInput in{from, 2.0f * (c.xa.p - from), 1.0f};
      benchmark::DoNotOptimize(rc::rayCast(c.a, c.xa, in));
    });
    registerPair("raycast/" + n + "/box2d", cases, [](const PairCase& c) {
      Vec2 from = c.xb.p + Vec2{2.0f * c.xb.q.c, 2.0f * c.xb.q.s};
      Vec2 to = from + 2.0f * (c.xa.p - from);
      b2RayCastInput in;
      in.p1.Set(from.x, from.y);
      in.p2.Set(to.x, to.y);
      in.maxFraction = 1.0f;
      b2RayCastOutput out;
      benchmark::DoNotOptimize(c.oa.get()->RayCast(&out, in, c.ba, 0));
      benchmark::DoNotOptimize(out);
    });
  }
}

}  // namespace

int main(int argc, char** argv) {
  return rc::bench::runWithRatioTable(argc, argv, "geometry_bench", registerAll);
}
