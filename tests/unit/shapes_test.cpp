// Shape factories, validation, hulls, bounding boxes, containment and mass properties against
// closed forms and a Monte Carlo integral (an independent check for rounded polygons).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "physics/random.h"
#include "physics/shapes.h"
#include "support/random_shapes.h"
#include "support/reference_geometry.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace shapes_test {

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

// ---------------------------------------------------------------------------------------------
// Polygons from 1 mm to 100 m keep their shape.
//
// Each polygon is built from float points rounded from an exact polygon in long double
// (rc::testing::randomConvexPolygon: regular n-gons, n = 3..8, and irregular ones on ellipses, at
// random rotations, centred within 3 R of the origin, circumradius R from 1 mm to 100 m), and is
// held to that exact polygon. The tolerances are what rounding the vertices to float allows, to
// first order: each coordinate moves by at most u M (u = 2^-24, M the largest coordinate), so
// each vertex by delta = sqrt(2) u M and the outline by at most delta. That changes the area by
// at most delta P (P the perimeter), the first moment about the centroid by delta P rho (rho the
// farthest point of the outline from the centroid), so the centroid by delta P rho / A, and the
// polar moment by delta P rho^2. On top, the float results' own rounding: 2u relative, 2u M for
// the centre. Here that is 1e-6 to 1e-5 relative (M <= 4 R).

constexpr long double kU = 0x1p-24L;
constexpr long double kPiL = 3.141592653589793238462643383279503L;

// Circumradius 1 mm and 100 m first, then log-uniform between.
long double sizeOfCase(rc::Random& rng, int i) {
  if (i < 2) return i == 0 ? 1e-3L : 1e2L;
  return 1e-3L * std::pow(10.0L, 5.0L * rng.uniformDouble());
}

long double largestCoordinate(const rc::testing::ExactPolygon& p) {
  long double m = 0;
  for (int k = 0; k < p.count; ++k)
    m = std::max({m, std::fabs(p.x[k]), std::fabs(p.y[k])});
  return m;
}

std::string describe(const rc::testing::TestPolygon& t) {
  std::string out;
  char buf[64];
  for (int k = 0; k < t.exact.count; ++k) {
    std::snprintf(buf, sizeof buf, " (%.12Lg, %.12Lg)", t.exact.x[k], t.exact.y[k]);
    out += buf;
  }
  return out;
}

// The exact answer for one polygon, and what float vertices allow around it.
struct MassReference {
  long double area, cx, cy, inertia;
  long double perimeter, rho;  // of the outline, rho from the centroid
};

// Failures counted and the first described: a broken hull reports once, not once per polygon.
struct Failures {
  int count = 0;
  std::string first;
  double worstArea = 0, worstCentre = 0, worstInertia = 0;  // error over tolerance
  void fail(const std::string& what) {
    if (count++ == 0) first = what;
  }
};

// Builds the polygon, expects its vertices to be exactly the float vertices of the exact polygon
// in counter-clockwise order, and its mass within the rounding bounds of the reference.
void checkPolygon(const rc::testing::TestPolygon& t, float radius, const MassReference& ref,
                  Failures& f) {
  const rc::testing::ExactPolygon& e = t.exact;
  rc::Polygon p;
  try {
    p = rc::makePolygon(t.points, radius);
  } catch (const rc::InvalidShape& ex) {
    f.fail(std::string("refused: ") + ex.what() + describe(t));
    return;
  }
  if (p.count != e.count) {
    f.fail("hull has " + std::to_string(p.count) + " vertices, not " + std::to_string(e.count) +
           ":" + describe(t));
    return;
  }
  const Vec2 first{static_cast<float>(e.x[0]), static_cast<float>(e.y[0])};
  int start = 0;  // the stored vertex that is exact vertex 0
  while (start < p.count && !(p.vertices[start] == first))
    ++start;
  for (int k = 0; k < e.count; ++k) {
    Vec2 want{static_cast<float>(e.x[k]), static_cast<float>(e.y[k])};
    if (start == p.count || !(p.vertices[(start + k) % p.count] == want)) {
      f.fail("hull is not the float vertices in order:" + describe(t));
      return;
    }
  }
  try {
    rc::validate(p);
  } catch (const rc::InvalidShape& ex) {
    f.fail(std::string("invalid: ") + ex.what() + describe(t));
    return;
  }

  const long double delta = std::sqrt(2.0L) * kU * largestCoordinate(e);
  const long double tolArea = delta * ref.perimeter / ref.area + 2 * kU;
  const long double tolCentre =
      delta * ref.perimeter * ref.rho / ref.area + 2 * kU * largestCoordinate(e);
  const long double tolInertia = delta * ref.perimeter * ref.rho * ref.rho / ref.inertia + 2 * kU;
  rc::MassData md = rc::computeMass(p, 1.0f);
  const long double area = std::fabs(md.area - ref.area) / ref.area;
  const long double centre = std::hypot(md.center.x - ref.cx, md.center.y - ref.cy);
  const long double inertia = std::fabs(md.inertia - ref.inertia) / ref.inertia;
  f.worstArea = std::max(f.worstArea, static_cast<double>(area / tolArea));
  f.worstCentre = std::max(f.worstCentre, static_cast<double>(centre / tolCentre));
  f.worstInertia = std::max(f.worstInertia, static_cast<double>(inertia / tolInertia));
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "area off by %.3Lg relative (tolerance %.3Lg), centre by %.3Lg m (%.3Lg), inertia "
                "by %.3Lg relative (%.3Lg), radius %g:",
                area, tolArea, centre, tolCentre, inertia, tolInertia, static_cast<double>(radius));
  if (area > tolArea || centre > tolCentre || inertia > tolInertia) f.fail(buf + describe(t));
}

void expectNoFailures(const Failures& f, int cases) {
  EXPECT_EQ(f.count, 0) << f.count << " of " << cases << " polygons; the first: " << f.first;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", f.worstArea);
  ::testing::Test::RecordProperty("worst_area_over_tolerance", buf);
  std::snprintf(buf, sizeof buf, "%.3g", f.worstCentre);
  ::testing::Test::RecordProperty("worst_centre_over_tolerance", buf);
  std::snprintf(buf, sizeof buf, "%.3g", f.worstInertia);
  ::testing::Test::RecordProperty("worst_inertia_over_tolerance", buf);
}

// Regular n-gons against their closed forms: area n/2 R^2 sin(2 pi/n), polar moment about the
// centre A R^2 (2 + cos(2 pi/n)) / 6, centroid the centre. Rounded by r, the outline gains a
// rectangle r deep on each edge (length L = 2 R sin(pi/n), centroid a + r/2 from the centre with
// a = R cos(pi/n) the apothem) and a sector of angle 2 pi/n at each vertex (on the line from the
// centre through the vertex, its centroid 4 r sin(pi/n) / (3 (2 pi/n)) beyond it).
MassReference regularReference(const rc::testing::TestPolygon& t, long double R, long double r) {
  const int n = t.exact.count;
  const long double theta = 2 * kPiL / n, a = R * std::cos(kPiL / n),
                    L = 2 * R * std::sin(kPiL / n);
  MassReference ref;
  ref.area = n / 2.0L * R * R * std::sin(theta);
  ref.inertia = ref.area * R * R * (2 + std::cos(theta)) / 6;
  ref.cx = t.centerX;
  ref.cy = t.centerY;
  ref.perimeter = n * L;
  ref.rho = R;
  if (r > 0) {
    const long double rect = L * r, sector = theta * r * r / 2;
    const long double d = 4 * r * std::sin(theta / 2) / (3 * theta);
    ref.inertia += n * (rect * (L * L + r * r) / 12 + rect * (a + r / 2) * (a + r / 2));
    ref.inertia += n * (theta * r * r * r * r / 4 - sector * d * d + sector * (R + d) * (R + d));
    ref.area += n * (rect + sector);
    ref.perimeter += 2 * kPiL * r;
    ref.rho += r;
  }
  return ref;
}

TEST(PolygonShape, RegularPolygonsFrom1mmTo100mKeepTheirShapeAndMass) {
  rc::Random rng(20);
  Failures f;
  int cases = 0;
  for (int n = 3; n <= rc::kMaxPolygonVertices; ++n) {
    for (int i = 0; i < 200; ++i, ++cases) {
      const long double R = sizeOfCase(rng, i);
      rc::testing::TestPolygon t = rc::testing::randomConvexPolygon(rng, n, R, true, 5);
      checkPolygon(t, 0.0f, regularReference(t, R, 0), f);
    }
  }
  expectNoFailures(f, cases);
}

// The same rounded by 1% to 100% of R: exercises the sectors' angles (shapes.cpp computes them
// without libm) against the closed form.
TEST(PolygonShape, RoundedRegularPolygonsMatchTheClosedForm) {
  rc::Random rng(21);
  Failures f;
  int cases = 0;
  for (int n = 3; n <= rc::kMaxPolygonVertices; ++n) {
    for (int i = 0; i < 200; ++i, ++cases) {
      const long double R = sizeOfCase(rng, i);
      rc::testing::TestPolygon t = rc::testing::randomConvexPolygon(rng, n, R, true, 5);
      const float r = static_cast<float>(R * std::pow(10.0L, -2.0L * rng.uniformDouble()));
      checkPolygon(t, r, regularReference(t, R, r), f);
    }
  }
  expectNoFailures(f, cases);
}

// Irregular convex polygons against the shoelace sums of the exact vertices.
TEST(PolygonShape, IrregularPolygonsFrom1mmTo100mKeepTheirShapeAndMass) {
  rc::Random rng(22);
  Failures f;
  int cases = 0;
  for (int n = 3; n <= rc::kMaxPolygonVertices; ++n) {
    for (int i = 0; i < 200; ++i, ++cases) {
      const long double R = sizeOfCase(rng, i);
      rc::testing::TestPolygon t = rc::testing::randomConvexPolygon(rng, n, R, false, 5);
      rc::testing::ExactMass m = rc::testing::exactMass(t.exact);
      MassReference ref{m.area, m.cx, m.cy, m.inertia, rc::testing::perimeter(t.exact), 0};
      for (int k = 0; k < n; ++k)
        ref.rho = std::max(ref.rho, std::hypot(t.exact.x[k] - m.cx, t.exact.y[k] - m.cy));
      checkPolygon(t, 0.0f, ref, f);
    }
  }
  expectNoFailures(f, cases);
}

// The hull drops a vertex only when it is collinear within rounding: a unit square with a fifth
// vertex pushed out of its bottom edge by 1e-5 m (a turn of 4e-5 rad) keeps it; by 1e-8 m (4e-8
// rad, under the 4.8e-7 of 4 float epsilons) it is straight and dropped.
TEST(PolygonShape, HullDropsOnlyCornersStraightWithinRounding) {
  auto square = [](float bulge) {
    return rc::makePolygon(std::vector<Vec2>{{0, 0}, {0.5f, -bulge}, {1, 0}, {1, 1}, {0, 1}});
  };
  EXPECT_EQ(square(1e-5f).count, 5);
  EXPECT_EQ(square(1e-8f).count, 4);
  EXPECT_EQ(square(0.0f).count, 4);
  EXPECT_EQ(square(-1e-5f).count, 4);  // pushed in: not on the hull
}

// Near-duplicates are welded, at Box2D's half slop for polygons over 25 cm and at 1% of the size
// below: a 1 mm triangle keeps its corners, and its corners given twice, 1e-7 m apart, do not
// make sliver edges. Welding runs along the hull: a diamond 1 m long and 2 mm thick keeps its
// thickness although its two side corners are closer than the weld.
TEST(PolygonShape, WeldsNearDuplicatesRelativeToTheSize) {
  std::vector<Vec2> tiny = {{0, 0}, {1e-3f, 0}, {0, 1e-3f}};
  EXPECT_EQ(rc::makePolygon(tiny).count, 3);
  std::vector<Vec2> doubled = tiny;
  for (Vec2 v : tiny)
    doubled.push_back(v + Vec2{1e-7f, 5e-8f});
  rc::Polygon p = rc::makePolygon(doubled);
  EXPECT_EQ(p.count, 3);
  EXPECT_NO_THROW(rc::validate(p));
  EXPECT_NEAR(rc::computeMass(p, 1.0f).area, 0.5e-6, 0.5e-6 * 2e-3);
  // At 1 m, 2 mm apart is within Box2D's weld.
  EXPECT_EQ(rc::makePolygon(std::vector<Vec2>{{0, 0}, {1, 0}, {1, 0.002f}, {0, 1}}).count, 3);
  rc::Polygon diamond =
      rc::makePolygon(std::vector<Vec2>{{0, 0}, {0.5f, -0.001f}, {1, 0}, {0.5f, 0.001f}});
  EXPECT_EQ(diamond.count, 4);
  EXPECT_NEAR(rc::computeMass(diamond, 1.0f).area, 0.001, 1e-9);
}

// A point set whose hull has more vertices than a polygon may have is refused, with the count,
// however many points it has: 200,000 points on a circle of 1 m (their hull, welded at 2.5 mm,
// has about 2,400 vertices; it must not be simplified into a sliver). The hull sorts once and
// walks the points a few times, so this takes milliseconds (before, the weld compared every pair).
TEST(PolygonShape, ManyPointsOnACircleAreRefusedWithTheHullsVertexCount) {
  std::vector<Vec2> circle;
  constexpr int kPoints = 200000;
  for (int i = 0; i < kPoints; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / kPoints;
    circle.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))});
  }
  try {
    rc::Polygon p = rc::makePolygon(circle);
    FAIL() << "accepted as a polygon of " << p.count << " vertices, area "
           << rc::computeMass(p, 1.0f).area;
  } catch (const rc::InvalidShape& e) {
    const std::string what = e.what();
    const std::string head = "polygon: the hull has ";
    ASSERT_EQ(what.rfind(head, 0), 0u) << what;
    const int count = std::stoi(what.substr(head.size()));
    EXPECT_GT(count, 1000) << what;  // 2 pi m / 2.5 mm is 2,513
    EXPECT_NE(what.find(std::to_string(count) + " vertices; at most 8"), std::string::npos) << what;
  }
  // And 200,000 points filling a square give the square.
  rc::Random rng(23);
  std::vector<Vec2> cloud;
  for (int i = 0; i < kPoints; ++i)
    cloud.push_back(rng.inBox({-50, -50}, {50, 50}));
  std::vector<Vec2> corners = {{-50, -50}, {50, -50}, {50, 50}, {-50, 50}};
  cloud.insert(cloud.begin() + 777, corners.begin(), corners.end());
  rc::Polygon square = rc::makePolygon(cloud);
  ASSERT_EQ(square.count, 4);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(square.vertices[k], corners[static_cast<size_t>(k)]);
}

}  // namespace shapes_test
