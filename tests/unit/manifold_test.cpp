// Contact manifolds: hand-worked cases, fast paths against the general path, mirrored pairs,
// ghost-free chains, and a brute-force check of the deepest separation for every pair.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "physics/collide.h"
#include "physics/distance.h"
#include "physics/random.h"
#include "support/random_shapes.h"
#include "support/reference_geometry.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace manifold_test {

using rc::Vec2;
using rc::testing::Kind;
using rc::testing::support;

float deepest(const rc::Manifold& m) {
  float s = 1e30f;
  for (int i = 0; i < m.pointCount; ++i)
    s = std::min(s, m.points[i].separation);
  return s;
}

TEST(Manifold, BoxRestingOnGround) {
  rc::Transform ground{{0, -1.5f}, {}};
  rc::Transform body{{0.3f, -0.01f}, {}};
  for (bool general : {false, true}) {
    rc::Shape g =
        general ? rc::Shape(rc::makeOrientedBox(5, 0.5f)) : rc::Shape(rc::makeBox(5, 0.5f));
    rc::Shape b = general ? rc::Shape(rc::makeOrientedBox(1, 1)) : rc::Shape(rc::makeBox(1, 1));
    rc::Manifold m = rc::collide(g, ground, b, body);
    ASSERT_EQ(m.pointCount, 2) << general;
    EXPECT_NEAR(m.normal.x, 0.0f, 1e-6f);
    EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
    float xs[2] = {m.points[0].point.x, m.points[1].point.x};
    EXPECT_NEAR(std::min(xs[0], xs[1]), -0.7f, 1e-5f);
    EXPECT_NEAR(std::max(xs[0], xs[1]), 1.3f, 1e-5f);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(m.points[i].separation, -0.01f, 1e-5f);
      EXPECT_NEAR(m.points[i].point.y, -1.005f, 1e-5f);
      // Anchors are the point relative to each body's origin.
      EXPECT_NEAR(m.points[i].anchorA.y, 0.495f, 1e-5f);
      EXPECT_NEAR(m.points[i].anchorB.y, -0.995f, 1e-5f);
    }
  }
}

TEST(Manifold, CircleOnBoxAndOnPolygon) {
  rc::Shape circle = rc::makeCircle({0, 0}, 0.5f);
  rc::Transform c{{0.2f, 0.49f}, {}};
  for (rc::Shape ground :
       {rc::Shape(rc::makeBox(5, 1, {0, -1})), rc::Shape(rc::makeOrientedBox(5, 1, {0, -1}))}) {
    rc::Manifold m = rc::collide(ground, {}, circle, c);
    ASSERT_EQ(m.pointCount, 1);
    EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
    EXPECT_NEAR(m.points[0].separation, -0.01f, 1e-5f);
    EXPECT_NEAR(m.points[0].point.x, 0.2f, 1e-6f);
    EXPECT_NEAR(m.points[0].point.y, -0.005f, 1e-5f);
  }
  // Past the corner: the normal points from the corner to the centre.
  rc::Manifold corner = rc::collide(rc::makeBox(1, 1), {}, circle, {{1.3f, 1.3f}, {}});
  ASSERT_EQ(corner.pointCount, 1);
  EXPECT_NEAR(corner.normal.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(corner.points[0].separation, 0.3f * std::sqrt(2.0f) - 0.5f, 1e-5f);
}

TEST(Manifold, CapsuleFlatOnGroundAndEndToEnd) {
  rc::Shape cap = rc::makeCapsule({-1, 0}, {1, 0}, 0.25f);
  rc::Manifold flat = rc::collide(rc::makeBox(5, 0.5f), {{0, -0.5f}, {}}, cap, {{0, 0.24f}, {}});
  ASSERT_EQ(flat.pointCount, 2);
  EXPECT_NEAR(flat.normal.y, 1.0f, 1e-6f);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(flat.points[i].separation, -0.01f, 1e-5f);
  // End to end along x: the closest features are two vertices, one point, normal along x.
  rc::Manifold ends = rc::collide(cap, {}, cap, {{2.505f, 0.0f}, {}});
  ASSERT_EQ(ends.pointCount, 1);
  EXPECT_NEAR(ends.normal.x, 1.0f, 1e-6f);
  EXPECT_NEAR(ends.points[0].separation, 0.005f, 1e-5f);
  // Crossed at right angles, cores intersecting: the shortest way out is up by the 0.55 m of
  // B's core below A's axis plus both radii.
  rc::Manifold crossed = rc::collide(cap, {}, cap, {{0, 0.45f}, rc::Rot::fromAngle(rc::kPi / 2)});
  ASSERT_EQ(crossed.pointCount, 1);
  EXPECT_NEAR(crossed.normal.y, 1.0f, 1e-6f);
  EXPECT_NEAR(deepest(crossed), -1.05f, 1e-5f);
}

TEST(Manifold, SeparatedPolygonsVertexToVertexGetTheDiagonalNormal) {
  rc::Shape box = rc::makeOrientedBox(0.5f, 0.5f);
  rc::Transform b{{1.005f, 1.005f}, {}};
  rc::Manifold m = rc::collide(box, {}, box, b);
  ASSERT_EQ(m.pointCount, 1);
  EXPECT_NEAR(m.normal.x, std::sqrt(0.5f), 1e-4f);
  EXPECT_NEAR(m.points[0].separation, 0.005f * std::sqrt(2.0f), 1e-5f);
  // The aligned-box fast path agrees.
  rc::Manifold fast = rc::collide(rc::makeBox(0.5f, 0.5f), {}, rc::makeBox(0.5f, 0.5f), b);
  ASSERT_EQ(fast.pointCount, 1);
  EXPECT_NEAR(fast.points[0].separation, m.points[0].separation, 1e-6f);
}

TEST(Manifold, NothingBeyondTheSpeculativeDistance) {
  rc::Shape c = rc::makeCircle({}, 1);
  EXPECT_EQ(rc::collide(c, {}, c, {{2.0f + rc::kSpeculativeDistance * 1.1f, 0}, {}}).pointCount, 0);
  EXPECT_EQ(rc::collide(c, {}, c, {{2.0f + rc::kSpeculativeDistance * 0.9f, 0}, {}}).pointCount, 1);
}

TEST(Manifold, AlignedBoxFastPathMatchesGeneralPath) {
  rc::Random rng(21);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    rc::Box a =
        rc::makeBox(rng.uniform(0.1f, 2), rng.uniform(0.1f, 2), rng.inBox({-1, -1}, {1, 1}));
    rc::Box b =
        rc::makeBox(rng.uniform(0.1f, 2), rng.uniform(0.1f, 2), rng.inBox({-1, -1}, {1, 1}));
    rc::Transform xa{rng.inBox({-2, -2}, {2, 2}), {}}, xb{rng.inBox({-2, -2}, {2, 2}), {}};
    rc::Manifold fast = rc::collide(a, xa, b, xb);
    rc::Manifold slow = rc::collideHulls(a, xa, b, xb);
    ASSERT_EQ(fast.pointCount > 0, slow.pointCount > 0) << i;
    if (fast.pointCount == 0) continue;
    ++compared;
    EXPECT_NEAR(deepest(fast), deepest(slow), 1e-5f) << i;
    // Ties between the x and y axes may pick different normals; otherwise they agree.
    if (rc::dot(fast.normal, slow.normal) < 0.999f) {
      EXPECT_NEAR(deepest(fast), deepest(slow), 1e-5f);
      continue;
    }
    EXPECT_EQ(fast.pointCount, slow.pointCount) << i;
  }
  EXPECT_GT(compared, 5000);
}

// Turned boxes take a closed-form separating axis test (collideBoxes); the general path is the
// reference: the same points (matched by feature id), separations and normal, up to rounding.
// Random pairs at any angle, and boxes resting on and beside each other as in a pyramid
// (tilted by up to 0.02 rad, overlapping or apart by up to 5 mm), where nearly every contact
// takes the closed form. Where the two paths' reference faces differ (a tie between axes, or
// the hysteresis threshold met within rounding), the deepest separation must still agree.
TEST(Manifold, OrientedBoxesMatchTheHullPath) {
  rc::Random rng(31);
  int compared = 0, differentFace = 0;
  for (int i = 0; i < 40000; ++i) {
    rc::Box a, b;
    rc::Transform xa, xb;
    if (i % 2 == 0) {
      a = rc::makeBox(rng.uniform(0.1f, 2), rng.uniform(0.1f, 2), rng.inBox({-1, -1}, {1, 1}));
      b = rc::makeBox(rng.uniform(0.1f, 2), rng.uniform(0.1f, 2), rng.inBox({-1, -1}, {1, 1}));
      xa = {rng.inBox({-2, -2}, {2, 2}), rc::Rot::fromAngle(rng.uniform(-3.2f, 3.2f))};
      xb = {rng.inBox({-2, -2}, {2, 2}), rc::Rot::fromAngle(rng.uniform(-3.2f, 3.2f))};
    } else {
      a = rc::makeBox(0.5f, 0.5f);
      b = rc::makeBox(0.5f, 0.5f);
      const float gap = rng.uniform(-0.005f, 0.005f), offset = rng.uniform(-0.9f, 0.9f);
      const Vec2 base{rng.uniform(-20, 20), rng.uniform(0, 20)};
      const Vec2 up = i % 4 == 1 ? Vec2{offset, 1.0f + gap} : Vec2{1.0f + gap, 0.1f * offset};
      xa = {base, rc::Rot::fromAngle(rng.uniform(-0.02f, 0.02f))};
      xb = {base + up, rc::Rot::fromAngle(rng.uniform(-0.02f, 0.02f))};
    }
    const rc::Manifold fast = rc::collideBoxes(a, xa, b, xb);
    const rc::Manifold slow = rc::collideHulls(a, xa, b, xb);
    ASSERT_EQ(fast.pointCount > 0, slow.pointCount > 0) << i;
    if (fast.pointCount == 0) continue;
    ++compared;
    if (rc::dot(fast.normal, slow.normal) < 0.99999f) {
      ++differentFace;
      EXPECT_NEAR(deepest(fast), deepest(slow), 1e-5f) << i;
      continue;
    }
    ASSERT_EQ(fast.pointCount, slow.pointCount) << i;
    EXPECT_NEAR(fast.normal.x, slow.normal.x, 1e-6f) << i;
    EXPECT_NEAR(fast.normal.y, slow.normal.y, 1e-6f) << i;
    for (int k = 0; k < fast.pointCount; ++k) {
      int j = 0;
      while (j < slow.pointCount && slow.points[j].id != fast.points[k].id)
        ++j;
      ASSERT_LT(j, slow.pointCount) << i << ": no point with id " << fast.points[k].id;
      EXPECT_NEAR(fast.points[k].separation, slow.points[j].separation, 2e-5f) << i;
      EXPECT_NEAR(fast.points[k].point.x, slow.points[j].point.x, 1e-4f) << i;
      EXPECT_NEAR(fast.points[k].point.y, slow.points[j].point.y, 1e-4f) << i;
      EXPECT_NEAR(fast.points[k].anchorA.x, slow.points[j].anchorA.x, 1e-4f) << i;
      EXPECT_NEAR(fast.points[k].anchorB.y, slow.points[j].anchorB.y, 1e-4f) << i;
    }
  }
  std::printf("%d touching pairs compared, %d with another reference face\n", compared,
              differentFace);
  EXPECT_GT(compared, 20000);
  EXPECT_LT(differentFace, compared / 100);
}

TEST(Manifold, MirroredPairsAgree) {
  rc::Random rng(22);
  const Kind kinds[] = {Kind::circle,      Kind::box,     Kind::polygon, Kind::roundedPolygon,
                        Kind::orientedBox, Kind::capsule, Kind::segment};
  for (Kind ka : kinds) {
    for (Kind kb : kinds) {
      if (ka == Kind::segment && kb == Kind::segment) continue;
      int ties = 0;
      for (int i = 0; i < 2000; ++i) {
        rc::Shape a = rc::testing::randomShape(rng, ka), b = rc::testing::randomShape(rng, kb);
        rc::Transform xa = rc::testing::randomTransform(rng, {}, 1.0f);
        rc::Transform xb = rc::testing::randomTransform(rng, {}, 1.0f);
        rc::Manifold ab = rc::collide(a, xa, b, xb), ba = rc::collide(b, xb, a, xa);
        // Each side computes in its own frame, so results agree to rounding, not bits, and the
        // reference face is chosen with a 0.1 * slop preference for shape A: within that window
        // the mirrored call may use the other shape's face.
        ASSERT_EQ(ab.pointCount > 0, ba.pointCount > 0);
        if (ab.pointCount == 0) continue;
        EXPECT_NEAR(deepest(ab), deepest(ba), 0.1f * rc::kLinearSlop + 1e-5f);
        // Opposite normals (within 1e-3 rad), except where the two calls chose different
        // reference faces; those ties are counted and bounded.
        if (rc::dot(ab.normal, ba.normal) > -0.9999995f) ++ties;
      }
      EXPECT_LE(ties, 100) << rc::testing::kindName(ka) << " vs " << rc::testing::kindName(kb);
    }
  }
}

// Gap between the shapes' projections on n (A below, B above); its maximum over all directions
// is the distance when apart and minus the penetration depth when overlapping.
double gap(const rc::Shape& a, const rc::Transform& xa, const rc::Shape& b, const rc::Transform& xb,
           double angle) {
  Vec2 n{static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle))};
  return -static_cast<double>(support(b, xb, -n)) - support(a, xa, n);
}
double bestGap(const rc::Shape& a, const rc::Transform& xa, const rc::Shape& b,
               const rc::Transform& xb) {
  // The gap is a kinked function of the angle (Lipschitz with the shapes' size), so sample
  // densely and refine every local maximum among the samples by golden-section search.
  constexpr int kSamples = 1440;
  constexpr double kTwoPi = 6.283185307179586;
  constexpr double kStep = kTwoPi / kSamples;
  double g[kSamples];
  for (int k = 0; k < kSamples; ++k)
    g[k] = gap(a, xa, b, xb, kStep * k);
  double best = -1e30;
  for (int k = 0; k < kSamples; ++k) {
    best = std::max(best, g[k]);
    if (g[k] < g[(k + 1) % kSamples] || g[k] < g[(k + kSamples - 1) % kSamples]) continue;
    double lo = kStep * (k - 1), hi = kStep * (k + 1);
    const double r = 0.6180339887498949;
    for (int it = 0; it < 40; ++it) {
      double m1 = hi - r * (hi - lo), m2 = lo + r * (hi - lo);
      if (gap(a, xa, b, xb, m1) < gap(a, xa, b, xb, m2))
        lo = m1;
      else
        hi = m2;
    }
    best = std::max(best, gap(a, xa, b, xb, 0.5 * (lo + hi)));
  }
  return best;
}

TEST(Manifold, DeepestSeparationMatchesBruteForceForEveryPair) {
  rc::Random rng(23);
  const Kind kinds[] = {Kind::circle,      Kind::box,     Kind::polygon, Kind::roundedPolygon,
                        Kind::orientedBox, Kind::capsule, Kind::segment};
  for (Kind ka : kinds) {
    for (Kind kb : kinds) {
      if (ka == Kind::segment && kb == Kind::segment) continue;
      int touching = 0, clippedAway = 0;
      for (int i = 0; i < 600; ++i) {
        rc::Shape a = rc::testing::randomShape(rng, ka), b = rc::testing::randomShape(rng, kb);
        rc::Transform xa = rc::testing::randomTransform(rng, {}, 0.8f);
        rc::Transform xb = rc::testing::randomTransform(rng, {}, 0.8f);
        double truth = bestGap(a, xa, b, xb);
        rc::Manifold m = rc::collide(a, xa, b, xb);
        std::string what = std::string(rc::testing::kindName(ka)) + " vs " +
                           rc::testing::kindName(kb) + " case " + std::to_string(i);
        if (truth > rc::kSpeculativeDistance + 1e-4) {
          EXPECT_EQ(m.pointCount, 0) << what << " gap " << truth;
          continue;
        }
        if (truth < rc::kSpeculativeDistance - 1e-4) {
          ASSERT_GT(m.pointCount, 0) << what << " gap " << truth;
        }
        if (m.pointCount == 0) continue;
        ++touching;
        // The normal is (near) optimal: the projections along it are as far apart as the best.
        double along = -static_cast<double>(support(b, xb, -m.normal)) - support(a, xa, m.normal);
        EXPECT_NEAR(along, truth, 1e-3) << what;
        // The deepest point has the depth along the normal, unless clipping to the reference
        // face removed the deepest incident vertex (then it is shallower): count those.
        double d = deepest(m);
        if (d > along + 1e-3) {
          ++clippedAway;
          continue;
        }
        EXPECT_NEAR(d, along, 1e-3) << what;
      }
      EXPECT_GT(touching, 60) << rc::testing::kindName(ka) << " vs " << rc::testing::kindName(kb);
      EXPECT_LE(clippedAway, touching / 20)
          << rc::testing::kindName(ka) << " vs " << rc::testing::kindName(kb);
    }
  }
}

TEST(Manifold, SeparationsAgreeWithDistanceWhenApart) {
  rc::Random rng(24);
  for (int i = 0; i < 20000; ++i) {
    Kind ka = static_cast<Kind>(rng.below(7)), kb = static_cast<Kind>(rng.below(6));
    rc::Shape a = rc::testing::randomShape(rng, ka), b = rc::testing::randomShape(rng, kb);
    rc::Transform xa = rc::testing::randomTransform(rng, {}, 1.0f);
    rc::Transform xb = rc::testing::randomTransform(rng, {}, 1.0f);
    float dist = rc::shapeDistance(a, xa, b, xb).distance;
    if (dist <= 1e-4f) continue;
    rc::Manifold m = rc::collide(a, xa, b, xb);
    if (dist > rc::kSpeculativeDistance + 1e-4f) {
      EXPECT_EQ(m.pointCount, 0);
    } else if (dist < rc::kSpeculativeDistance - 1e-4f) {
      ASSERT_GT(m.pointCount, 0);
      EXPECT_NEAR(deepest(m), dist, 1e-4f) << i;
    }
  }
}

TEST(Manifold, InvariantUnderMovingBothShapes) {
  rc::Random rng(25);
  for (int i = 0; i < 20000; ++i) {
    Kind ka = static_cast<Kind>(rng.below(7)), kb = static_cast<Kind>(rng.below(6));
    rc::Shape a = rc::testing::randomShape(rng, ka), b = rc::testing::randomShape(rng, kb);
    rc::Transform xa = rc::testing::randomTransform(rng, {}, 0.8f);
    rc::Transform xb = rc::testing::randomTransform(rng, {}, 0.8f);
    rc::Transform move = rc::testing::randomTransform(rng, {}, 50.0f);
    rc::Manifold m1 = rc::collide(a, xa, b, xb);
    rc::Manifold m2 = rc::collide(a, rc::mul(move, xa), b, rc::mul(move, xb));
    if (m1.pointCount == 0 && m2.pointCount == 0) continue;
    if (m1.pointCount == 0 || m2.pointCount == 0) {
      // Only a case right at the speculative boundary may differ.
      float d = rc::shapeDistance(a, xa, b, xb).distance;
      EXPECT_NEAR(d, rc::kSpeculativeDistance, 1e-3f) << i;
      continue;
    }
    EXPECT_NEAR(deepest(m1), deepest(m2), 2e-4f) << i;
  }
}

TEST(Manifold, ShapesFarFromTheOriginBehaveAsAtTheOrigin) {
  rc::Shape box = rc::makeOrientedBox(0.5f, 0.5f);
  for (float far : {0.0f, 1e3f, 1e4f}) {
    rc::Transform ground{{far, far - 1.0f}, {}};
    rc::Transform body{{far + 0.1f, far - 0.002f}, rc::Rot::fromAngle(0.001f)};
    rc::Manifold m = rc::collide(rc::makeOrientedBox(5, 0.5f), ground, box, body);
    ASSERT_EQ(m.pointCount, 2) << far;
    EXPECT_NEAR(deepest(m), -0.002f - 0.5f * std::sin(0.001f), 1e-3f) << far;
  }
}

TEST(Manifold, FeatureIdsStableUnderSmallMotion) {
  rc::Shape ground = rc::makeOrientedBox(5, 0.5f), box = rc::makeOrientedBox(0.5f, 0.5f);
  rc::Manifold prev = rc::collide(ground, {{0, -0.5f}, {}}, box, {{0, 0.49f}, {}});
  ASSERT_EQ(prev.pointCount, 2);
  for (int step = 1; step < 100; ++step) {
    rc::Transform body{{0.01f * static_cast<float>(step), 0.49f},
                       rc::Rot::fromAngle(0.0005f * static_cast<float>(step % 3))};
    rc::Manifold m = rc::collide(ground, {{0, -0.5f}, {}}, box, body);
    ASSERT_EQ(m.pointCount, 2);
    EXPECT_EQ(m.points[0].id, prev.points[0].id);
    EXPECT_EQ(m.points[1].id, prev.points[1].id);
    prev = m;
  }
}

// A box sliding across a flat floor made of links must only ever see the floor's normal.
// The same floor made of independent segments catches the box's corner on the joints (a ghost
// collision), which shows this test can fail.
TEST(Manifold, FlatChainHasNoGhostCollisions) {
  // Right to left, so each link's right side (its collision side) faces up.
  std::vector<Vec2> pts = {{4, 0}, {3, 0}, {2, 0}, {1, 0}, {0, 0}};
  auto links = rc::makeChain(pts, false, true);
  rc::Shape box = rc::makeOrientedBox(0.25f, 0.25f);
  int ghostsWithSegments = 0, contacts = 0;
  for (int k = 0; k <= 300; ++k) {
    rc::Transform body{{0.5f + 0.01f * static_cast<float>(k), 0.25f - 0.003f}, {}};
    for (const rc::ChainSegment& link : links) {
      rc::Manifold m = rc::collide(link, {}, box, body);
      if (m.pointCount > 0) {
        ++contacts;
        EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f) << "x " << body.p.x;
      }
      rc::Manifold plain = rc::collide(rc::Shape(link.segment), {}, box, body);
      if (plain.pointCount > 0 && plain.normal.y < 0.99f) ++ghostsWithSegments;
    }
  }
  EXPECT_GT(contacts, 300);
  EXPECT_GT(ghostsWithSegments, 0);
}

TEST(Manifold, ConvexChainCornerKeepsTheCornerNormal) {
  // A counter-clockwise square loop: its outside is the links' right side.
  std::vector<Vec2> pts = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  auto links = rc::makeChain(pts, true, true);
  rc::Shape circle = rc::makeCircle({}, 0.5f);
  rc::Transform c{{2.3f, 2.3f}, {}};  // diagonally off the corner (2, 2)
  int reported = 0;
  for (const rc::ChainSegment& link : links) {
    rc::Manifold m = rc::collide(link, {}, circle, c);
    if (m.pointCount == 0) continue;
    ++reported;
    EXPECT_NEAR(m.normal.x, std::sqrt(0.5f), 1e-5f);
    EXPECT_NEAR(m.normal.y, std::sqrt(0.5f), 1e-5f);
  }
  EXPECT_GE(reported, 1);
  // One-sided: a circle inside the loop collides with nothing.
  for (const rc::ChainSegment& link : links)
    EXPECT_EQ(rc::collide(link, {}, circle, {{1.0f, 0.3f}, {}}).pointCount, 0);
}

// The chain-circle fast path against the general chain path (which builds two hulls), on
// random links with convex, concave, flat and open joints, circles up to 0.2 m deep from both
// sides, one-sided and two-sided.
TEST(Manifold, ChainCircleFastPathMatchesTheGeneralPath) {
  rc::Random rng(4242);
  int contacts = 0, clamped = 0, leaning = 0;
  for (int i = 0; i < 100000; ++i) {
    rc::ChainSegment link = rc::testing::randomChainLink(rng, rng.below(4) != 0);
    rc::Circle circle =
        rc::makeCircle(rng.inBox({-0.2f, -0.2f}, {0.2f, 0.2f}), rng.uniform(0.05f, 0.8f));
    rc::Transform xa = rc::testing::randomTransform(rng, {}, 1.0f);
    // The circle's centre near the link or one of its joints.
    Vec2 p1 = link.segment.point1, p2 = link.segment.point2;
    Vec2 near = rc::lerp(p1, p2, rng.uniform(-0.3f, 1.3f));
    Vec2 n = rc::normalize(rc::rightPerp(p2 - p1));
    float offset = circle.radius + rng.uniform(-0.2f, 0.05f);
    if (rng.below(5) == 0) offset = -offset;  // behind the link
    Vec2 centre = rc::mulAdd(near, offset, n) + 0.05f * rng.inBox({-1, -1}, {1, 1});
    rc::Transform xb{rc::apply(xa, centre - circle.center), xa.q};
    rc::Manifold fast = rc::collideChainSegmentAndCircle(link, xa, circle, xb);
    rc::Manifold general = rc::collideChainSegment(link, xa, rc::Shape(circle), xb);
    ASSERT_EQ(fast.pointCount, general.pointCount) << "case " << i;
    if (fast.pointCount == 0) continue;
    ++contacts;
    clamped += (fast.points[0].id & 0x2000) != 0;
    leaning += (fast.points[0].id & 0x100) != 0;
    // Rounding differs (world to link frame once, or through the hulls): a normal from a
    // difference of points a few centimetres long moves by ~1e-5.
    EXPECT_NEAR(fast.normal.x, general.normal.x, 1e-4f) << "case " << i;
    EXPECT_NEAR(fast.normal.y, general.normal.y, 1e-4f) << "case " << i;
    EXPECT_NEAR(fast.points[0].separation, general.points[0].separation, 1e-5f) << "case " << i;
    EXPECT_NEAR(fast.points[0].point.x, general.points[0].point.x, 1e-5f) << "case " << i;
    EXPECT_NEAR(fast.points[0].point.y, general.points[0].point.y, 1e-5f) << "case " << i;
    EXPECT_EQ(fast.points[0].id, general.points[0].id)
        << "case " << i << " sep " << fast.points[0].separation << " normal (" << fast.normal.x
        << ", " << fast.normal.y << ")";
  }
  EXPECT_GT(contacts, 30000);
  EXPECT_GT(leaning, 1000);  // the joints are exercised
  std::printf("%d contacts, %d at the ends, %d clamped to a joint's vertex\n", contacts, leaning,
              clamped);
}

// A box pressed into a V-shaped valley of one-sided links (a concave joint) is pushed out of
// both walls along their own normals, whichever face of the box leans towards the joint.
TEST(Manifold, ChainValleyPushesOutOfBothWalls) {
  // Right wall down to the bottom, left wall up: the valley opens upwards (the links' right).
  std::vector<Vec2> pts = {{2, 2}, {0, 0}, {-2, 2}};
  auto links = rc::makeChain(pts, false, true);
  ASSERT_EQ(links.size(), 2u);
  const Vec2 right = rc::normalize(Vec2{-1, 1}), left = rc::normalize(Vec2{1, 1});
  for (float angle : {0.0f, 0.3f, -0.3f, 0.7f}) {
    rc::Shape box = rc::makeOrientedBox(0.5f, 0.5f, {}, angle);
    rc::Transform body{{0.0f, 0.65f}, {}};
    rc::Manifold m0 = rc::collide(links[0], {}, box, body);
    rc::Manifold m1 = rc::collide(links[1], {}, box, body);
    ASSERT_GT(m0.pointCount, 0) << angle;
    ASSERT_GT(m1.pointCount, 0) << angle;
    EXPECT_NEAR(rc::dot(m0.normal, right), 1.0f, 1e-5f) << angle;
    EXPECT_NEAR(rc::dot(m1.normal, left), 1.0f, 1e-5f) << angle;
  }
}

// A one-sided link with neighbours on both sides never pushes a shape in front of it out
// through its back: every normal it reports is its own or lies in a convex joint's fan, so it
// points to the link's front. Random polygons up to 0.3 m deep across random links.
TEST(Manifold, ChainNeverPushesThroughItsBack) {
  rc::Random rng(777);
  int contacts = 0;
  for (int i = 0; i < 50000; ++i) {
    rc::ChainSegment link = rc::testing::randomChainLink(rng, true);
    if (link.ghost1 == link.segment.point1 || link.ghost2 == link.segment.point2) continue;
    rc::Shape b = rc::testing::randomShape(rng, Kind::polygon);
    Vec2 p1 = link.segment.point1, p2 = link.segment.point2;
    Vec2 n = rc::normalize(rc::rightPerp(p2 - p1));
    rc::Transform xb = rc::testing::randomTransform(rng, rc::lerp(p1, p2, rng.uniform()), 0.0f);
    // Deepest point of b 0 to 0.3 m past the link's line.
    float gap = -support(b, xb, -n) - rc::dot(n, p1);
    xb.p = rc::mulAdd(xb.p, -gap - rng.uniform(0.0f, 0.3f), n);
    if (rc::dot(rc::apply(xb, rc::computeMass(b, 1.0f).center) - p1, n) < 0.0f) continue;
    rc::Manifold m = rc::collide(link, {}, b, xb);
    if (m.pointCount == 0) continue;
    ++contacts;
    EXPECT_GT(rc::dot(m.normal, n), 0.0f) << "case " << i;
  }
  EXPECT_GT(contacts, 10000);
}

TEST(Manifold, UnregisteredPairFailsLoudly) {
  rc::Shape s = rc::makeSegment({0, 0}, {1, 0});
  EXPECT_THROW(rc::collide(s, {}, s, {}), rc::UnsupportedPair);
  EXPECT_FALSE(rc::hasManifold(rc::ShapeType::segment, rc::ShapeType::chainSegment));
  EXPECT_TRUE(rc::hasManifold(rc::ShapeType::chainSegment, rc::ShapeType::polygon));
  // Overlap is defined for every pair, segments included.
  EXPECT_TRUE(rc::testOverlap(s, {}, rc::makeSegment({0.5f, -1}, {0.5f, 1}), {}));
}

TEST(Overlap, AgreesWithDistanceForEveryPair) {
  rc::Random rng(26);
  for (int i = 0; i < 20000; ++i) {
    Kind ka = static_cast<Kind>(rng.below(7)), kb = static_cast<Kind>(rng.below(7));
    rc::Shape a = rc::testing::randomShape(rng, ka), b = rc::testing::randomShape(rng, kb);
    rc::Transform xa = rc::testing::randomTransform(rng, {}, 1.0f);
    rc::Transform xb = rc::testing::randomTransform(rng, {}, 1.0f);
    double truth = bestGap(a, xa, b, xb);
    if (std::fabs(truth) < 1e-4) continue;  // the touching band
    EXPECT_EQ(rc::testOverlap(a, xa, b, xb), truth < 0)
        << rc::testing::kindName(ka) << " vs " << rc::testing::kindName(kb) << " " << i;
  }
}

}  // namespace manifold_test
