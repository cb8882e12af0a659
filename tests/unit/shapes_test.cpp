// Shape factories, validation, hulls, bounding boxes, containment and mass properties against
// closed forms and a Monte Carlo integral (an independent check for rounded polygons).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "physics/random.h"
#include "physics/shapes.h"

namespace {

using rc::Vec2;
constexpr double kPi = 3.14159265358979323846;
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

TEST(Shapes, RejectsNonFiniteAndNonPositive) {
  EXPECT_THROW(rc::makeCircle({kNaN, 0}, 1), rc::InvalidShape);
  EXPECT_THROW(rc::makeCircle({0, 0}, 0), rc::InvalidShape);
  EXPECT_THROW(rc::makeCircle({0, 0}, -1), rc::InvalidShape);
  EXPECT_THROW(rc::makeCircle({0, 0}, kInf), rc::InvalidShape);
  EXPECT_THROW(rc::makeBox(0, 1), rc::InvalidShape);
  EXPECT_THROW(rc::makeBox(1, kNaN), rc::InvalidShape);
  EXPECT_THROW(rc::makeCapsule({0, 0}, {0, 0}, 1), rc::InvalidShape);
  EXPECT_THROW(rc::makeSegment({1, 1}, {1, 1}), rc::InvalidShape);
  EXPECT_THROW(rc::makeOrientedBox(1, 1, {}, kNaN), rc::InvalidShape);
  EXPECT_THROW(rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {kInf, 1}}), rc::InvalidShape);
  EXPECT_THROW(rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}}, -0.1f), rc::InvalidShape);
}

TEST(Shapes, ErrorMessagesNameTheField) {
  try {
    rc::makeCircle({0, 0}, -2);
    FAIL();
  } catch (const rc::InvalidShape& e) {
    EXPECT_STREQ(e.what(), "circle: radius must be positive, got -2");
  }
  try {
    rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}});
    FAIL();
  } catch (const rc::InvalidShape& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
}

TEST(Shapes, HullDropsDuplicatesCollinearAndInteriorPoints) {
  std::vector<Vec2> pts = {{0, 0}, {2, 0}, {1, 0}, {2, 2}, {0, 2},
                           {1, 1}, {0, 0}, {2, 2}, {0, 1}, {1e-4f, 1e-4f}};
  rc::Polygon p = rc::makePolygon(pts);
  ASSERT_EQ(p.count, 4);
  // Counter-clockwise, unit normals pointing out.
  for (int i = 0; i < p.count; ++i) {
    Vec2 e1 = p.vertices[(i + 1) % 4] - p.vertices[i];
    Vec2 e2 = p.vertices[(i + 2) % 4] - p.vertices[(i + 1) % 4];
    EXPECT_GT(rc::cross(e1, e2), 0.0f);
    EXPECT_NEAR(rc::length(p.normals[i]), 1.0f, 1e-6f);
    EXPECT_NEAR(rc::dot(p.normals[i], p.vertices[i] - p.centroid), 1.0f, 1e-6f);
  }
  EXPECT_NEAR(p.centroid.x, 1.0f, 1e-6f);
  EXPECT_NEAR(p.centroid.y, 1.0f, 1e-6f);
}

TEST(Shapes, HullRejectsTooManyVerticesAndDegenerateClouds) {
  std::vector<Vec2> circle;
  for (int i = 0; i < 12; ++i) {
    rc::SinCos sc = rc::sincos(static_cast<float>(i) * 2.0f * rc::kPi / 12.0f);
    circle.push_back({sc.cosine, sc.sine});
  }
  EXPECT_THROW(rc::makePolygon(circle), rc::InvalidShape);
  std::vector<Vec2> same(1000, Vec2{3, 4});
  EXPECT_THROW(rc::makePolygon(same), rc::InvalidShape);
  EXPECT_THROW(rc::makeTriangle({0, 0}, {1, 1}, {2, 2}), rc::InvalidShape);
  // A random cloud always gives a valid convex polygon containing every point.
  rc::Random rng(7);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<Vec2> cloud;
    for (int i = 0; i < 8; ++i)
      cloud.push_back(rng.inBox({-1, -1}, {1, 1}));
    rc::Polygon p = rc::makePolygon(cloud);
    EXPECT_NO_THROW(rc::validate(p));
    for (Vec2 q : cloud) {
      for (int i = 0; i < p.count; ++i)
        EXPECT_LE(rc::dot(p.normals[i], q - p.vertices[i]), rc::kLinearSlop);
    }
  }
}

TEST(Shapes, ChainLinksKnowTheirNeighbours) {
  std::vector<Vec2> pts = {{0, 0}, {1, 0}, {2, 1}, {3, 1}};
  auto open = rc::makeChain(pts, false);
  ASSERT_EQ(open.size(), 3u);
  EXPECT_EQ(open[0].ghost1, (Vec2{0, 0}));
  EXPECT_EQ(open[0].ghost2, (Vec2{2, 1}));
  EXPECT_EQ(open[2].ghost2, (Vec2{3, 1}));
  auto loop = rc::makeChain(pts, true);
  ASSERT_EQ(loop.size(), 4u);
  EXPECT_EQ(loop[0].ghost1, (Vec2{3, 1}));
  EXPECT_EQ(loop[3].segment.point2, (Vec2{0, 0}));
  EXPECT_EQ(loop[3].ghost2, (Vec2{1, 0}));
  EXPECT_THROW(rc::makeChain(std::vector<Vec2>{{0, 0}, {0, 0}, {1, 1}}, false), rc::InvalidShape);
  EXPECT_THROW(rc::makeChain(std::vector<Vec2>{{0, 0}, {1, 1}}, true), rc::InvalidShape);
}

TEST(Shapes, AabbsBoundTheShapeUnderTransforms) {
  rc::Random rng(3);
  std::vector<rc::Shape> shapes = {
      rc::makeCircle({0.3f, -0.2f}, 0.7f), rc::makeBox(1.0f, 0.4f, {0.1f, 0.2f}),
      rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {0.3f, 1.2f}}, 0.1f),
      rc::makeCapsule({-1, 0}, {1, 0.5f}, 0.3f), rc::makeSegment({-1, -1}, {2, 0.5f})};
  for (const rc::Shape& s : shapes) {
    for (int t = 0; t < 200; ++t) {
      rc::Transform xf{rng.inBox({-50, -50}, {50, 50}), rc::Rot::fromAngle(rng.uniform(-4, 4))};
      rc::AABB box = rc::computeAABB(s, xf);
      // Sample points of the shape by rejection; each must lie in the box.
      for (int k = 0; k < 200; ++k) {
        Vec2 local = rng.inBox({-3, -3}, {3, 3});
        Vec2 world = rc::apply(xf, local);
        if (rc::containsPoint(s, xf, world)) {
          EXPECT_TRUE(rc::inflate(box, 1e-4f).contains(world)) << rc::shapeTypeName(s.type);
        }
      }
    }
  }
}

TEST(Shapes, ClosedFormMass) {
  rc::MassData c = rc::computeMass(rc::makeCircle({1, 2}, 2.0f), 3.0f);
  EXPECT_NEAR(c.mass, 3 * kPi * 4, 1e-4);
  EXPECT_NEAR(c.inertia, 0.5 * c.mass * 4, 1e-4);
  EXPECT_EQ(c.center, (Vec2{1, 2}));
  rc::MassData b = rc::computeMass(rc::makeBox(2, 1, {5, 0}), 1.0f);
  EXPECT_NEAR(b.mass, 8, 1e-6);
  EXPECT_NEAR(b.inertia, 8.0 * (16 + 4) / 12, 1e-5);
  rc::MassData pb = rc::computeMass(rc::makeOrientedBox(2, 1, {5, 0}, 0.3f), 1.0f);
  EXPECT_NEAR(pb.mass, b.mass, 1e-5);
  EXPECT_NEAR(pb.inertia, b.inertia, 1e-4);
  EXPECT_NEAR(pb.center.x, 5.0f, 1e-5f);
  // Capsule: rectangle 2r x L plus a disc of radius r.
  double r = 0.5, len = 2.0;
  rc::MassData cap = rc::computeMass(rc::makeCapsule({-1, 0}, {1, 0}, 0.5f), 1.0f);
  double rectI = 2 * r * len * (len * len + 4 * r * r) / 12;
  double d = 4 * r / (3 * kPi);
  double halfI = 0.25 * kPi * r * r * r * r - 0.5 * kPi * r * r * d * d +
                 0.5 * kPi * r * r * (len / 2 + d) * (len / 2 + d);
  EXPECT_NEAR(cap.area, 2 * r * len + kPi * r * r, 1e-5);
  EXPECT_NEAR(cap.inertia, rectI + 2 * halfI, 1e-5);
}

// Monte Carlo estimate of area, centroid and polar moment: independent of the exact
// decomposition in computeMass.
rc::MassData monteCarlo(const rc::Shape& s, uint64_t seed, int samples) {
  rc::AABB box = rc::computeAABB(s, rc::Transform{});
  rc::Random rng(seed);
  double n = 0, sx = 0, sy = 0, sxx = 0;
  for (int i = 0; i < samples; ++i) {
    Vec2 p = rng.inBox(box.lower, box.upper);
    if (!rc::containsPoint(s, rc::Transform{}, p)) continue;
    n += 1;
    sx += p.x;
    sy += p.y;
    sxx += static_cast<double>(p.x) * p.x + static_cast<double>(p.y) * p.y;
  }
  double boxArea = static_cast<double>(box.upper.x - box.lower.x) * (box.upper.y - box.lower.y);
  double area = boxArea * n / samples;
  double cx = sx / n, cy = sy / n;
  rc::MassData md;
  md.area = static_cast<float>(area);
  md.mass = md.area;
  md.center = {static_cast<float>(cx), static_cast<float>(cy)};
  md.inertia = static_cast<float>(area * (sxx / n - cx * cx - cy * cy));
  return md;
}

TEST(Shapes, RoundedPolygonMassMatchesMonteCarloAndCapsule) {
  rc::Polygon rounded =
      rc::makePolygon(std::vector<Vec2>{{0, 0}, {2, 0}, {2.5f, 1}, {0.5f, 1.5f}}, 0.3f);
  rc::MassData exact = rc::computeMass(rounded, 1.0f);
  rc::MassData mc = monteCarlo(rounded, 11, 2'000'000);
  // 2e6 samples: relative standard error about 1e-3.
  EXPECT_NEAR(exact.area, mc.area, 5e-3 * exact.area);
  EXPECT_NEAR(exact.center.x, mc.center.x, 5e-3f);
  EXPECT_NEAR(exact.center.y, mc.center.y, 5e-3f);
  EXPECT_NEAR(exact.inertia, mc.inertia, 1e-2 * exact.inertia);
  // Area of a rounded polygon: core + perimeter * r + pi r^2 (Steiner's formula).
  rc::Polygon core = rc::makePolygon(std::vector<Vec2>{{0, 0}, {2, 0}, {2.5f, 1}, {0.5f, 1.5f}});
  double perimeter = 0;
  for (int i = 0; i < core.count; ++i)
    perimeter += rc::distance(core.vertices[i], core.vertices[(i + 1) % core.count]);
  EXPECT_NEAR(exact.area, rc::computeMass(core, 1).area + perimeter * 0.3 + kPi * 0.09, 1e-5);
  // A thin box rounded by r approaches a capsule of radius r: the extra area is the core
  // (2 x 0.002) plus the rectangles on the two short edges (2 x 0.002 x 0.5), and the extra
  // inertia is the first-order growth of a 0.002 m slab through the middle (about 0.3%).
  rc::Polygon thin = rc::makeOrientedBox(1.0f, 0.001f, {}, 0.0f, 0.5f);
  rc::MassData cap = rc::computeMass(rc::makeCapsule({-1, 0}, {1, 0}, 0.5f), 1.0f);
  rc::MassData thinMass = rc::computeMass(thin, 1.0f);
  EXPECT_NEAR(thinMass.area, cap.area + 0.006, 1e-5);
  EXPECT_NEAR(thinMass.inertia, cap.inertia, 8e-3);
  EXPECT_GT(thinMass.inertia, cap.inertia);
}

TEST(Shapes, CompoundMassUsesParallelAxis) {
  // Two unit discs at x = -2 and x = 2: I = 2 (m r^2/2 + m d^2).
  rc::MassData a = rc::computeMass(rc::makeCircle({-2, 0}, 1), 1);
  rc::MassData b = rc::computeMass(rc::makeCircle({2, 0}, 1), 1);
  rc::MassData parts[] = {a, b};
  rc::MassData both = rc::combineMass(parts);
  EXPECT_NEAR(both.mass, 2 * kPi, 1e-5);
  EXPECT_NEAR(both.center.x, 0.0f, 1e-6f);
  EXPECT_NEAR(both.inertia, 2 * (kPi / 2 + kPi * 4), 1e-4);
  // A box split in two halves has the mass properties of the whole box.
  rc::MassData left = rc::computeMass(rc::makeBox(0.5f, 1, {-0.5f, 0}), 2);
  rc::MassData right = rc::computeMass(rc::makeBox(0.5f, 1, {0.5f, 0}), 2);
  rc::MassData halves[] = {left, right};
  rc::MassData whole = rc::computeMass(rc::makeBox(1, 1), 2);
  rc::MassData sum = rc::combineMass(halves);
  EXPECT_NEAR(sum.mass, whole.mass, 1e-6);
  EXPECT_NEAR(sum.inertia, whole.inertia, 1e-5);
}

TEST(Shapes, ContainsPointOnHandWorkedCases) {
  rc::Transform xf{{10, 0}, rc::Rot::fromAngle(rc::kPi / 2)};
  rc::Shape box = rc::makeBox(2, 0.5f);  // rotated 90 degrees: 1 wide, 4 tall in the world
  EXPECT_TRUE(rc::containsPoint(box, xf, {10, 1.9f}));
  EXPECT_FALSE(rc::containsPoint(box, xf, {11, 0}));
  rc::Shape cap = rc::makeCapsule({0, 0}, {2, 0}, 1);
  EXPECT_TRUE(rc::containsPoint(cap, {}, {2.7f, 0.7f}));
  EXPECT_FALSE(rc::containsPoint(cap, {}, {2.8f, 0.8f}));
  rc::Shape seg = rc::makeSegment({0, 0}, {1, 0});
  EXPECT_FALSE(rc::containsPoint(seg, {}, {0.5f, 0}));
}

}  // namespace
