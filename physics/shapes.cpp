#include "physics/shapes.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>

namespace rc {
namespace {

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
}

std::string vec(Vec2 v) {
  return "(" + num(v.x) + ", " + num(v.y) + ")";
}

[[noreturn]] void fail(const std::string& what) {
  throw InvalidShape(what);
}

void requireFinite(const char* shape, const char* field, float v) {
  if (!isFinite(v)) fail(std::string(shape) + ": " + field + " is not finite (" + num(v) + ")");
}
void requireFinite(const char* shape, const char* field, Vec2 v) {
  if (!isFinite(v)) fail(std::string(shape) + ": " + field + " is not finite " + vec(v));
}
void requirePositive(const char* shape, const char* field, float v) {
  requireFinite(shape, field, v);
  if (!(v > 0.0f)) fail(std::string(shape) + ": " + field + " must be positive, got " + num(v));
}
void requireNonNegative(const char* shape, const char* field, float v) {
  requireFinite(shape, field, v);
  if (v < 0.0f) fail(std::string(shape) + ": " + field + " must not be negative, got " + num(v));
}

// True when the outline a -> b -> c turns left at b by more than rounding: the sine of the turn
// above 4 float epsilons. Below that a float evaluation of the same cross product (validate(),
// the contact code) errs by up to 2.5 epsilons of |b - a| |c - b| and could see the corner turn
// either way, so the corner counts as straight. Box2D 2.4.1 drops only exactly collinear points;
// this drops only points collinear within rounding. In double, ~1e-16 relative.
bool turnsLeft(Vec2 a, Vec2 b, Vec2 c) {
  constexpr double kStraight = 4.0 * std::numeric_limits<float>::epsilon();
  const double e1x = static_cast<double>(b.x) - a.x, e1y = static_cast<double>(b.y) - a.y;
  const double e2x = static_cast<double>(c.x) - b.x, e2y = static_cast<double>(c.y) - b.y;
  const double turn = e1x * e2y - e1y * e2x;
  // Squared to do without a root: from float coordinates these neither overflow nor underflow.
  return turn > 0.0 &&
         turn * turn > kStraight * kStraight * (e1x * e1x + e1y * e1y) * (e2x * e2x + e2y * e2y);
}

// Removes the corners of a closed outline that do not turn left (straight within rounding,
// repeated points, or bent the wrong way by rounding), each judged by its remaining neighbours.
void dropStraightCorners(std::vector<Vec2>& ring) {
  std::vector<Vec2> kept;
  kept.reserve(ring.size());
  for (Vec2 v : ring) {
    while (kept.size() >= 2 && !turnsLeft(kept[kept.size() - 2], kept.back(), v))
      kept.pop_back();
    kept.push_back(v);
  }
  // Only the corners at the seam (the last and the first) are left to check; removing one of
  // them changes only the other seam corner.
  size_t first = 0, end = kept.size();
  while (end - first >= 3) {
    if (!turnsLeft(kept[end - 2], kept[end - 1], kept[first])) {
      --end;
    } else if (!turnsLeft(kept[end - 1], kept[first], kept[first + 1])) {
      ++first;
    } else {
      break;
    }
  }
  if (end - first < 3) first = end;  // nothing with an area is left
  ring.assign(kept.begin() + static_cast<std::ptrdiff_t>(first),
              kept.begin() + static_cast<std::ptrdiff_t>(end));
}

// Weld radius: Box2D's half slop for polygons over 25 cm, 1% of the size below (Box2D's ratio at
// 25 cm), so a 1 mm polygon is scaled down, not welded to a point.
double weldRadius(std::span<const Vec2> points) {
  Vec2 lo = points.empty() ? Vec2{} : points[0], hi = lo;
  for (Vec2 p : points) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  const double size = std::max(static_cast<double>(hi.x) - lo.x, static_cast<double>(hi.y) - lo.y);
  return std::min(0.5 * kLinearSlop, 0.01 * size);
}

// Convex hull, counter-clockwise from the lowest-x (then lowest-y) vertex: Andrew's monotone
// chain over the sorted points, O(n log n), keeping only corners that turn (turnsLeft). Then each
// vertex closer than the weld radius to the one kept before it is dropped, so no edge is shorter
// than that, and any corner this straightens goes too. Welding along the hull rather than the
// whole cloud keeps a thin polygon's thickness; each welded point is within the radius of a
// kept vertex.
std::vector<Vec2> convexHull(std::span<const Vec2> input, double weld) {
  std::vector<Vec2> pts;
  pts.reserve(input.size());
  for (Vec2 p : input)
    pts.push_back({p.x + 0.0f, p.y + 0.0f});  // -0 as +0: equal points are the same bits
  std::sort(pts.begin(), pts.end(),
            [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return {};

  std::vector<Vec2> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && !turnsLeft(hull[k - 2], hull[k - 1], pts[i]))
      --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && !turnsLeft(hull[k - 2], hull[k - 1], pts[i]))
      --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);  // the last point repeats the first

  auto near = [&](Vec2 a, Vec2 b) {
    const double dx = static_cast<double>(b.x) - a.x, dy = static_cast<double>(b.y) - a.y;
    return dx * dx + dy * dy < weld * weld;
  };
  std::vector<Vec2> welded;
  welded.reserve(hull.size());
  for (Vec2 v : hull) {
    if (welded.empty() || !near(welded.back(), v)) welded.push_back(v);
  }
  while (welded.size() >= 2 && near(welded.back(), welded.front()))
    welded.pop_back();
  dropStraightCorners(welded);
  return welded;
}

Vec2 polygonCentroid(const Vec2* v, int count) {
  // Triangle fan about the first vertex, in coordinates relative to it for precision.
  double cx = 0.0, cy = 0.0, area = 0.0;
  Vec2 origin = v[0];
  for (int i = 1; i < count - 1; ++i) {
    Vec2 e1 = v[i] - origin;
    Vec2 e2 = v[i + 1] - origin;
    double a = 0.5 * (static_cast<double>(e1.x) * e2.y - static_cast<double>(e1.y) * e2.x);
    cx += a * (static_cast<double>(e1.x) + e2.x) / 3.0;
    cy += a * (static_cast<double>(e1.y) + e2.y) / 3.0;
    area += a;
  }
  return {static_cast<float>(origin.x + cx / area), static_cast<float>(origin.y + cy / area)};
}

Polygon finishPolygon(const std::vector<Vec2>& hull, float radius) {
  Polygon poly;
  poly.count = static_cast<int>(hull.size());
  poly.radius = radius;
  for (int i = 0; i < poly.count; ++i)
    poly.vertices[i] = hull[static_cast<size_t>(i)];
  for (int i = 0; i < poly.count; ++i) {
    Vec2 edge = poly.vertices[(i + 1) % poly.count] - poly.vertices[i];
    poly.normals[i] = normalize(rightPerp(edge));
  }
  poly.centroid = polygonCentroid(poly.vertices, poly.count);
  return poly;
}

// The angle in [0, pi/2] whose sine and cosine are proportional to s >= 0 and c >= 0, in double
// from +, -, *, / and sqrt alone (each correctly rounded by IEEE 754), so the same bits on every
// platform, unlike libm's atan2. Four half-angle steps tan(a/2) = s / (c + |(s, c)|) bring the
// angle below pi/32, where atan's odd series to t^17 leaves a relative error under 1e-19 (the
// first omitted term, t^18 / 19 with t = tan(pi/32) < 0.0985); each step rounds by ~1e-16.
double quarterTurnAngle(double s, double c) {
  double t = s / (c + std::sqrt(s * s + c * c));  // tan(a/2), in [0, 1]
  for (int i = 0; i < 3; ++i)
    t /= 1.0 + std::sqrt(1.0 + t * t);  // tan(a/16) <= tan(pi/32)
  const double t2 = t * t;
  double series = 1.0 / 17.0;  // atan(t) / t = 1 - t^2/3 + t^4/5 - ..., by Horner
  for (int k = 15; k >= 1; k -= 2)
    series = 1.0 / k - t2 * series;
  return 16.0 * t * series;
}

// Mass properties accumulated in double: they are computed once per shape, and double keeps the
// parallel-axis shifts of far-off shapes exact enough for the 1e-5 relative oracle tolerance.
struct MassSum {
  double area = 0.0, cx = 0.0, cy = 0.0, inertiaOrigin = 0.0;  // second moment about origin
  void add(double a, double x, double y, double ownInertia) {
    area += a;
    cx += a * x;
    cy += a * y;
    inertiaOrigin += ownInertia + a * (x * x + y * y);
  }
  MassData finish(float density) const {
    MassData md;
    if (area <= 0.0) return md;
    double x = cx / area, y = cy / area;
    md.area = static_cast<float>(area);
    md.mass = static_cast<float>(density * area);
    md.center = {static_cast<float>(x), static_cast<float>(y)};
    md.inertia = static_cast<float>(density * (inertiaOrigin - area * (x * x + y * y)));
    return md;
  }
};

}  // namespace

const char* shapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::circle:
      return "circle";
    case ShapeType::box:
      return "box";
    case ShapeType::polygon:
      return "polygon";
    case ShapeType::capsule:
      return "capsule";
    case ShapeType::segment:
      return "segment";
    case ShapeType::chainSegment:
      return "chain segment";
  }
  return "unknown shape";
}

Circle makeCircle(Vec2 center, float radius) {
  requireFinite("circle", "center", center);
  requirePositive("circle", "radius", radius);
  return {center, radius};
}

Box makeBox(float halfWidth, float halfHeight, Vec2 center) {
  requirePositive("box", "half width", halfWidth);
  requirePositive("box", "half height", halfHeight);
  requireFinite("box", "center", center);
  return {center, {halfWidth, halfHeight}};
}

Capsule makeCapsule(Vec2 center1, Vec2 center2, float radius) {
  requireFinite("capsule", "center1", center1);
  requireFinite("capsule", "center2", center2);
  requirePositive("capsule", "radius", radius);
  if (distanceSquared(center1, center2) < kLinearSlop * kLinearSlop)
    fail("capsule: centers " + vec(center1) + " and " + vec(center2) +
         " are closer than the linear slop; use a circle");
  return {center1, center2, radius};
}

Segment makeSegment(Vec2 point1, Vec2 point2) {
  requireFinite("segment", "point1", point1);
  requireFinite("segment", "point2", point2);
  if (distanceSquared(point1, point2) < kLinearSlop * kLinearSlop)
    fail("segment: points " + vec(point1) + " and " + vec(point2) + " are closer than the slop");
  return {point1, point2};
}

Polygon makePolygon(std::span<const Vec2> points, float radius) {
  requireNonNegative("polygon", "radius", radius);
  for (size_t i = 0; i < points.size(); ++i) {
    if (!isFinite(points[i]))
      fail("polygon: point " + std::to_string(i) + " is not finite " + vec(points[i]));
  }
  std::vector<Vec2> hull = convexHull(points, weldRadius(points));
  if (hull.size() < 3)
    fail("polygon: the " + std::to_string(points.size()) +
         " points have a degenerate hull (all coincident or collinear)");
  if (hull.size() > static_cast<size_t>(kMaxPolygonVertices))
    fail("polygon: the hull has " + std::to_string(hull.size()) + " vertices; at most " +
         std::to_string(kMaxPolygonVertices) + " are supported");
  return finishPolygon(hull, radius);
}

Polygon makeOrientedBox(float halfWidth, float halfHeight, Vec2 center, float angle, float radius) {
  requirePositive("oriented box", "half width", halfWidth);
  requirePositive("oriented box", "half height", halfHeight);
  requireFinite("oriented box", "center", center);
  requireFinite("oriented box", "angle", angle);
  requireNonNegative("oriented box", "radius", radius);
  Transform xf{center, Rot::fromAngle(angle)};
  std::vector<Vec2> v = {apply(xf, {-halfWidth, -halfHeight}), apply(xf, {halfWidth, -halfHeight}),
                         apply(xf, {halfWidth, halfHeight}), apply(xf, {-halfWidth, halfHeight})};
  Polygon poly = finishPolygon(v, radius);
  poly.centroid = center;
  // Exact normals: the rotated axes, not the normalised differences of rounded vertices.
  Vec2 ax = rotate(xf.q, {1.0f, 0.0f});
  Vec2 ay = rotate(xf.q, {0.0f, 1.0f});
  poly.normals[0] = -ay;
  poly.normals[1] = ax;
  poly.normals[2] = ay;
  poly.normals[3] = -ax;
  poly.boxHalfExtents = {halfWidth, halfHeight};
  return poly;
}

Polygon makeTriangle(Vec2 a, Vec2 b, Vec2 c, float radius) {
  Vec2 pts[3] = {a, b, c};
  requireFinite("triangle", "vertex a", a);
  requireFinite("triangle", "vertex b", b);
  requireFinite("triangle", "vertex c", c);
  return makePolygon(pts, radius);
}

Polygon boxToPolygon(const Box& box) {
  return makeOrientedBox(box.halfExtents.x, box.halfExtents.y, box.center);
}

std::vector<ChainSegment> makeChain(std::span<const Vec2> points, bool loop, bool oneSided) {
  size_t n = points.size();
  if (n < (loop ? 3u : 2u))
    fail(std::string("chain: a ") + (loop ? "loop" : "open chain") + " needs at least " +
         (loop ? "3" : "2") + " points, got " + std::to_string(n));
  for (size_t i = 0; i < n; ++i) {
    if (!isFinite(points[i]))
      fail("chain: point " + std::to_string(i) + " is not finite " + vec(points[i]));
  }
  size_t links = loop ? n : n - 1;
  for (size_t i = 0; i < links; ++i) {
    if (distanceSquared(points[i], points[(i + 1) % n]) < kLinearSlop * kLinearSlop)
      fail("chain: points " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
           " are closer than the slop " + vec(points[i]));
  }
  std::vector<ChainSegment> out;
  out.reserve(links);
  for (size_t i = 0; i < links; ++i) {
    ChainSegment cs;
    cs.segment = {points[i], points[(i + 1) % n]};
    cs.ghost1 = loop ? points[(i + n - 1) % n] : (i == 0 ? points[0] : points[i - 1]);
    cs.ghost2 = loop ? points[(i + 2) % n] : (i + 2 < n ? points[i + 2] : points[n - 1]);
    cs.oneSided = oneSided;
    out.push_back(cs);
  }
  return out;
}

AABB computeAABB(const Circle& s, const Transform& xf) {
  Vec2 p = apply(xf, s.center);
  return {{p.x - s.radius, p.y - s.radius}, {p.x + s.radius, p.y + s.radius}};
}

AABB computeAABB(const Box& s, const Transform& xf) {
  Vec2 c = apply(xf, s.center);
  // Extent of a rotated box along each world axis: |R| * halfExtents.
  Vec2 h = s.halfExtents;
  float ex = std::fabs(xf.q.c) * h.x + std::fabs(xf.q.s) * h.y;
  float ey = std::fabs(xf.q.s) * h.x + std::fabs(xf.q.c) * h.y;
  return {{c.x - ex, c.y - ey}, {c.x + ex, c.y + ey}};
}

AABB computeAABB(const Polygon& s, const Transform& xf) {
  Vec2 lo = apply(xf, s.vertices[0]);
  Vec2 hi = lo;
  for (int i = 1; i < s.count; ++i) {
    Vec2 v = apply(xf, s.vertices[i]);
    lo = min(lo, v);
    hi = max(hi, v);
  }
  return inflate({lo, hi}, s.radius);
}

AABB computeAABB(const Capsule& s, const Transform& xf) {
  Vec2 a = apply(xf, s.center1), b = apply(xf, s.center2);
  return inflate({min(a, b), max(a, b)}, s.radius);
}

AABB computeAABB(const Segment& s, const Transform& xf) {
  Vec2 a = apply(xf, s.point1), b = apply(xf, s.point2);
  return {min(a, b), max(a, b)};
}

AABB computeAABB(const Shape& s, const Transform& xf) {
  switch (s.type) {
    case ShapeType::circle:
      return computeAABB(s.circle, xf);
    case ShapeType::box:
      return computeAABB(s.box, xf);
    case ShapeType::polygon:
      return computeAABB(s.polygon, xf);
    case ShapeType::capsule:
      return computeAABB(s.capsule, xf);
    case ShapeType::segment:
      return computeAABB(s.segment, xf);
    case ShapeType::chainSegment:
      return computeAABB(s.chainSegment.segment, xf);
  }
  return {};
}

MassData computeMass(const Circle& s, float density) {
  MassSum sum;
  double r2 = static_cast<double>(s.radius) * s.radius;
  double area = kPi * r2;
  sum.add(area, s.center.x, s.center.y, 0.5 * area * r2);
  return sum.finish(density);
}

MassData computeMass(const Box& s, float density) {
  MassSum sum;
  double w = 2.0 * s.halfExtents.x, h = 2.0 * s.halfExtents.y;
  double area = w * h;
  sum.add(area, s.center.x, s.center.y, area * (w * w + h * h) / 12.0);
  return sum.finish(density);
}

MassData computeMass(const Polygon& s, float density) {
  // Exact for a rounded polygon: the core polygon, a rectangle of depth r on every edge, and a
  // circular sector at every vertex whose angle is the turn of the outline there (they sum to
  // 2 pi). Everything is in double, relative to the first vertex, so float vertices far from the
  // origin lose nothing.
  struct D2 {
    double x, y;
  };
  MassSum sum;
  const Vec2 o = s.vertices[0];
  auto rel = [&](int i) {
    Vec2 v = s.vertices[i % s.count];
    return D2{static_cast<double>(v.x) - o.x, static_cast<double>(v.y) - o.y};
  };
  for (int i = 1; i < s.count - 1; ++i) {
    D2 e1 = rel(i), e2 = rel(i + 1);
    double a = 0.5 * (e1.x * e2.y - e1.y * e2.x);
    double x = (e1.x + e2.x) / 3.0, y = (e1.y + e2.y) / 3.0;
    // Second moment of triangle (0, e1, e2) about vertex 0, then moved to its own centroid.
    double aboutVertex =
        a * (e1.x * e1.x + e2.x * e1.x + e2.x * e2.x + e1.y * e1.y + e2.y * e1.y + e2.y * e2.y) /
        6.0;
    sum.add(a, x, y, aboutVertex - a * (x * x + y * y));
  }
  const double r = s.radius;
  if (r > 0.0) {
    // Edge normals in double from the edges themselves: the stored float normals tilt a sector
    // at a vertex where the outline turns by nearly pi (an interior angle of 1e-4 rad) by
    // enough to move the centroid 4e-5 m (mass oracle, case 94509). A plain root for the
    // length: squares of float differences cannot overflow or underflow a double.
    auto normal = [&](int i) {
      D2 a = rel(i), b = rel(i + 1);
      double ex = b.x - a.x, ey = b.y - a.y, l = std::sqrt(ex * ex + ey * ey);
      return D2{ey / l, -ex / l};
    };
    for (int i = 0; i < s.count; ++i) {
      D2 v1 = rel(i), v2 = rel(i + 1);
      D2 n = normal(i);
      double ex = v2.x - v1.x, ey = v2.y - v1.y, len = std::sqrt(ex * ex + ey * ey);
      double a = len * r;
      sum.add(a, 0.5 * (v1.x + v2.x) + 0.5 * r * n.x, 0.5 * (v1.y + v2.y) + 0.5 * r * n.y,
              a * (len * len + r * r) / 12.0);

      // Sector at vertex i+1, from this edge's normal n to the next edge's normal m, halved by
      // their bisector: half the turn and its sine, without libm.
      D2 m = normal(i + 1);
      D2 bis{n.x + m.x, n.y + m.y};
      double bl = std::sqrt(bis.x * bis.x + bis.y * bis.y);
      bis = {bis.x / bl, bis.y / bl};
      double sinHalf = n.x * bis.y - n.y * bis.x;
      double half = quarterTurnAngle(sinHalf, n.x * bis.x + n.y * bis.y);
      if (!(half > 0.0)) continue;  // a straight corner has no sector
      double area = half * r * r;
      double d = 2.0 * r * sinHalf / (3.0 * half);  // sector centroid from its apex
      double aboutApex = 0.5 * half * r * r * r * r;
      sum.add(area, v2.x + d * bis.x, v2.y + d * bis.y, aboutApex - area * d * d);
    }
  }
  MassData md = sum.finish(density);
  md.center = {static_cast<float>(static_cast<double>(md.center.x) + o.x),
               static_cast<float>(static_cast<double>(md.center.y) + o.y)};
  return md;
}

MassData computeMass(const Capsule& s, float density) {
  // A rectangle between the two half discs; each half disc's centroid is 4r/(3 pi) from its
  // centre and its second moment about the centre is pi r^4 / 4.
  MassSum sum;
  double r = s.radius;
  Vec2 c1 = s.center1, c2 = s.center2;
  Vec2 axis = c2 - c1;
  double len = length(axis);
  Vec2 u = normalize(axis);
  double rect = 2.0 * r * len;
  sum.add(rect, 0.5 * (static_cast<double>(c1.x) + c2.x), 0.5 * (static_cast<double>(c1.y) + c2.y),
          rect * (len * len + 4.0 * r * r) / 12.0);
  constexpr double kPiD = 3.14159265358979323846;
  double half = 0.5 * kPiD * r * r;
  double d = 4.0 * r / (3.0 * kPiD);
  double aboutCentre = 0.25 * kPiD * r * r * r * r;
  sum.add(half, c2.x + d * u.x, c2.y + d * u.y, aboutCentre - half * d * d);
  sum.add(half, c1.x - d * u.x, c1.y - d * u.y, aboutCentre - half * d * d);
  return sum.finish(density);
}

MassData computeMass(const Shape& s, float density) {
  switch (s.type) {
    case ShapeType::circle:
      return computeMass(s.circle, density);
    case ShapeType::box:
      return computeMass(s.box, density);
    case ShapeType::polygon:
      return computeMass(s.polygon, density);
    case ShapeType::capsule:
      return computeMass(s.capsule, density);
    case ShapeType::segment:
    case ShapeType::chainSegment:
      return {};
  }
  return {};
}

MassData combineMass(std::span<const MassData> parts) {
  double mass = 0.0, cx = 0.0, cy = 0.0, area = 0.0;
  for (const MassData& m : parts) {
    mass += m.mass;
    area += m.area;
    cx += static_cast<double>(m.mass) * m.center.x;
    cy += static_cast<double>(m.mass) * m.center.y;
  }
  MassData out;
  out.area = static_cast<float>(area);
  if (mass <= 0.0) return out;
  cx /= mass;
  cy /= mass;
  double inertia = 0.0;
  for (const MassData& m : parts) {
    double dx = m.center.x - cx, dy = m.center.y - cy;
    inertia += m.inertia + m.mass * (dx * dx + dy * dy);
  }
  out.mass = static_cast<float>(mass);
  out.center = {static_cast<float>(cx), static_cast<float>(cy)};
  out.inertia = static_cast<float>(inertia);
  return out;
}

bool containsPoint(const Shape& s, const Transform& xf, Vec2 point) {
  Vec2 p = invApply(xf, point);
  switch (s.type) {
    case ShapeType::circle:
      return distanceSquared(p, s.circle.center) <= s.circle.radius * s.circle.radius;
    case ShapeType::box: {
      Vec2 d = abs(p - s.box.center);
      return d.x <= s.box.halfExtents.x && d.y <= s.box.halfExtents.y;
    }
    case ShapeType::polygon: {
      const Polygon& poly = s.polygon;
      float maxSep = -1e30f;
      for (int i = 0; i < poly.count; ++i)
        maxSep = std::max(maxSep, dot(poly.normals[i], p - poly.vertices[i]));
      if (maxSep <= 0.0f) return true;
      if (poly.radius == 0.0f) return false;
      // Rounded: within radius of the core's boundary.
      float best = 1e30f;
      for (int i = 0; i < poly.count; ++i) {
        Vec2 a = poly.vertices[i], b = poly.vertices[(i + 1) % poly.count];
        Vec2 e = b - a;
        float t = std::clamp(dot(p - a, e) / lengthSquared(e), 0.0f, 1.0f);
        best = std::min(best, distanceSquared(p, mulAdd(a, t, e)));
      }
      return best <= poly.radius * poly.radius;
    }
    case ShapeType::capsule: {
      Vec2 a = s.capsule.center1, e = s.capsule.center2 - a;
      float t = std::clamp(dot(p - a, e) / lengthSquared(e), 0.0f, 1.0f);
      return distanceSquared(p, mulAdd(a, t, e)) <= s.capsule.radius * s.capsule.radius;
    }
    case ShapeType::segment:
    case ShapeType::chainSegment:
      return false;
  }
  return false;
}

BoundingCircle computeBoundingCircle(const Shape& s) {
  switch (s.type) {
    case ShapeType::circle:
      return {s.circle.center, s.circle.radius};
    case ShapeType::box:
      return {s.box.center, length(s.box.halfExtents)};
    case ShapeType::polygon: {
      float r = 0.0f;
      for (int i = 0; i < s.polygon.count; ++i)
        r = std::max(r, distance(s.polygon.centroid, s.polygon.vertices[i]));
      return {s.polygon.centroid, r + s.polygon.radius};
    }
    case ShapeType::capsule: {
      Vec2 c = 0.5f * (s.capsule.center1 + s.capsule.center2);
      return {c, 0.5f * distance(s.capsule.center1, s.capsule.center2) + s.capsule.radius};
    }
    case ShapeType::segment: {
      Vec2 c = 0.5f * (s.segment.point1 + s.segment.point2);
      return {c, 0.5f * distance(s.segment.point1, s.segment.point2)};
    }
    case ShapeType::chainSegment: {
      const Segment& g = s.chainSegment.segment;
      return {0.5f * (g.point1 + g.point2), 0.5f * distance(g.point1, g.point2)};
    }
  }
  return {};
}

void validate(const Shape& s) {
  switch (s.type) {
    case ShapeType::circle:
      (void)makeCircle(s.circle.center, s.circle.radius);
      return;
    case ShapeType::box:
      (void)makeBox(s.box.halfExtents.x, s.box.halfExtents.y, s.box.center);
      return;
    case ShapeType::polygon: {
      const Polygon& p = s.polygon;
      if (p.count < 3 || p.count > kMaxPolygonVertices)
        fail("polygon: vertex count " + std::to_string(p.count) + " is outside [3, 8]");
      requireNonNegative("polygon", "radius", p.radius);
      for (int i = 0; i < p.count; ++i) {
        requireFinite("polygon", "vertex", p.vertices[i]);
        Vec2 e1 = p.vertices[(i + 1) % p.count] - p.vertices[i];
        Vec2 e2 = p.vertices[(i + 2) % p.count] - p.vertices[(i + 1) % p.count];
        if (!(cross(e1, e2) > 0.0f))
          fail("polygon: vertices are not strictly convex and counter-clockwise at vertex " +
               std::to_string((i + 1) % p.count));
      }
      return;
    }
    case ShapeType::capsule:
      (void)makeCapsule(s.capsule.center1, s.capsule.center2, s.capsule.radius);
      return;
    case ShapeType::segment:
      (void)makeSegment(s.segment.point1, s.segment.point2);
      return;
    case ShapeType::chainSegment: {
      const ChainSegment& c = s.chainSegment;
      (void)makeSegment(c.segment.point1, c.segment.point2);
      requireFinite("chain segment", "ghost1", c.ghost1);
      requireFinite("chain segment", "ghost2", c.ghost2);
      return;
    }
  }
  fail("shape: unknown type tag " + std::to_string(static_cast<int>(s.type)));
}

}  // namespace rc
