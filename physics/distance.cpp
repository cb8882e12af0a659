#include "physics/distance.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace rc {
namespace {

int support(const ShapeProxy& p, Vec2 d) {
  int best = 0;
  float bestValue = dot(p.points[0], d);
  // Kept a loop: GCC -O3 otherwise peels it completely (count <= 8) into a chain of
  // data-dependent branches that mispredict, 1.5x slower on polygon pairs.
#pragma GCC unroll 1
  for (int i = 1; i < p.count; ++i) {
    float v = dot(p.points[i], d);
    if (v > bestValue) {
      best = i;
      bestValue = v;
    }
  }
  return best;
}

// A vertex of the simplex on the Minkowski difference B - A, all in A's frame.
struct SimplexVertex {
  Vec2 wA, wB, w;  // support point of A, of B, and w = wB - wA
  float a;         // barycentric weight of the closest point
  int indexA, indexB;
};

struct Simplex {
  SimplexVertex v[3];
  int count;

  // Closest point of the simplex to the origin, by the Voronoi regions of its features with
  // barycentric coordinates (Ericson, Real-Time Collision Detection, 5.1; Catto, GDC 2010).
  void solve2() {
    Vec2 w1 = v[0].w, w2 = v[1].w;
    Vec2 e12 = w2 - w1;
    float d12_2 = -dot(w1, e12);
    if (d12_2 <= 0.0f) {  // origin beyond w1
      v[0].a = 1.0f;
      count = 1;
      return;
    }
    float d12_1 = dot(w2, e12);
    if (d12_1 <= 0.0f) {  // origin beyond w2
      v[1].a = 1.0f;
      v[0] = v[1];
      count = 1;
      return;
    }
    float inv = 1.0f / (d12_1 + d12_2);
    v[0].a = d12_1 * inv;
    v[1].a = d12_2 * inv;
    count = 2;
  }

  void solve3() {
    Vec2 w1 = v[0].w, w2 = v[1].w, w3 = v[2].w;
    Vec2 e12 = w2 - w1, e13 = w3 - w1, e23 = w3 - w2;
    float d12_1 = dot(w2, e12), d12_2 = -dot(w1, e12);
    float d13_1 = dot(w3, e13), d13_2 = -dot(w1, e13);
    float d23_1 = dot(w3, e23), d23_2 = -dot(w2, e23);
    float n123 = cross(e12, e13);
    float d123_1 = n123 * cross(w2, w3);
    float d123_2 = n123 * cross(w3, w1);
    float d123_3 = n123 * cross(w1, w2);

    if (d12_2 <= 0.0f && d13_2 <= 0.0f) {  // vertex 1
      v[0].a = 1.0f;
      count = 1;
      return;
    }
    if (d12_1 > 0.0f && d12_2 > 0.0f && d123_3 <= 0.0f) {  // edge 12
      float inv = 1.0f / (d12_1 + d12_2);
      v[0].a = d12_1 * inv;
      v[1].a = d12_2 * inv;
      count = 2;
      return;
    }
    if (d13_1 > 0.0f && d13_2 > 0.0f && d123_2 <= 0.0f) {  // edge 13
      float inv = 1.0f / (d13_1 + d13_2);
      v[0].a = d13_1 * inv;
      v[2].a = d13_2 * inv;
      v[1] = v[2];
      count = 2;
      return;
    }
    if (d12_1 <= 0.0f && d23_2 <= 0.0f) {  // vertex 2
      v[1].a = 1.0f;
      v[0] = v[1];
      count = 1;
      return;
    }
    if (d13_1 <= 0.0f && d23_1 <= 0.0f) {  // vertex 3
      v[2].a = 1.0f;
      v[0] = v[2];
      count = 1;
      return;
    }
    if (d23_1 > 0.0f && d23_2 > 0.0f && d123_1 <= 0.0f) {  // edge 23
      float inv = 1.0f / (d23_1 + d23_2);
      v[1].a = d23_1 * inv;
      v[2].a = d23_2 * inv;
      v[0] = v[2];
      count = 2;
      return;
    }
    // Inside the triangle: the cores overlap.
    float inv = 1.0f / (d123_1 + d123_2 + d123_3);
    v[0].a = d123_1 * inv;
    v[1].a = d123_2 * inv;
    v[2].a = d123_3 * inv;
    count = 3;
  }

  // Direction from the simplex towards the origin. For an edge, its perpendicular on the
  // origin's side: more robust than the negated closest point when the origin is near the edge.
  Vec2 searchDirection() const {
    if (count == 1) return -v[0].w;
    Vec2 e12 = v[1].w - v[0].w;
    float sgn = cross(e12, -v[0].w);
    return sgn > 0.0f ? leftPerp(e12) : rightPerp(e12);
  }

  void witnessPoints(Vec2* a, Vec2* b) const {
    if (count == 1) {
      *a = v[0].wA;
      *b = v[0].wB;
    } else if (count == 2) {
      *a = v[0].a * v[0].wA + v[1].a * v[1].wA;
      *b = v[0].a * v[0].wB + v[1].a * v[1].wB;
    } else {
      *a = v[0].a * v[0].wA + v[1].a * v[1].wA + v[2].a * v[2].wA;
      *b = *a;
    }
  }
};

}  // namespace

ShapeProxy makeProxy(const Vec2* points, int count, float radius) {
  ShapeProxy p;
  p.count = count;
  p.radius = radius;
  for (int i = 0; i < count; ++i)
    p.points[i] = points[i];
  return p;
}

ShapeProxy makeProxy(const Shape& s) {
  switch (s.type) {
    case ShapeType::circle:
      return makeProxy(&s.circle.center, 1, s.circle.radius);
    case ShapeType::box: {
      Vec2 c = s.box.center, h = s.box.halfExtents;
      Vec2 v[4] = {{c.x - h.x, c.y - h.y},
                   {c.x + h.x, c.y - h.y},
                   {c.x + h.x, c.y + h.y},
                   {c.x - h.x, c.y + h.y}};
      return makeProxy(v, 4, 0.0f);
    }
    case ShapeType::polygon:
      return makeProxy(s.polygon.vertices, s.polygon.count, s.polygon.radius);
    case ShapeType::capsule:
      return makeProxy(&s.capsule.center1, 2, s.capsule.radius);
    case ShapeType::segment:
      return makeProxy(&s.segment.point1, 2, 0.0f);
    case ShapeType::chainSegment:
      return makeProxy(&s.chainSegment.segment.point1, 2, 0.0f);
  }
  return {};
}

DistanceOutput shapeDistance(const ShapeProxy& a, const Transform& xfA, const ShapeProxy& b,
                             const Transform& xfB, SimplexCache* cache) {
  const Transform rel = invMul(xfA, xfB);  // B in A's frame
  Simplex s;
  s.count = 0;
  auto makeVertex = [&](int ia, int ib) {
    SimplexVertex v;
    v.indexA = ia;
    v.indexB = ib;
    v.wA = a.points[ia];
    v.wB = apply(rel, b.points[ib]);
    v.w = v.wB - v.wA;
    v.a = 1.0f;
    return v;
  };
  if (cache != nullptr && cache->count > 0 && cache->count <= 3) {
    s.count = cache->count;
    for (int i = 0; i < s.count; ++i) {
      int ia = cache->indexA[i], ib = cache->indexB[i];
      if (ia >= a.count || ib >= b.count) {  // stale cache: start over
        s.count = 0;
        break;
      }
      s.v[i] = makeVertex(ia, ib);
    }
  }
  if (s.count == 0) {
    s.v[0] = makeVertex(0, 0);
    s.count = 1;
  }

  constexpr int kMaxIterations = 24;
  int iter = 0;
  bool solved = false;
  while (iter < kMaxIterations) {
    int savedA[3], savedB[3];
    int savedCount = s.count;
    for (int i = 0; i < savedCount; ++i) {
      savedA[i] = s.v[i].indexA;
      savedB[i] = s.v[i].indexB;
    }
    if (s.count == 2) s.solve2();
    if (s.count == 3) s.solve3();
    solved = true;
    if (s.count == 3) break;  // origin inside: the cores overlap

    Vec2 d = s.searchDirection();
    if (lengthSquared(d) < 1e-30f) break;  // origin on the simplex: touching cores

    int ia = support(a, -d);
    int ib = support(b, invRotate(rel.q, d));
    ++iter;
    bool duplicate = false;
    for (int i = 0; i < savedCount; ++i) {
      if (savedA[i] == ia && savedB[i] == ib) {
        duplicate = true;
        break;
      }
    }
    if (duplicate) break;  // no progress: converged
    s.v[s.count++] = makeVertex(ia, ib);
    solved = false;
  }
  if (!solved) {  // out of iterations with a vertex just added: weigh it in
    if (s.count == 2) s.solve2();
    if (s.count == 3) s.solve3();
  }

  DistanceOutput out;
  out.iterations = iter;
  out.simplexCount = s.count;
  if (cache != nullptr) {
    cache->count = static_cast<std::uint8_t>(s.count);
    for (int i = 0; i < s.count; ++i) {
      cache->indexA[i] = static_cast<std::uint8_t>(s.v[i].indexA);
      cache->indexB[i] = static_cast<std::uint8_t>(s.v[i].indexB);
    }
  }
  Vec2 pA, pB;
  s.witnessPoints(&pA, &pB);
  // Normal and core distance. On an edge of the Minkowski difference the normal is the edge's
  // perpendicular: the weighted sum pB - pA cancels to a vector of the distance's size, so when
  // the cores are close (a face resting on a face) its direction is off by ulp(coordinates) /
  // distance, while the perpendicular of the edge is good to an ulp at any distance.
  float coreDistance;
  Vec2 n{};
  if (s.count == 2) {
    Vec2 perp = leftPerp(s.v[1].w - s.v[0].w);
    float side = dot(perp, s.v[0].w);
    if (side < 0.0f) perp = -perp;
    n = normalize(perp);
    coreDistance = side == 0.0f ? 0.0f : dot(n, s.v[0].w);
    if (coreDistance <= 0.0f) {
      coreDistance = 0.0f;
      n = Vec2{};
    }
  } else {
    Vec2 delta = pB - pA;
    coreDistance = length(delta);
    if (coreDistance > 0.0f) n = (1.0f / coreDistance) * delta;
  }
  float radii = a.radius + b.radius;
  if (coreDistance > radii) {
    pA = mulAdd(pA, a.radius, n);
    pB = mulSub(pB, b.radius, n);
    out.distance = coreDistance - radii;
  } else {
    // Overlap: the middle of the stretch of the core line inside both shapes, so the point
    // lies in both even when one radius dwarfs the other.
    float lo = std::max(-a.radius, coreDistance - b.radius);
    float hi = std::min(a.radius, coreDistance + b.radius);
    Vec2 p = mulAdd(pA, 0.5f * (lo + hi), n);
    pA = pB = p;
    out.distance = 0.0f;
  }
  out.pointA = apply(xfA, pA);
  out.pointB = apply(xfA, pB);
  out.normal = rotate(xfA.q, n);
  return out;
}

DistanceOutput shapeDistance(const Shape& a, const Transform& xfA, const Shape& b,
                             const Transform& xfB) {
  return shapeDistance(makeProxy(a), xfA, makeProxy(b), xfB, nullptr);
}

SegmentDistanceResult segmentDistance(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2) {
  // Ericson 5.1.9 in double: the float inputs' differences and products are exact there, so
  // nearly parallel segments keep their digits.
  double d1x = static_cast<double>(q1.x) - p1.x, d1y = static_cast<double>(q1.y) - p1.y;
  double d2x = static_cast<double>(q2.x) - p2.x, d2y = static_cast<double>(q2.y) - p2.y;
  double rx = static_cast<double>(p1.x) - p2.x, ry = static_cast<double>(p1.y) - p2.y;
  double a = d1x * d1x + d1y * d1y, e = d2x * d2x + d2y * d2y;
  double f = d2x * rx + d2y * ry;
  double s = 0.0, t = 0.0;
  constexpr double kEps = 1e-30;
  if (a <= kEps && e <= kEps) {
    s = t = 0.0;
  } else if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    double c = d1x * rx + d1y * ry;
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      double b = d1x * d2x + d1y * d2y;
      double denom = a * e - b * b;  // >= 0; zero when parallel
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  double c1x = p1.x + s * d1x, c1y = p1.y + s * d1y;
  double c2x = p2.x + t * d2x, c2y = p2.y + t * d2y;
  SegmentDistanceResult r;
  r.closest1 = {static_cast<float>(c1x), static_cast<float>(c1y)};
  r.closest2 = {static_cast<float>(c2x), static_cast<float>(c2y)};
  r.fraction1 = static_cast<float>(s);
  r.fraction2 = static_cast<float>(t);
  double dx = c2x - c1x, dy = c2y - c1y;
  r.distanceSquared = static_cast<float>(dx * dx + dy * dy);
  return r;
}

SegmentIntersection intersectSegments(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2) {
  // In double, so the orientation tests keep their digits
  // even for segments 1e-8 rad from parallel.
  double rx = static_cast<double>(q1.x) - p1.x, ry = static_cast<double>(q1.y) - p1.y;
  double sx = static_cast<double>(q2.x) - p2.x, sy = static_cast<double>(q2.y) - p2.y;
  double qx = static_cast<double>(p2.x) - p1.x, qy = static_cast<double>(p2.y) - p1.y;
  double denom = rx * sy - ry * sx;
  double qr = qx * ry - qy * rx;
  SegmentIntersection out;
  if (denom == 0.0) {
    if (qr != 0.0) return out;  // parallel, apart
    double rr = rx * rx + ry * ry;
    if (rr == 0.0) {
      // The first segment is a point: on the second segment (or equal to it when both are)?
      double ss = sx * sx + sy * sy;
      double px = -qx, py = -qy;  // p1 - p2
      bool on = ss == 0.0 ? (px == 0.0 && py == 0.0)
                          : (px * sy - py * sx == 0.0 && px * sx + py * sy >= 0.0 &&
                             px * sx + py * sy <= ss);
      if (!on) return out;
      out.hit = true;
      out.fraction = 0.0f;
      out.point = p1;
      return out;
    }
    double t0 = (qx * rx + qy * ry) / rr;
    double t1 = t0 + (sx * rx + sy * ry) / rr;
    double lo = std::max(0.0, std::min(t0, t1)), hi = std::min(1.0, std::max(t0, t1));
    if (lo > hi) return out;
    out.hit = true;
    out.fraction = static_cast<float>(lo);
  } else {
    double t = (qx * sy - qy * sx) / denom;
    double u = qr / denom;
    // Differences of floats of different magnitudes carry up to ~30 bits, so the products are
    // not always exact in double and a shared endpoint can come out at 1 + 2e-16: accept a
    // 1e-12 band and clamp.
    constexpr double kBand = 1e-12;
    if (t < -kBand || t > 1.0 + kBand || u < -kBand || u > 1.0 + kBand) return out;
    out.hit = true;
    out.fraction = static_cast<float>(std::clamp(t, 0.0, 1.0));
  }
  double f = out.fraction;
  out.point = {static_cast<float>(p1.x + f * rx), static_cast<float>(p1.y + f * ry)};
  return out;
}

namespace {

// Knuth's TwoSum: s = fl(a + b) and s + e == a + b exactly. Needs round-to-nearest double
// arithmetic without reassociation or extended precision (SSE2; the build has no -ffast-math).
void twoSum(double a, double b, double& s, double& e) {
  s = a + b;
  double bv = s - a, av = s - bv;
  e = (a - av) + (b - bv);
}

// Sign of (q - p) x (r - p), exact for all finite float inputs: +1 when r is left of p -> q,
// -1 right, 0 on the line (always 0 when p == q).
int orientation(Vec2 p, Vec2 q, Vec2 r) {
  // Expanded, the determinant is six products of two floats, each exact in double (24 + 24 bits),
  // so only their sum can round. The rounded sum errs by at most 5 u sum|t| (u = 2^-53); beyond
  // 8 u sum|t| its sign is the true one, which settles all but near-collinear triples.
  const double t[6] = {static_cast<double>(q.x) * r.y,  -static_cast<double>(q.x) * p.y,
                       -static_cast<double>(p.x) * r.y, -static_cast<double>(q.y) * r.x,
                       static_cast<double>(q.y) * p.x,  static_cast<double>(p.y) * r.x};
  double sum = 0.0, magnitude = 0.0;
  for (double v : t) {
    sum += v;
    magnitude += std::fabs(v);
  }
  if (std::fabs(sum) > 4.0 * DBL_EPSILON * magnitude) return sum > 0.0 ? 1 : -1;
  // Otherwise sum exactly: grow a nonoverlapping expansion with TwoSum (Shewchuk, "Adaptive
  // precision floating-point arithmetic and fast robust geometric predicates", 1997). Its
  // components increase in magnitude, zeros aside, and the largest nonzero one outweighs all the
  // others together, so it carries the sign of the sum.
  double e[6];
  int n = 0;
  for (double v : t) {
    double grown = v;
    for (int k = 0; k < n; ++k)
      twoSum(grown, e[k], grown, e[k]);
    e[n++] = grown;
  }
  for (int k = n - 1; k >= 0; --k) {
    if (e[k] != 0.0) return e[k] > 0.0 ? 1 : -1;
  }
  return 0;
}

// Whether x, known to be collinear with p and q, lies on the closed segment [p, q]. For p == q
// (no line) it asks whether x == p, which is also the right question.
bool withinSpan(Vec2 p, Vec2 q, Vec2 x) {
  return std::min(p.x, q.x) <= x.x && x.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= x.y &&
         x.y <= std::max(p.y, q.y);
}

}  // namespace

bool trianglesOverlap(const Vec2 a[3], const Vec2 b[3]) {
  // Every decision is an exact orientation sign or a comparison of coordinates, so touching is
  // decided exactly, with no tolerance. The triangles (or segments or points: a zero-area triangle
  // is the union of its three edges) share a point iff an edge of one meets an edge of the other,
  // or, failing that, one lies wholly inside the other, which only a triangle with area can
  // contain.
  for (int k = 0; k < 3; ++k) {
    if (!isFinite(a[k]) || !isFinite(b[k])) return false;
  }
  int sideA[3][3], sideB[3][3];  // sideA[i][j]: b[j] against edge a[i] -> a[i+1]; sideB alike
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      sideA[i][j] = orientation(a[i], a[(i + 1) % 3], b[j]);
      sideB[j][i] = orientation(b[j], b[(j + 1) % 3], a[i]);
    }
  }
  for (int i = 0; i < 3; ++i) {
    int i1 = (i + 1) % 3;
    for (int j = 0; j < 3; ++j) {
      int j1 = (j + 1) % 3;
      // Closed segments [a_i, a_i1] and [b_j, b_j1] (either may be a point) meet iff they cross
      // properly or an endpoint of one lies on the other.
      int o1 = sideA[i][j], o2 = sideA[i][j1], o3 = sideB[j][i], o4 = sideB[j][i1];
      if (o1 * o2 < 0 && o3 * o4 < 0) return true;
      if ((o1 == 0 && withinSpan(a[i], a[i1], b[j])) ||
          (o2 == 0 && withinSpan(a[i], a[i1], b[j1])) ||
          (o3 == 0 && withinSpan(b[j], b[j1], a[i])) || (o4 == 0 && withinSpan(b[j], b[j1], a[i1])))
        return true;
    }
  }
  // No boundaries meet: they overlap only if one lies strictly inside the other, and then so
  // does its vertex 0.
  int areaA = orientation(a[0], a[1], a[2]), areaB = orientation(b[0], b[1], b[2]);
  if (areaA != 0 && sideA[0][0] == areaA && sideA[1][0] == areaA && sideA[2][0] == areaA)
    return true;
  return areaB != 0 && sideB[0][0] == areaB && sideB[1][0] == areaB && sideB[2][0] == areaB;
}

float circlePlaneSeparation(Vec2 center, float radius, Vec2 n, float d) {
  return dot(n, center) + d - radius;
}

bool segmentLineIntersection(Vec2 r0, Vec2 v, Vec2 n, float d, float* t) {
  float vn = dot(v, n);
  if (vn == 0.0f) return false;
  float tt = -(dot(r0, n) + d) / vn;
  if (!(tt >= 0.0f && tt <= 1.0f)) return false;
  *t = tt;
  return true;
}

}  // namespace rc
