// Shape distance (rc::shapeDistance, GJK) against Box2D 2.4.1's b2Distance.
//
// Both sides get exactly the same geometry. The Box2D proxies are not built with
// b2DistanceProxy::Set(shape, ...): that would give every polygon Box2D's skin b2_polygonRadius
// (2 * b2_linearSlop = 1 cm) and push polygon distances 1 cm apart from ours. Instead the proxy
// members (m_vertices, m_count, m_radius, m_buffer) are filled directly from our rc::ShapeProxy
// (rc::makeProxy): the same core points and our own radius, 0 for sharp polygons, boxes and
// segments. b2Distance runs with useRadii = true and a cold b2SimplexCache (count = 0), as ours
// runs without a cache.
//
// For each of the 21 unordered pairs of {circle, box, polygon (half sharp, half rounded), capsule,
// segment, chain link}, 100,000 seeded cases, half in each order (case i of a pair draws
// everything from rc::Random(pairSeed * 1'000'003 + i), so any case replays alone), with the
// shapes within a few metres of each other so that both separated and overlapping cases occur.
// Chain links (rc::testing::randomChainLink) are half one-sided, half two-sided: distance ignores
// sidedness and ghosts, and rc::makeProxy makes a link the 2-point core of its segment (Box2D's
// b2DistanceProxy::Set does the same with a chain's b2EdgeShape). A quarter of the cases turn B a
// whole number of quarter turns from A (parallel edges), and a quarter are moved to within
// [-3e-4, 1e-3] m of touching. Checks:
//   - distances agree within 1e-4 m;
//   - the overlap decision (distance == 0 or > 0) agrees outside a +-1e-4 m band around touching;
//   - when the distance is above 1e-3 m, the closest points agree within 1e-4 m, except where the
//     closest feature is not unique (parallel edges): GJK may then return any of a continuum of
//     closest pairs, and Box2D's and ours may differ. That case is recognised by both answers
//     being right: each side's point A on A's surface and at the distance from B (the
//     |pointB - pointA| of either answer, measured from either side's point), within 1e-4 m, and
//     likewise for the B points. Point-to-shape distances are computed here independently, in
//     double.
#include <box2d/b2_distance.h>
#include <box2d/box2d.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "physics/distance.h"
#include "physics/random.h"
#include "physics/shapes.h"
#include "support/box2d_adapter.h"
#include "support/random_shapes.h"
#include "support/reference_geometry.h"
#include "support/sanitizers.h"

namespace {

using rc::Vec2;
using rc::testing::Core;
using rc::testing::dist;
using rc::testing::P2;
using rc::testing::pointSegmentDistance;
using rc::testing::signedSurfaceDistance;
using rc::testing::toP2;

enum Kind { kCircle, kBox, kPolygon, kCapsule, kSegment, kChainLink, kKindCount };
const char* const kKindNames[kKindCount] = {"circle",  "box",     "polygon",
                                            "capsule", "segment", "chain_link"};

constexpr int kCasesPerPair = rc::testing::casesUnderSanitizers(100000);
constexpr double kDistanceTolerance = 1e-4;
constexpr double kPointTolerance = 1e-4;
constexpr double kPointCompareAbove = 1e-3;

// ---- Independent point-to-shape distance in double ----

P2 toP2(b2Vec2 v) {
  return {v.x, v.y};
}

// The core as Box2D sees it: our proxy's points, transformed in double.
Core worldCore(const rc::ShapeProxy& s, const rc::Transform& xf) {
  return rc::testing::worldCore(s.points, s.count, s.radius, xf);
}

// ---- Random shapes ----

rc::Shape randomShape(rc::Random& rng, int kind) {
  for (;;) {
    Vec2 c = rng.inBox({-0.5f, -0.5f}, {0.5f, 0.5f});
    try {
      switch (kind) {
        case kCircle:
          return rc::makeCircle(c, rng.uniform(0.05f, 1.2f));
        case kBox:
          return rc::makeBox(rng.uniform(0.05f, 1.2f), rng.uniform(0.05f, 1.2f), c);
        case kPolygon: {
          int n = 3 + static_cast<int>(rng.below(6));
          float size = rng.uniform(0.1f, 1.5f);
          Vec2 pts[rc::kMaxPolygonVertices];
          for (int k = 0; k < n; ++k)
            pts[k] = c + size * rng.inBox({-1, -1}, {1, 1});
          // Half sharp, half rounded.
          float radius = rng.below(2) == 0 ? 0.0f : rng.uniform(0.01f, 0.4f);
          return rc::makePolygon(std::span<const Vec2>(pts, static_cast<size_t>(n)), radius);
        }
        case kCapsule:
          return rc::makeCapsule(c, c + rng.inBox({-1.5f, -1.5f}, {1.5f, 1.5f}),
                                 rng.uniform(0.05f, 0.8f));
        case kChainLink:
          // A link 0.2 to 2.5 m long within 1 m of the origin, with ghosts (ignored here).
          return rc::testing::randomChainLink(rng, rng.below(2) == 0);
        default:
          return rc::makeSegment(c, c + rng.inBox({-2, -2}, {2, 2}));
      }
    } catch (const rc::InvalidShape&) {
      // Degenerate cloud or too-short axis: draw again.
    }
  }
}

struct PairKinds {
  int a;
  int b;
};

std::string pairName(const ::testing::TestParamInfo<PairKinds>& info) {
  return std::string(kKindNames[info.param.a]) + "_" + kKindNames[info.param.b];
}

class ShapePairs : public ::testing::TestWithParam<PairKinds> {};

TEST_P(ShapePairs, AgreeWithBox2D) {
  const PairKinds kinds = GetParam();
  const std::uint64_t pairSeed = 5000 + static_cast<std::uint64_t>(10 * kinds.a + kinds.b);
  int overlapping = 0, separated = 0, pointsCompared = 0, nonUnique = 0, failures = 0;
  double worstDistance = 0.0, worstPoint = 0.0;
  std::ostringstream firstFailures;
  firstFailures.precision(9);

  for (int i = 0; i < kCasesPerPair; ++i) {
    const std::uint64_t seed = pairSeed * 1'000'003u + static_cast<std::uint64_t>(i);
    rc::Random rng(seed);
    // Odd cases swap the order, so both (A, B) and (B, A) of the unordered pair are run.
    const bool swap = (i % 2) == 1;
    rc::Shape a = randomShape(rng, swap ? kinds.b : kinds.a);
    rc::Shape b = randomShape(rng, swap ? kinds.a : kinds.b);
    rc::Transform xfA{rng.inBox({-1, -1}, {1, 1}), rc::Rot::fromAngle(rng.uniform(-4, 4))};
    rc::Transform xfB{rng.inBox({-2, -2}, {2, 2}), rc::Rot::fromAngle(rng.uniform(-4, 4))};
    const int mode = static_cast<int>(rng.below(4));
    if (mode == 2) {
      // B turned a whole number of quarter turns from A, exactly: boxes get parallel edges, so
      // closest features are often not unique.
      const rc::Rot quarter{0.0f, 1.0f};
      xfB.q = xfA.q;
      for (std::uint32_t k = rng.below(4); k > 0; --k)
        xfB.q = rc::mul(xfB.q, quarter);
    }
    rc::ShapeProxy pa = rc::makeProxy(a), pb = rc::makeProxy(b);

    rc::DistanceOutput ours = rc::shapeDistance(pa, xfA, pb, xfB);
    if (mode == 3 && ours.distance > 0.0f) {
      // Near touching: move B along the normal to leave a gap in [-3e-4, 1e-3] m (a negative gap
      // is an overlap of that depth), so the +-1e-4 band around touching is crossed both ways.
      const float gap = rng.uniform(-3e-4f, 1e-3f);
      xfB.p = rc::mulSub(xfB.p, ours.distance - gap, ours.normal);
      ours = rc::shapeDistance(pa, xfA, pb, xfB);
    }

    const b2DistanceOutput theirs =
        rc::testing::box2dDistance(pa, rc::testing::toB2(xfA), pb, rc::testing::toB2(xfB), true);

    auto fail = [&](const std::string& what) {
      if (failures < 5) {
        firstFailures << "\n  case " << i << " (rc::Random seed " << seed << "): " << what
                      << "; ours d=" << ours.distance << " A=(" << ours.pointA.x << ", "
                      << ours.pointA.y << ") B=(" << ours.pointB.x << ", " << ours.pointB.y
                      << "); box2d d=" << theirs.distance << " A=(" << theirs.pointA.x << ", "
                      << theirs.pointA.y << ") B=(" << theirs.pointB.x << ", " << theirs.pointB.y
                      << ")";
      }
      ++failures;
    };

    if (!rc::isFinite(ours.distance) || !rc::isFinite(ours.pointA) || !rc::isFinite(ours.pointB) ||
        !rc::isFinite(ours.normal)) {
      fail("non-finite output");
      continue;
    }
    const double dOurs = ours.distance, dTheirs = theirs.distance;
    const double dErr = std::fabs(dOurs - dTheirs);
    worstDistance = std::max(worstDistance, dErr);
    if (dErr > kDistanceTolerance) fail("distance differs by " + std::to_string(dErr));

    const bool oursOverlap = ours.distance == 0.0f, theirsOverlap = theirs.distance == 0.0f;
    if (oursOverlap != theirsOverlap && std::max(dOurs, dTheirs) > kDistanceTolerance)
      fail("overlap decision differs outside the touching band");
    (theirsOverlap ? overlapping : separated) += 1;

    if (dOurs > kPointCompareAbove && dTheirs > kPointCompareAbove) {
      ++pointsCompared;
      const double eA = dist(toP2(ours.pointA), toP2(theirs.pointA));
      const double eB = dist(toP2(ours.pointB), toP2(theirs.pointB));
      if (eA > kPointTolerance || eB > kPointTolerance) {
        // Both answers right? Each A point on A's surface and at the distance from B, and each B
        // point on B's surface and at the distance from A.
        Core ca = worldCore(pa, xfA), cb = worldCore(pb, xfB);
        auto closestOnA = [&](P2 p) {
          return std::fabs(signedSurfaceDistance(ca, p)) <= kPointTolerance &&
                 std::fabs(signedSurfaceDistance(cb, p) - dTheirs) <= kPointTolerance;
        };
        auto closestOnB = [&](P2 p) {
          return std::fabs(signedSurfaceDistance(cb, p)) <= kPointTolerance &&
                 std::fabs(signedSurfaceDistance(ca, p) - dTheirs) <= kPointTolerance;
        };
        if (closestOnA(toP2(ours.pointA)) && closestOnA(toP2(theirs.pointA)) &&
            closestOnB(toP2(ours.pointB)) && closestOnB(toP2(theirs.pointB))) {
          ++nonUnique;
        } else {
          worstPoint = std::max(worstPoint, std::max(eA, eB));
          fail("closest points differ by " + std::to_string(std::max(eA, eB)));
        }
      } else {
        worstPoint = std::max(worstPoint, std::max(eA, eB));
      }
    }
  }

  EXPECT_EQ(failures, 0) << failures << " of " << kCasesPerPair
                         << " cases disagree; the first:" << firstFailures.str();
  // Both regimes are exercised.
  EXPECT_GT(overlapping, kCasesPerPair / 20);
  EXPECT_GT(separated, kCasesPerPair / 20);
  // Non-unique closest features are the exception.
  EXPECT_LT(nonUnique, pointsCompared / 20);
  RecordProperty("overlapping", overlapping);
  RecordProperty("separated", separated);
  RecordProperty("points_compared", pointsCompared);
  RecordProperty("non_unique", nonUnique);
  RecordProperty("worst_distance_error", std::to_string(worstDistance));
  RecordProperty("worst_point_error", std::to_string(worstPoint));
}

std::vector<PairKinds> allUnorderedPairs() {
  std::vector<PairKinds> pairs;
  for (int a = 0; a < kKindCount; ++a) {
    for (int b = a; b < kKindCount; ++b)
      pairs.push_back({a, b});
  }
  return pairs;
}

// The prefix keeps the full names under DistanceOracle* (DistanceOracle/ShapePairs.Agree...).
INSTANTIATE_TEST_SUITE_P(DistanceOracle, ShapePairs, ::testing::ValuesIn(allUnorderedPairs()),
                         pairName);

TEST(DistanceOracle, PairListCoversAllTwentyOneUnorderedPairs) {
  EXPECT_EQ(allUnorderedPairs().size(), 21u);
}

}  // namespace
