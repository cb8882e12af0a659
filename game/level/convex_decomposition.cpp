#include "game/level/convex_decomposition.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace game {

namespace {

struct P {
  double x, y;
};

P operator-(P a, P b) {
  return {a.x - b.x, a.y - b.y};
}
double cross(P a, P b) {
  return a.x * b.y - a.y * b.x;
}
double dot(P a, P b) {
  return a.x * b.x + a.y * b.y;
}
double orient(P a, P b, P c) {
  return cross(b - a, c - b);
}

// Collinear within float input's rounding: the cross product against the edges' lengths.
bool straight(P a, P b, P c) {
  const P e1 = b - a, e2 = c - b;
  const double scale = std::sqrt(dot(e1, e1) * dot(e2, e2));
  return std::fabs(cross(e1, e2)) <= 1e-9 * scale;
}

bool onSegment(P a, P b, P p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Closed segments ab and cd share a point (touching counts).
bool segmentsMeet(P a, P b, P c, P d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c),
               d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && onSegment(c, d, a)) || (d2 == 0 && onSegment(c, d, b)) ||
         (d3 == 0 && onSegment(a, b, c)) || (d4 == 0 && onSegment(a, b, d));
}

// p inside or on the boundary of the counter-clockwise triangle abc.
bool inTriangle(P a, P b, P c, P p) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

// The points without consecutive duplicates (the last equal to the first included).
std::vector<P> distinct(std::span<const rc::Vec2> polygon) {
  std::vector<P> pts;
  for (const rc::Vec2 v : polygon) {
    const P p{v.x, v.y};
    if (pts.empty() || p.x != pts.back().x || p.y != pts.back().y) pts.push_back(p);
  }
  while (pts.size() > 1 && pts.front().x == pts.back().x && pts.front().y == pts.back().y)
    pts.pop_back();
  return pts;
}

// Drops straight-through vertices until none is left; a vertex where the outline doubles back
// on itself is not simple.
void withoutStraights(std::vector<P>& pts) {
  bool changed = true;
  while (changed && pts.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size() && pts.size() >= 3; ++i) {
      const P a = pts[(i + pts.size() - 1) % pts.size()], b = pts[i], c = pts[(i + 1) % pts.size()];
      if (!straight(a, b, c)) continue;
      if (dot(b - a, c - b) < 0)
        throw DecompositionError("doubles back on itself at vertex " + std::to_string(i));
      pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
      changed = true;
      --i;
    }
  }
}

void requireSimple(const std::vector<P>& pts) {
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // neighbours through the closing edge
      if (segmentsMeet(pts[i], pts[(i + 1) % n], pts[j], pts[(j + 1) % n]))
        throw DecompositionError("crosses or touches itself: edges " + std::to_string(i) + " and " +
                                 std::to_string(j) + " meet");
    }
}

using Triangle = std::array<int, 3>;

std::vector<Triangle> earClip(const std::vector<P>& pts) {
  const int n = static_cast<int>(pts.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  std::vector<Triangle> out;
  int remaining = n, i = 0, sinceLastEar = 0;
  while (remaining > 3) {
    const int a = prev[i], c = next[i];
    bool ear = orient(pts[a], pts[i], pts[c]) > 0;
    for (int k = next[c]; ear && k != a; k = next[k])
      ear = !inTriangle(pts[a], pts[i], pts[c], pts[k]);
    if (ear) {
      out.push_back({a, i, c});
      next[a] = c;
      prev[c] = a;
      --remaining;
      sinceLastEar = 0;
      i = c;
    } else {
      // A simple polygon always has two ears; none in a whole turn means rounding made the
      // remaining outline degenerate.
      if (++sinceLastEar > remaining)
        throw DecompositionError(
            "cannot be triangulated (nearly degenerate: vertices almost "
            "on top of each other or edges almost touching)");
      i = c;
    }
  }
  out.push_back({prev[i], i, next[i]});
  return out;
}

// The merged outline if the two pieces share the edge u -> v (in `a`) and v -> u (in `b`).
std::vector<int> mergeAlong(const std::vector<int>& a, const std::vector<int>& b, int u, int v) {
  const std::size_t na = a.size(), nb = b.size();
  std::size_t ia = 0, ib = 0;
  while (ia < na && !(a[ia] == u && a[(ia + 1) % na] == v))
    ++ia;
  while (ib < nb && !(b[ib] == v && b[(ib + 1) % nb] == u))
    ++ib;
  if (ia == na || ib == nb) return {};
  std::vector<int> out;
  for (std::size_t k = 0; k < na; ++k)
    out.push_back(a[(ia + 1 + k) % na]);  // v ... u
  for (std::size_t k = 2; k < nb; ++k)
    out.push_back(b[(ib + k) % nb]);  // after u, up to before v
  return out;
}

// Drops vertices where the outline goes straight on; false if any vertex turns clockwise.
bool convexWithoutStraights(const std::vector<P>& pts, std::vector<int>& piece) {
  for (std::size_t k = 0; k < piece.size() && piece.size() >= 3;) {
    const std::size_t n = piece.size();
    const P a = pts[piece[(k + n - 1) % n]], b = pts[piece[k]], c = pts[piece[(k + 1) % n]];
    if (straight(a, b, c)) {
      piece.erase(piece.begin() + static_cast<std::ptrdiff_t>(k));
      continue;
    }
    if (orient(a, b, c) < 0) return false;
    ++k;
  }
  return piece.size() >= 3;
}

}  // namespace

double signedArea(std::span<const rc::Vec2> polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const rc::Vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    twice += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
  }
  return 0.5 * twice;
}

std::vector<std::vector<rc::Vec2>> decomposeConvex(std::span<const rc::Vec2> polygon,
                                                   int maxVertices) {
  if (maxVertices < 3) throw std::invalid_argument("decomposeConvex: maxVertices below 3");
  if (polygon.size() > kMaxDecomposedVertices)
    throw DecompositionError("has " + std::to_string(polygon.size()) + " vertices, more than the " +
                             std::to_string(kMaxDecomposedVertices) + " that can be split");
  for (const rc::Vec2 v : polygon)
    if (!std::isfinite(v.x) || !std::isfinite(v.y))
      throw DecompositionError("has a vertex that is not finite");
  std::vector<P> pts = distinct(polygon);
  if (pts.size() < 3) throw DecompositionError("has fewer than 3 distinct corners");
  bool line = true;
  for (std::size_t i = 2; i < pts.size() && line; ++i)
    line = straight(pts[0], pts[1], pts[i]);
  if (line) throw DecompositionError("has no area: its points lie on one line");
  withoutStraights(pts);
  requireSimple(pts);
  double area = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    area += cross(pts[i], pts[(i + 1) % pts.size()]);
  if (area == 0) throw DecompositionError("has no area");
  if (area < 0) std::reverse(pts.begin(), pts.end());

  const std::vector<Triangle> triangles = earClip(pts);
  // Pieces start as the triangles; owner[t] is the piece that holds triangle t.
  std::vector<std::vector<int>> pieces;
  std::vector<int> owner(triangles.size());
  std::map<std::pair<int, int>, std::vector<int>> edgeTriangles;  // ordered: deterministic
  std::vector<std::pair<int, int>> diagonals;                     // in the order they were cut
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    pieces.push_back({triangles[t][0], triangles[t][1], triangles[t][2]});
    owner[t] = static_cast<int>(t);
    for (int k = 0; k < 3; ++k) {
      const int u = triangles[t][k], v = triangles[t][(k + 1) % 3];
      auto& list = edgeTriangles[{std::min(u, v), std::max(u, v)}];
      list.push_back(static_cast<int>(t));
      if (list.size() == 2) diagonals.push_back({u, v});
    }
  }
  std::vector<bool> alive(pieces.size(), true);
  for (const auto& [u, v] : diagonals) {
    const auto& list = edgeTriangles[{std::min(u, v), std::max(u, v)}];
    const int pa = owner[list[0]], pb = owner[list[1]];
    if (pa == pb) continue;
    // The piece with u -> v first: triangles are counter-clockwise, so exactly one has it.
    std::vector<int> merged = mergeAlong(pieces[pa], pieces[pb], u, v);
    if (merged.empty()) merged = mergeAlong(pieces[pa], pieces[pb], v, u);
    if (merged.empty() || !convexWithoutStraights(pts, merged) ||
        static_cast<int>(merged.size()) > maxVertices)
      continue;
    pieces[pa] = std::move(merged);
    alive[pb] = false;
    for (int& o : owner)
      if (o == pb) o = pa;
  }
  std::vector<std::vector<rc::Vec2>> out;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (!alive[p]) continue;
    std::vector<int> piece = pieces[p];
    if (!convexWithoutStraights(pts, piece)) continue;  // a sliver of zero area
    std::vector<rc::Vec2> poly;
    for (const int k : piece)
      poly.push_back({static_cast<float>(pts[k].x), static_cast<float>(pts[k].y)});
    out.push_back(std::move(poly));
  }
  return out;
}

}  // namespace game
