// Geometry micro-benchmarks: every query of every shape pair, ours beside Box2D 2.4.1 on the
// same seeded cases in the same run. Not part of ctest; run
//   ./build/release/tests/geometry_bench [--benchmark_min_time=0.2] [--table=FILE.md]
// At the end it prints a table of nanoseconds per query and the speed ratio (Box2D time over
// ours: above 1 means we are faster).
//
// Each row's label gives the share of its cases that find something (manifold points, overlap,
// a time of impact, a ray hit). The two rows of a pair should show about the same share: a
// check that both engines were given the same geometry.
//
// Rows, "query/case/engine":
//   manifold, overlap   the oracle pairs, capsules, rounded polygons and one-sided chain links;
//   distance, toi       the 15 pairs of {circle, box, polygon, capsule, segment}, and rounded
//                       polygon vs box;
//   raycast             every kind, capsules and one-sided chain links included;
//   overlap-prefilter   the pairs whose overlap test is GJK, with the bounding-circle test
//                       first (".../with") and GJK alone (".../without"), on the random
//                       placement and on pairs whose AABBs overlap. There the table's speed-up
//                       is the time without over the time with: above 1, the prefilter pays.
//                       overlap-prefilter-cached: the same with the circles computed beforehand.
#include <benchmark/benchmark.h>
#include <box2d/b2_time_of_impact.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
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

// A capsule as a Box2D 2.4.1 user builds it for ray casts: b2PolygonShape::RayCast ignores
// m_radius, so the capsule is three fixtures, the box of width 2r along the axis and a circle at
// each end, and a closest-hit cast keeps the nearest of the three.
struct Box2DCapsuleFixtures {
  b2PolygonShape box;
  b2CircleShape end1, end2;
};

struct PairCase {
  rc::Shape a = rc::makeCircle({}, 1), b = rc::makeCircle({}, 1);
  rc::Transform xa, xb;
  rc::ShapeProxy pa, pb;
  Box2DShape oa, ob;
  b2Transform ba, bb;
  Box2DProxy qa, qb;
  rc::Sweep sa, sb;
  b2Sweep wa, wb;
  Box2DCapsuleFixtures capsuleA, capsuleB;  // set when a (b) is a capsule
  rc::RayCastInput linkRay;                 // set when a is a chain link
  rc::BoundingCircle circleA{}, circleB{};  // the prefilter's circles, computed once
};

// Box2D 2.4.1 has no capsule. Its stand-in for manifolds and overlap: a box of half-thickness
// b2_linearSlop along the axis, rounded by m_radius = the capsule radius (b2CollidePolygons,
// b2CollidePolygonAndCircle and b2TestOverlap round polygons by m_radius). Its sides stand
// b2_linearSlop (5 mm) further out than the capsule's; the ends are the capsule's. For ray
// casts, the three fixtures above.
void capsuleToB2(const rc::Capsule& s, Box2DShape* o, Box2DCapsuleFixtures* f) {
  Vec2 axis = s.center2 - s.center1;
  Vec2 mid = rc::lerp(s.center1, s.center2, 0.5f);
  float half = 0.5f * rc::length(axis);
  float angle = std::atan2(axis.y, axis.x);
  o->type = b2Shape::e_polygon;
  o->polygon.SetAsBox(half, b2_linearSlop, b2Vec2(mid.x, mid.y), angle);
  o->polygon.m_radius = s.radius;
  f->box.SetAsBox(half, s.radius, b2Vec2(mid.x, mid.y), angle);
  f->box.m_radius = 0.0f;
  f->end1.m_p.Set(s.center1.x, s.center1.y);
  f->end1.m_radius = s.radius;
  f->end2.m_p.Set(s.center2.x, s.center2.y);
  f->end2.m_radius = s.radius;
}

// False when Box2D would not hold the same shape (a polygon whose hull it builds differently).
bool shapeToB2(const rc::Shape& s, Box2DShape* o, Box2DCapsuleFixtures* f) {
  if (s.type != rc::ShapeType::capsule) return rc::testing::toB2(s, o);
  capsuleToB2(s.capsule, o, f);
  return true;
}

struct Placement {
  // a is a one-sided chain link, which collides only with shapes on its right: b is mirrored
  // across the link's line when its centre is on the left, so every case starts on the colliding
  // side (the centre is what both engines' side tests look at).
  bool rightOfLink = false;
  // Only pairs whose AABBs overlap (rejection sampling): what the broadphase hands on.
  bool aabbOverlap = false;
};

void moveToRightOfLink(PairCase* c) {
  const rc::Segment& g = c->a.chainSegment.segment;
  Vec2 p1 = rc::apply(c->xa, g.point1), p2 = rc::apply(c->xa, g.point2);
  Vec2 n = rc::normalize(rc::rightPerp(p2 - p1));
  float side = rc::dot(rc::apply(c->xb, rc::computeBoundingCircle(c->b).center) - p1, n);
  if (side < 0.0f) c->xb.p = rc::mulAdd(c->xb.p, -2.0f * side, n);
}

// A ray of 4 m through a random point of the link, from 2 m away on its right side (the only
// side a one-sided link is hit from): the direction of xb's rotation, mirrored onto that side.
rc::RayCastInput rayThroughLink(rc::Random& rng, const PairCase& c) {
  const rc::Segment& g = c.a.chainSegment.segment;
  Vec2 p1 = rc::apply(c.xa, g.point1), p2 = rc::apply(c.xa, g.point2);
  Vec2 n = rc::normalize(rc::rightPerp(p2 - p1));
  Vec2 d{c.xb.q.c, c.xb.q.s};
  if (rc::dot(d, n) < 0.0f) d = rc::mulAdd(d, -2.0f * rc::dot(d, n), n);
  Vec2 target = rc::lerp(p1, p2, rng.uniform(0.05f, 0.95f));
  Vec2 from = rc::mulAdd(target, 2.0f, d);
  return {from, -4.0f * d, 1.0f};
}

using Cases = std::vector<std::unique_ptr<PairCase>>;

// A case's shapes and transforms as both engines take them (our proxies, Box2D's shapes,
// transforms and proxies). False when Box2D would hold a different polygon.
bool setEngines(PairCase* c) {
  c->pa = rc::makeProxy(c->a);
  c->pb = rc::makeProxy(c->b);
  if (!shapeToB2(c->a, &c->oa, &c->capsuleA) || !shapeToB2(c->b, &c->ob, &c->capsuleB))
    return false;
  c->ba = rc::testing::toB2(c->xa);
  c->bb = rc::testing::toB2(c->xb);
  c->qa.set(c->pa);
  c->qb.set(c->pb);
  return true;
}

// Cases are heap-allocated once and never moved: the Box2D proxies point into them. Both
// engines get every case's shapes, transforms and sweeps.
Cases makeCases(Kind ka, Kind kb, uint64_t seed, Placement place = {}) {
  rc::Random rng(seed);
  Cases cases;
  while (static_cast<int>(cases.size()) < kCases) {
    auto c = std::make_unique<PairCase>();
    c->a = rc::testing::randomShape(rng, ka);
    c->b = rc::testing::randomShape(rng, kb);
    c->xa = rc::testing::randomTransform(rng, {}, 0.8f, ka != Kind::box);
    c->xb = rc::testing::randomTransform(rng, {}, 0.8f, kb != Kind::box);
    if (place.rightOfLink) moveToRightOfLink(c.get());
    if (place.aabbOverlap &&
        !rc::overlaps(rc::computeAABB(c->a, c->xa), rc::computeAABB(c->b, c->xb)))
      continue;
    if (!setEngines(c.get())) continue;  // drawn again: Box2D would hold a different polygon
    c->circleA = rc::computeBoundingCircle(c->a);
    c->circleB = rc::computeBoundingCircle(c->b);
    // A sweep that closes a 3 m gap with up to a radian of spin: most cases hit.
    c->sa = {{}, {-3, 0}, {0.5f, 0}, 0.0f, rng.uniform(-1, 1)};
    c->sb = {{}, {3, rng.uniform(-0.5f, 0.5f)}, {0, 0}, 0.0f, rng.uniform(-1, 1)};
    if (kb == Kind::segment) {
      // A segment is static geometry: it rests across a's path, turned by the drawn angle.
      float y = c->sb.c1.y, angle = c->sb.a2;
      c->sb = {{}, {0.0f, y}, {0.0f, y}, angle, angle};
    }
    c->wa = rc::testing::toB2(c->sa);
    c->wb = rc::testing::toB2(c->sb);
    if (ka == Kind::chainLink) c->linkRay = rayThroughLink(rng, *c);
    cases.push_back(std::move(c));
  }
  return cases;
}

// Boxes at rest on each other, as in a stack or pyramid: 1 m boxes, the upper one offset sideways
// by up to 0.8 m, both tilted by up to 0.02 rad, the gap between them -5 mm to +5 mm (overlap
// to Box2D's slop either way). Half the pairs side by side instead of one on the other. The
// random boxes of makeCases are axis-aligned (the aligned fast path); these are what a settling
// pyramid's contacts are.
Cases makeRestingBoxes(uint64_t seed) {
  rc::Random rng(seed);
  Cases cases;
  while (static_cast<int>(cases.size()) < kCases) {
    auto c = std::make_unique<PairCase>();
    c->a = rc::makeBox(0.5f, 0.5f);
    c->b = rc::makeBox(0.5f, 0.5f);
    const float gap = rng.uniform(-0.005f, 0.005f), offset = rng.uniform(-0.8f, 0.8f);
    const Vec2 pb =
        rng.uniform(0.0f, 1.0f) < 0.5f ? Vec2{offset, 1.0f + gap} : Vec2{1.0f + gap, 0.1f * offset};
    c->xa = {{}, rc::Rot::fromAngle(rng.uniform(-0.02f, 0.02f))};
    c->xb = {pb, rc::Rot::fromAngle(rng.uniform(-0.02f, 0.02f))};
    if (!setEngines(c.get())) continue;
    cases.push_back(std::move(c));
  }
  return cases;
}

template <typename F>
void registerPair(const std::string& name, const std::vector<std::unique_ptr<PairCase>>* cases, F f,
                  const std::string& label = {}) {
  benchmark::RegisterBenchmark(name.c_str(), [cases, f, label](benchmark::State& state) {
    for (auto _ : state) {
      for (const auto& c : *cases)
        f(*c);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(cases->size()));
    if (!label.empty()) state.SetLabel(label);
  });
}

// "what NN%": the share of cases for which pred holds.
template <typename P>
std::string share(const char* what, const Cases* cases, P pred) {
  int n = 0;
  for (const auto& c : *cases)
    n += pred(*c) ? 1 : 0;
  char s[64];
  std::snprintf(s, sizeof s, "%s %.1f%%", what, 100.0 * n / static_cast<double>(cases->size()));
  return s;
}

struct PairKind {
  Kind a, b;
};

std::string underscored(std::string n) {
  for (char& ch : n)
    if (ch == ' ') ch = '_';
  return n;
}

std::string pairName(PairKind p) {
  return underscored(std::string(rc::testing::kindName(p.a)) + "-" + rc::testing::kindName(p.b));
}

// --- The queries, ours and Box2D's -------------------------------------------------------------

// Box2D's manifold routine for the pair. Our manifold is in world space (points, separations,
// anchors); Box2D's b2Manifold is local and b2WorldManifold::Initialize makes the world version:
// both are timed. Returns the point count.
int box2dManifold(const PairCase& c, b2WorldManifold* wm) {
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
  wm->Initialize(&m, c.ba, sa->m_radius, c.bb, sb->m_radius);
  return m.pointCount;
}

bool box2dOverlap(const PairCase& c) {
  return b2TestOverlap(c.oa.get(), 0, c.ob.get(), 0, c.ba, c.bb);
}

b2DistanceOutput box2dDistance(const PairCase& c) {
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
  return out;
}

rc::ToiOutput ourToi(const PairCase& c) {
  // Box2D's target: the cores stop max(slop, rA + rB - 3 slop) apart; the same here.
  float radii = c.pa.radius + c.pb.radius;
  float target = std::max(rc::kLinearSlop, radii - 3.0f * rc::kLinearSlop) - radii;
  return rc::timeOfImpact(c.pa, c.sa, c.pb, c.sb, 1.0f, target);
}

b2TOIOutput box2dToi(const PairCase& c) {
  b2TOIInput in;
  in.proxyA = c.qa.proxy;
  in.proxyB = c.qb.proxy;
  in.sweepA = c.wa;
  in.sweepB = c.wb;
  in.tMax = 1.0f;
  b2TOIOutput out;
  b2TimeOfImpact(&out, &in);
  return out;
}

// A ray of 4 m from a random point 2 m around the shape towards it.
rc::RayCastInput aimedRay(const PairCase& c) {
  Vec2 from = c.xb.p + Vec2{2.0f * c.xb.q.c, 2.0f * c.xb.q.s};
  return {from, 2.0f * (c.xa.p - from), 1.0f};
}

b2RayCastInput toB2(const rc::RayCastInput& r) {
  Vec2 to = r.origin + r.translation;
  b2RayCastInput in;
  in.p1.Set(r.origin.x, r.origin.y);
  in.p2.Set(to.x, to.y);
  in.maxFraction = r.maxFraction;
  return in;
}

// The closest hit of the three fixtures, each cast clipped to the nearest hit so far (as
// b2World::RayCast does with a closest-hit callback).
bool box2dCapsuleRay(const PairCase& c, b2RayCastInput in, b2RayCastOutput* best) {
  const b2Shape* parts[3] = {&c.capsuleA.box, &c.capsuleA.end1, &c.capsuleA.end2};
  bool hit = false;
  for (const b2Shape* s : parts) {
    b2RayCastOutput out;
    if (s->RayCast(&out, in, c.ba, 0)) {
      *best = out;
      in.maxFraction = out.fraction;
      hit = true;
    }
  }
  return hit;
}

// Bounding circles first, then GJK: the prefilter rc::testOverlap had before these rows
// measured it.
bool circlesThenGjk(const PairCase& c) {
  rc::BoundingCircle ca = rc::computeBoundingCircle(c.a), cb = rc::computeBoundingCircle(c.b);
  float r = ca.radius + cb.radius;
  if (rc::distanceSquared(rc::apply(c.xa, ca.center), rc::apply(c.xb, cb.center)) > r * r)
    return false;
  return rc::shapeDistance(c.a, c.xa, c.b, c.xb).distance <= 0.0f;
}

// The same with the bounding circles computed beforehand, as a shape could store them (the
// library computes them on every call: a square root per polygon vertex).
bool cachedCirclesThenGjk(const PairCase& c) {
  float r = c.circleA.radius + c.circleB.radius;
  if (rc::distanceSquared(rc::apply(c.xa, c.circleA.center), rc::apply(c.xb, c.circleB.center)) >
      r * r)
    return false;
  return rc::shapeDistance(c.a, c.xa, c.b, c.xb).distance <= 0.0f;
}

bool gjkOnly(const PairCase& c) {
  return rc::shapeDistance(c.a, c.xa, c.b, c.xb).distance <= 0.0f;
}

bool circlesApart(const PairCase& c) {
  rc::BoundingCircle ca = rc::computeBoundingCircle(c.a), cb = rc::computeBoundingCircle(c.b);
  float r = ca.radius + cb.radius;
  return rc::distanceSquared(rc::apply(c.xa, ca.center), rc::apply(c.xb, cb.center)) > r * r;
}

// --- Rows --------------------------------------------------------------------------------------

std::deque<Cases> storage;  // a deque: the rows keep pointers to its elements

const Cases* keep(Cases cases) {
  storage.push_back(std::move(cases));
  return &storage.back();
}

void manifoldRows(const std::string& n, const Cases* cases) {
  registerPair(
      "manifold/" + n + "/ours", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(rc::collide(c.a, c.xa, c.b, c.xb)); },
      share("points", cases,
            [](const PairCase& c) { return rc::collide(c.a, c.xa, c.b, c.xb).pointCount > 0; }));
  registerPair(
      "manifold/" + n + "/box2d", cases,
      [](const PairCase& c) {
        b2WorldManifold wm;
        benchmark::DoNotOptimize(box2dManifold(c, &wm));
        benchmark::DoNotOptimize(wm);
      },
      share("points", cases, [](const PairCase& c) {
        b2WorldManifold wm;
        return box2dManifold(c, &wm) > 0;
      }));
}

void overlapRows(const std::string& n, const Cases* cases) {
  registerPair(
      "overlap/" + n + "/ours", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(rc::testOverlap(c.a, c.xa, c.b, c.xb)); },
      share("overlap", cases,
            [](const PairCase& c) { return rc::testOverlap(c.a, c.xa, c.b, c.xb); }));
  registerPair(
      "overlap/" + n + "/box2d", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(box2dOverlap(c)); },
      share("overlap", cases, box2dOverlap));
}

void distanceAndToiRows(const std::string& n, const Cases* cases) {
  registerPair(
      "distance/" + n + "/ours", cases,
      [](const PairCase& c) {
        benchmark::DoNotOptimize(rc::shapeDistance(c.pa, c.xa, c.pb, c.xb));
      },
      share("touching", cases, [](const PairCase& c) {
        return rc::shapeDistance(c.pa, c.xa, c.pb, c.xb).distance <= 0.0f;
      }));
  registerPair(
      "distance/" + n + "/box2d", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(box2dDistance(c)); },
      share("touching", cases,
            [](const PairCase& c) { return box2dDistance(c).distance <= 0.0f; }));
  registerPair(
      "toi/" + n + "/ours", cases, [](const PairCase& c) { benchmark::DoNotOptimize(ourToi(c)); },
      share("hit", cases, [](const PairCase& c) { return ourToi(c).state == rc::ToiState::hit; }) +
          share(", overlapped", cases,
                [](const PairCase& c) { return ourToi(c).state == rc::ToiState::overlapped; }));
  registerPair(
      "toi/" + n + "/box2d", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(box2dToi(c)); },
      share("hit", cases, [](const PairCase& c) {
        return box2dToi(c).state == b2TOIOutput::e_touching;
      }) + share(", overlapped", cases, [](const PairCase& c) {
        return box2dToi(c).state == b2TOIOutput::e_overlapped;
      }));
}

// The prefilter against GJK alone on one case set. rc::testOverlap no longer has it (these rows
// showed it costs more than it saves on the pairs the broadphase hands on): "with" is the order
// written out here, bounding circles first, then GJK.
void prefilterRows(const std::string& n, const Cases* cases) {
  std::string apart = share("circles apart", cases, circlesApart);
  std::string overlap = share("overlap", cases, gjkOnly);
  registerPair(
      "overlap-prefilter/" + n + "/with", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(circlesThenGjk(c)); },
      overlap + ", " + apart);
  registerPair(
      "overlap-prefilter/" + n + "/without", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(gjkOnly(c)); }, overlap);
  // The prefilter at its cheapest: circles computed beforehand. "without" is timed again so
  // that the table has the pair side by side.
  registerPair(
      "overlap-prefilter-cached/" + n + "/with", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(cachedCirclesThenGjk(c)); },
      overlap + ", " + apart);
  registerPair(
      "overlap-prefilter-cached/" + n + "/without", cases,
      [](const PairCase& c) { benchmark::DoNotOptimize(gjkOnly(c)); }, overlap);
}

void registerAll() {
  std::map<std::string, const Cases*> overlapCases;  // by pair name, for the prefilter rows

  const PairKind oraclePairs[] = {
      {Kind::circle, Kind::circle},   {Kind::box, Kind::circle},
      {Kind::polygon, Kind::circle},  {Kind::orientedBox, Kind::circle},
      {Kind::box, Kind::box},         {Kind::box, Kind::polygon},
      {Kind::polygon, Kind::polygon}, {Kind::orientedBox, Kind::polygon},
      {Kind::segment, Kind::circle},  {Kind::segment, Kind::polygon},
      {Kind::segment, Kind::box}};
  uint64_t seed = 500;
  for (PairKind p : oraclePairs) {
    const Cases* cases = keep(makeCases(p.a, p.b, seed++));
    manifoldRows(pairName(p), cases);
    overlapRows(pairName(p), cases);
  }

  manifoldRows("resting_boxes", keep(makeRestingBoxes(900)));

  // Distance and time of impact work on proxies: capsules and rounded polygons too.
  const PairKind proxyPairs[] = {{Kind::circle, Kind::circle},   {Kind::box, Kind::circle},
                                 {Kind::polygon, Kind::polygon}, {Kind::capsule, Kind::capsule},
                                 {Kind::capsule, Kind::polygon}, {Kind::roundedPolygon, Kind::box}};
  for (PairKind p : proxyPairs)
    distanceAndToiRows(pairName(p), keep(makeCases(p.a, p.b, seed++)));

  // Ray casts: a ray of 4 m from a random point 2 m around the shape towards it.
  const Kind rayKinds[] = {Kind::circle, Kind::box, Kind::polygon, Kind::orientedBox,
                           Kind::segment};
  for (Kind k : rayKinds) {
    const Cases* cases = keep(makeCases(k, Kind::circle, seed++));
    std::string n = underscored(rc::testing::kindName(k));
    registerPair(
        "raycast/" + n + "/ours", cases,
        [](const PairCase& c) { benchmark::DoNotOptimize(rc::rayCast(c.a, c.xa, aimedRay(c))); },
        share("hit", cases,
              [](const PairCase& c) { return rc::rayCast(c.a, c.xa, aimedRay(c)).hit; }));
    registerPair(
        "raycast/" + n + "/box2d", cases,
        [](const PairCase& c) {
          b2RayCastOutput out;
          benchmark::DoNotOptimize(c.oa.get()->RayCast(&out, toB2(aimedRay(c)), c.ba, 0));
          benchmark::DoNotOptimize(out);
        },
        share("hit", cases, [](const PairCase& c) {
          b2RayCastOutput out;
          return c.oa.get()->RayCast(&out, toB2(aimedRay(c)), c.ba, 0);
        }));
  }

  // Capsules, rounded polygons and one-sided chain links: manifold and overlap. Box2D's
  // stand-ins: for a capsule the rounded thin box of capsuleToB2; for a rounded polygon a
  // b2PolygonShape with m_radius = our radius; for a chain link the one-sided b2EdgeShape with
  // its ghost vertices (b2CollideEdgeAndCircle, b2CollideEdgeAndPolygon). The shape facing a
  // chain link is moved to the link's right, the side it collides with (see Placement).
  const PairKind solidPairs[] = {{Kind::capsule, Kind::circle},
                                 {Kind::capsule, Kind::capsule},
                                 {Kind::capsule, Kind::polygon},
                                 {Kind::capsule, Kind::box},
                                 {Kind::roundedPolygon, Kind::circle},
                                 {Kind::roundedPolygon, Kind::polygon},
                                 {Kind::roundedPolygon, Kind::roundedPolygon},
                                 {Kind::chainLink, Kind::circle},
                                 {Kind::chainLink, Kind::polygon},
                                 {Kind::chainLink, Kind::box}};
  seed = 600;
  for (PairKind p : solidPairs) {
    Placement place;
    place.rightOfLink = p.a == Kind::chainLink;
    const Cases* cases = keep(makeCases(p.a, p.b, seed++, place));
    manifoldRows(pairName(p), cases);
    overlapRows(pairName(p), cases);
    overlapCases[pairName(p)] = cases;
  }

  // The remaining distance and time of impact pairs of {circle, box, polygon, capsule,
  // segment}. A segment is static geometry: its sweep stays put across the other's path. In
  // segment-segment the first segment moves (as on a kinematic body) so that there is a motion.
  const PairKind moreProxyPairs[] = {
      {Kind::polygon, Kind::circle}, {Kind::capsule, Kind::circle},  {Kind::circle, Kind::segment},
      {Kind::box, Kind::box},        {Kind::box, Kind::polygon},     {Kind::capsule, Kind::box},
      {Kind::box, Kind::segment},    {Kind::polygon, Kind::segment}, {Kind::capsule, Kind::segment},
      {Kind::segment, Kind::segment}};
  seed = 700;
  for (PairKind p : moreProxyPairs)
    distanceAndToiRows(pairName(p), keep(makeCases(p.a, p.b, seed++)));

  // Ray casts against a capsule and a one-sided chain link. Box2D 2.4.1 has no capsule and
  // b2PolygonShape::RayCast ignores m_radius, so its user's capsule is three fixtures (the box
  // of width 2r and a circle at each end): the three casts and the closest hit are timed. The
  // chain link rays all come from the link's right (see rayThroughLink); Box2D's is
  // b2EdgeShape::RayCast on the one-sided edge.
  {
    const Cases* cases = keep(makeCases(Kind::capsule, Kind::circle, 800));
    registerPair(
        "raycast/capsule/ours", cases,
        [](const PairCase& c) { benchmark::DoNotOptimize(rc::rayCast(c.a, c.xa, aimedRay(c))); },
        share("hit", cases,
              [](const PairCase& c) { return rc::rayCast(c.a, c.xa, aimedRay(c)).hit; }));
    registerPair(
        "raycast/capsule/box2d", cases,
        [](const PairCase& c) {
          b2RayCastOutput out;
          benchmark::DoNotOptimize(box2dCapsuleRay(c, toB2(aimedRay(c)), &out));
          benchmark::DoNotOptimize(out);
        },
        share("hit", cases, [](const PairCase& c) {
          b2RayCastOutput out;
          return box2dCapsuleRay(c, toB2(aimedRay(c)), &out);
        }));

    cases = keep(makeCases(Kind::chainLink, Kind::circle, 801));
    registerPair(
        "raycast/chain_link/ours", cases,
        [](const PairCase& c) { benchmark::DoNotOptimize(rc::rayCast(c.a, c.xa, c.linkRay)); },
        share("hit", cases,
              [](const PairCase& c) { return rc::rayCast(c.a, c.xa, c.linkRay).hit; }));
    registerPair(
        "raycast/chain_link/box2d", cases,
        [](const PairCase& c) {
          b2RayCastOutput out;
          benchmark::DoNotOptimize(c.oa.get()->RayCast(&out, toB2(c.linkRay), c.ba, 0));
          benchmark::DoNotOptimize(out);
        },
        share("hit", cases, [](const PairCase& c) {
          b2RayCastOutput out;
          return c.oa.get()->RayCast(&out, toB2(c.linkRay), c.ba, 0);
        }));
  }

  // Does the bounding-circle test before GJK pay? On the pairs whose overlap goes through GJK,
  // first on the random placement of the overlap rows, then on pairs whose AABBs overlap.
  const PairKind gjkPairs[] = {{Kind::capsule, Kind::capsule},
                               {Kind::capsule, Kind::polygon},
                               {Kind::capsule, Kind::box},
                               {Kind::roundedPolygon, Kind::polygon},
                               {Kind::roundedPolygon, Kind::roundedPolygon},
                               {Kind::roundedPolygon, Kind::capsule},
                               {Kind::chainLink, Kind::circle},
                               {Kind::chainLink, Kind::polygon},
                               {Kind::chainLink, Kind::box}};
  seed = 900;
  for (PairKind p : gjkPairs) {
    std::string n = pairName(p);
    Placement place;
    place.rightOfLink = p.a == Kind::chainLink;
    const Cases* random =
        overlapCases.count(n) ? overlapCases.at(n) : keep(makeCases(p.a, p.b, seed + 50, place));
    prefilterRows(n + "/random", random);
    place.aabbOverlap = true;
    prefilterRows(n + "/aabb_overlap", keep(makeCases(p.a, p.b, seed++, place)));
  }
}

}  // namespace

int main(int argc, char** argv) {
  return rc::bench::runWithRatioTable(argc, argv, "geometry_bench", registerAll);
}
