// Convex decomposition: the pieces' areas sum to the polygon's (shoelace), each piece is
// convex, counter-clockwise, with at most 8 vertices, the engine accepts it, and together they
// cover the polygon and nothing else (sample points).
#include "game/level/convex_decomposition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics/random.h"
#include "physics/shapes.h"
#include "physics/trig.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace convex_decomposition_test {

using Poly = std::vector<rc::Vec2>;

double cross(rc::Vec2 o, rc::Vec2 a, rc::Vec2 b) {
  return (static_cast<double>(a.x) - o.x) * (static_cast<double>(b.y) - o.y) -
         (static_cast<double>(a.y) - o.y) * (static_cast<double>(b.x) - o.x);
}

// Even-odd crossing test, strict inside (points near the boundary are skipped by the caller).
bool insidePolygon(const Poly& p, rc::Vec2 q) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i].y > q.y) != (p[j].y > q.y) &&
        q.x < (p[j].x - p[i].x) * (q.y - p[i].y) / (p[j].y - p[i].y) + p[i].x)
      in = !in;
  }
  return in;
}

bool insideConvex(const Poly& p, rc::Vec2 q) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (cross(p[i], p[(i + 1) % p.size()], q) < 0) return false;
  return true;
}

double distanceToBoundary(const Poly& p, rc::Vec2 q) {
  double best = 1e30;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const rc::Vec2 a = p[i], b = p[(i + 1) % p.size()];
    const double ex = b.x - a.x, ey = b.y - a.y;
    double t = ((q.x - a.x) * ex + (q.y - a.y) * ey) / (ex * ex + ey * ey);
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, std::hypot(q.x - (a.x + t * ex), q.y - (a.y + t * ey)));
  }
  return best;
}

// Checks the pieces of `polygon`; returns how many.
std::size_t checkDecomposition(const Poly& polygon, int samples = 2000) {
  const auto pieces = game::decomposeConvex(polygon, rc::kMaxPolygonVertices);
  double area = 0;
  for (const Poly& piece : pieces) {
    EXPECT_GE(piece.size(), 3u);
    EXPECT_LE(piece.size(), static_cast<std::size_t>(rc::kMaxPolygonVertices));
    for (std::size_t i = 0; i < piece.size(); ++i)
      EXPECT_GT(cross(piece[i], piece[(i + 1) % piece.size()], piece[(i + 2) % piece.size()]), 0)
          << "piece not strictly convex and counter-clockwise at vertex " << (i + 1) % piece.size();
    EXPECT_NO_THROW(rc::makePolygon(piece));
    area += game::signedArea(piece);
  }
  const double whole = std::fabs(game::signedArea(polygon));
  EXPECT_NEAR(area, whole, 1e-5 * whole);
  // Sample the bounding box: inside the polygon iff inside one piece (points within a hair of
  // an edge are skipped: float rounding decides them either way).
  float lx = 1e30f, ly = 1e30f, hx = -1e30f, hy = -1e30f;
  for (const rc::Vec2 v : polygon) {
    lx = std::min(lx, v.x), ly = std::min(ly, v.y), hx = std::max(hx, v.x), hy = std::max(hy, v.y);
  }
  rc::Random random(7);
  const double hair = 1e-4 * std::max(hx - lx, hy - ly);
  for (int s = 0; s < samples; ++s) {
    const rc::Vec2 q = random.inBox({lx, ly}, {hx, hy});
    bool nearEdge = distanceToBoundary(polygon, q) < hair;
    int holders = 0;
    for (const Poly& piece : pieces) {
      nearEdge = nearEdge || distanceToBoundary(piece, q) < hair;
      holders += insideConvex(piece, q) ? 1 : 0;
    }
    if (nearEdge) continue;
    EXPECT_EQ(holders, insidePolygon(polygon, q) ? 1 : 0) << "at (" << q.x << ", " << q.y << ")";
  }
  return pieces.size();
}

TEST(ConvexDecomposition, ConvexPolygonStaysWhole) {
  EXPECT_EQ(checkDecomposition({{0, 0}, {4, 0}, {4, 3}, {0, 3}}), 1u);
  // Clockwise input comes out counter-clockwise.
  EXPECT_EQ(checkDecomposition({{0, 0}, {0, 3}, {4, 3}, {4, 0}}), 1u);
}

TEST(ConvexDecomposition, LAndUShapes) {
  EXPECT_EQ(checkDecomposition({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}), 2u);
  EXPECT_EQ(checkDecomposition({{0, 0}, {1, 0}, {1, 3}, {3, 3}, {3, 0}, {4, 0}, {4, 4}, {0, 4}}),
            3u);
}

TEST(ConvexDecomposition, CollinearAndDuplicatePointsAreDropped) {
  const auto pieces = game::decomposeConvex(
      Poly{{0, 0}, {1, 0}, {2, 0}, {2, 0}, {2, 2}, {1, 2}, {0, 2}, {0, 1}, {0, 0}}, 8);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].size(), 4u);
}

TEST(ConvexDecomposition, ConvexPolygonOfManyVerticesIsSplitIntoEights) {
  Poly circle;
  for (int i = 0; i < 40; ++i) {
    const rc::SinCos sc = rc::sincos(2.0f * rc::kPi * static_cast<float>(i) / 40.0f);
    circle.push_back({5.0f * sc.cosine, 5.0f * sc.sine});
  }
  const std::size_t n = checkDecomposition(circle);
  EXPECT_GE(n, 6u);  // 40 vertices, at most 8 per piece
  EXPECT_LE(n, 12u);
}

// Star-shaped polygons around the origin (random radii at sorted angles) are simple; at up to
// 60 vertices they have many reflex corners.
TEST(ConvexDecomposition, RandomStarsAndCombs) {
  rc::Random random(2024);
  for (int round = 0; round < 200; ++round) {
    const int n = 4 + static_cast<int>(random.below(57));
    Poly star;
    for (int i = 0; i < n; ++i) {
      const rc::SinCos sc =
          rc::sincos(2.0f * rc::kPi * (static_cast<float>(i) + random.uniform(0.1f, 0.9f)) /
                     static_cast<float>(n));
      const float r = random.uniform(1.0f, 10.0f);
      star.push_back({r * sc.cosine, r * sc.sine});
    }
    SCOPED_TRACE("star " + std::to_string(round));
    checkDecomposition(star, 300);
    if (HasFailure()) return;
  }
  // A comb: teeth on a bar, every gap a pair of reflex corners.
  Poly comb = {{0, 0}, {20, 0}, {20, 4}};
  for (int t = 9; t >= 0; --t) {
    const float x = 2.0f * static_cast<float>(t);
    comb.push_back({x + 1.5f, 4});
    comb.push_back({x + 1.5f, 1});
    comb.push_back({x + 0.5f, 1});
    comb.push_back({x + 0.5f, 4});
  }
  comb.push_back({0, 4});
  checkDecomposition(comb);
}

TEST(ConvexDecomposition, NonSimplePolygonsAreRefusedWithAReason) {
  auto reason = [](const Poly& p) -> std::string {
    try {
      game::decomposeConvex(p, 8);
    } catch (const game::DecompositionError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(reason({{0, 0}, {2, 2}, {2, 0}, {0, 2}}),
            "crosses or touches itself: edges 0 and 2 meet");
  // Touching itself at a vertex: two squares joined at a corner, drawn as one outline.
  EXPECT_EQ(reason({{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}, {1, 2}, {1, 1}, {0, 1}})
                .rfind("crosses or touches itself", 0),
            0u);
  EXPECT_EQ(reason({{0, 0}, {2, 0}, {1, 0}}), "has no area: its points lie on one line");
  EXPECT_EQ(reason({{0, 0}, {2, 0}, {0, 0}}), "has fewer than 3 distinct corners");
  EXPECT_EQ(reason({{0, 0}, {2, 0}, {2, 2}, {2, -1}}), "doubles back on itself at vertex 2");
  EXPECT_EQ(reason({{0, 0}, {1, 0}, {std::nanf(""), 1}}), "has a vertex that is not finite");
}

}  // namespace convex_decomposition_test
