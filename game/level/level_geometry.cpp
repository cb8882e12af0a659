#include "game/level/level_geometry.h"

#include <cmath>

#include "game/level/convex_decomposition.h"

namespace game {

float radiansFromTiled(double degrees) {
  double r = std::fmod(degrees, 360.0);
  if (r < 0) r += 360.0;
  if (r > 180) r -= 360;  // (-180, 180]
  return static_cast<float>(-r * (3.14159265358979323846 / 180.0));
}

Turn turnFromTiled(double degrees) {
  double r = std::fmod(degrees, 360.0);
  if (r < 0) r += 360.0;
  Turn t;
  if (r == 0 || r == 90 || r == 180 || r == 270) {
    // Clockwise on screen with y down is clockwise on the world with y up too: a clockwise
    // quarter turn is three counter-clockwise ones.
    t.quarters = (4 - static_cast<int>(r / 90)) % 4;
    return t;
  }
  t.exact = false;
  t.angle = radiansFromTiled(r);
  t.rot = rc::Rot::fromAngle(t.angle);
  return t;
}

rc::Vec2 turned(const Turn& turn, rc::Vec2 v) {
  if (!turn.exact) return rc::rotate(turn.rot, v);
  switch (turn.quarters) {
    case 1:
      return {-v.y, v.x};
    case 2:
      return {-v.x, -v.y};
    case 3:
      return {v.y, -v.x};
    default:
      return v;
  }
}

std::vector<rc::Vec2> ellipseOctagon(rc::Vec2 center, float halfWidth, float halfHeight) {
  // Area of the octagon through the ellipse at every 45 degrees: 2 sqrt(2) a b; the ellipse's:
  // pi a b. Scaling by the root of their ratio keeps the mass of a barrel right.
  const double scale = std::sqrt(3.14159265358979323846 / (2.0 * std::sqrt(2.0)));
  const double diagonal = std::sqrt(0.5);
  const double a = halfWidth * scale, b = halfHeight * scale;
  const double cs[8][2] = {{1, 0},  {diagonal, diagonal},   {0, 1},  {-diagonal, diagonal},
                           {-1, 0}, {-diagonal, -diagonal}, {0, -1}, {diagonal, -diagonal}};
  std::vector<rc::Vec2> out;
  for (const auto& c : cs)
    out.push_back(
        {static_cast<float>(center.x + a * c[0]), static_cast<float>(center.y + b * c[1])});
  return out;
}

rc::Shape ellipseShape(rc::Vec2 center, float halfWidth, float halfHeight) {
  if (halfWidth == halfHeight) return rc::makeCircle(center, halfWidth);
  const std::vector<rc::Vec2> octagon = ellipseOctagon(center, halfWidth, halfHeight);
  return rc::makePolygon(octagon);
}

void appendPolygonShapes(std::span<const rc::Vec2> polygon, std::vector<rc::Shape>& out) {
  const std::vector<std::vector<rc::Vec2>> pieces =
      decomposeConvex(polygon, rc::kMaxPolygonVertices);
  for (const std::vector<rc::Vec2>& piece : pieces)
    out.push_back(rc::makePolygon(piece));
}

}  // namespace game
