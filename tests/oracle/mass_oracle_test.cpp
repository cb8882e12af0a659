// Mass properties against Box2D 2.4.1 (b2CircleShape / b2PolygonShape::ComputeMass).
//
// Box2D 2.4.1 reports inertia about the body origin; ours is about the centre of mass, so the
// oracle's value is shifted back with the parallel-axis theorem (I_c = I_o - m |c|^2). Box2D's
// polygon skin (b2_polygonRadius) does not enter its mass computation, so sharp polygons compare
// directly. Box2D welds points closer than 0.5 * b2_linearSlop and needs at least 3 hull points,
// as we do. Tolerance: 1e-5 relative (the issue's), on 100,000 random shapes per kind.
#include <box2d/box2d.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <vector>

#include "physics/random.h"
#include "physics/shapes.h"

namespace {

using rc::Vec2;

void expectRel(double ours, double theirs, double rel, const char* what, int i) {
  double scale = std::max(std::fabs(theirs), 1e-6);
  EXPECT_LE(std::fabs(ours - theirs) / scale, rel)
      << what << " case " << i << " ours " << ours << " box2d " << theirs;
}

TEST(MassOracle, Circles) {
  rc::Random rng(100);
  for (int i = 0; i < 100000; ++i) {
    Vec2 c = rng.inBox({-10, -10}, {10, 10});
    float r = rng.uniform(0.01f, 5.0f), density = rng.uniform(0.1f, 10.0f);
    b2CircleShape b;
    b.m_p.Set(c.x, c.y);
    b.m_radius = r;
    b2MassData md;
    b.ComputeMass(&md, density);
    rc::MassData ours = rc::computeMass(rc::makeCircle(c, r), density);
    expectRel(ours.mass, md.mass, 1e-5, "mass", i);
    double shifted = md.I - md.mass * (static_cast<double>(md.center.x) * md.center.x +
                                       static_cast<double>(md.center.y) * md.center.y);
    // The shift cancels digits of Box2D's float result when the centre is far from the origin;
    // compare against the closed form there too so the tolerance stays 1e-5 of the true value.
    double exact = 0.5 * ours.mass * static_cast<double>(r) * r;
    expectRel(ours.inertia, exact, 1e-5, "inertia vs closed form", i);
    EXPECT_LE(std::fabs(ours.inertia - shifted), 1e-5 * std::fabs(md.I) + 1e-6)
        << "inertia vs box2d case " << i;
  }
}

TEST(MassOracle, Polygons) {
  rc::Random rng(101);
  int compared = 0;
  for (int i = 0; i < 100000; ++i) {
    int n = 3 + static_cast<int>(rng.below(6));
    Vec2 offset = rng.inBox({-5, -5}, {5, 5});
    float size = rng.uniform(0.1f, 4.0f);
    std::vector<Vec2> pts;
    std::vector<b2Vec2> bpts;
    for (int k = 0; k < n; ++k) {
      Vec2 p = offset + size * rng.inBox({-1, -1}, {1, 1});
      pts.push_back(p);
      bpts.push_back({p.x, p.y});
    }
    rc::Polygon poly;
    try {
      poly = rc::makePolygon(pts);
    } catch (const rc::InvalidShape&) {
      continue;  // degenerate cloud: Box2D would assert
    }
    // Feed Box2D our hull so both integrate the same polygon (hull algorithms may differ on
    // nearly collinear points, which is not what this test is about), relative to its centroid:
    // Box2D integrates in float about the vertex average, which costs it up to 5e-5 relative on
    // small polygons far from the origin. In its own best frame its error is ~1e-7.
    Vec2 c = poly.centroid;
    b2Vec2 hull[b2_maxPolygonVertices];
    for (int k = 0; k < poly.count; ++k)
      hull[k] = {poly.vertices[k].x - c.x, poly.vertices[k].y - c.y};
    b2PolygonShape b;
    b.Set(hull, poly.count);
    if (b.m_count != poly.count) continue;
    float density = rng.uniform(0.1f, 10.0f);
    b2MassData md;
    b.ComputeMass(&md, density);
    rc::MassData ours = rc::computeMass(poly, density);
    // Independent reference: the shoelace formula in long double on the same float vertices.
    long double a2 = 0, fanSum = 0;
    for (int k = 0; k < poly.count; ++k) {
      Vec2 p = poly.vertices[k], q = poly.vertices[(k + 1) % poly.count];
      a2 += static_cast<long double>(p.x) * q.y - static_cast<long double>(q.x) * p.y;
      fanSum += rc::length(p - c) * rc::length(q - c);
    }
    double exactMass = static_cast<double>(a2 / 2 * density);
    expectRel(ours.mass, exactMass, 1e-6, "mass vs shoelace", i);
    // Box2D sums float cross products; on slivers they cancel. Its rounding bound is a few float
    // epsilons times the condition number sum |e1||e2| / (2 A) of the triangle fan.
    double cond = static_cast<double>(fanSum / a2);
    double tol = 1e-5 + 8 * FLT_EPSILON * cond;
    expectRel(ours.mass, md.mass, tol, "mass", i);
    EXPECT_NEAR(ours.center.x, md.center.x + c.x, 1e-5 * (1 + std::fabs(c.x))) << i;
    EXPECT_NEAR(ours.center.y, md.center.y + c.y, 1e-5 * (1 + std::fabs(c.y))) << i;
    double shifted = md.I - md.mass * (static_cast<double>(md.center.x) * md.center.x +
                                       static_cast<double>(md.center.y) * md.center.y);
    expectRel(ours.inertia, shifted, tol, "inertia", i);
    ++compared;
  }
  EXPECT_GT(compared, 95000);
}

}  // namespace
