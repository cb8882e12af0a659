// From Tiled's geometry to the engine's: pixels with y down to metres with y up, Tiled's
// clockwise degrees to our counter-clockwise turns, ellipses to circles or octagons, polygons
// to convex pieces. Shared by the object layers and the tiles' collision shapes.
#pragma once

#include <span>
#include <vector>

#include "physics/shapes.h"

namespace game {

// Map pixels to world metres: x / ppm, -y / ppm (Tiled's y goes down, ours up).
struct MapUnits {
  double pixelsPerMeter = 32.0;
  rc::Vec2 point(double x, double y) const {
    return {static_cast<float>(x / pixelsPerMeter), static_cast<float>(-y / pixelsPerMeter)};
  }
  // A vector (an offset or an extent along x and y), flipped like a point.
  rc::Vec2 offset(double x, double y) const { return point(x, y); }
  float length(double pixels) const { return static_cast<float>(pixels / pixelsPerMeter); }
};

// Tiled's rotation as a turn of ours. Quarter turns are exact (a wall turned by 90 degrees
// stays an axis-aligned box, with no 1e-8 residue from a cosine); any other angle turns by
// rc::Rot::fromAngle, the rotation the world itself makes of a body's angle.
struct Turn {
  int quarters = 0;    // counter-clockwise quarter turns, 0..3, when exact
  bool exact = true;   // a multiple of 90 degrees
  float angle = 0.0f;  // radians, counter-clockwise, in (-pi, pi]; 0 when exact
  rc::Rot rot{};       // of `angle`
};
// Degrees clockwise on screen (finite, any size) as radians counter-clockwise in (-pi, pi].
float radiansFromTiled(double degrees);
// Degrees clockwise on screen (finite, any size) as a turn.
Turn turnFromTiled(double degrees);
// v turned by the turn (exactly for quarter turns).
rc::Vec2 turned(const Turn& turn, rc::Vec2 v);
// For a body: the turn's angle when not exact, else 0 (the quarter turns go into the shapes).
inline float bodyAngle(const Turn& turn) {
  return turn.exact ? 0.0f : turn.angle;
}

// An axis-aligned ellipse: a circle when round, else an octagon through the ellipse's
// directions at every 45 degrees, scaled so its area equals the ellipse's.
rc::Shape ellipseShape(rc::Vec2 center, float halfWidth, float halfHeight);
// The vertices of that octagon (for callers that transform it further).
std::vector<rc::Vec2> ellipseOctagon(rc::Vec2 center, float halfWidth, float halfHeight);

// A polygon as rc::Polygons: itself when convex with at most 8 vertices, else the convex
// pieces of decomposeConvex. Throws DecompositionError or rc::InvalidShape.
void appendPolygonShapes(std::span<const rc::Vec2> polygon, std::vector<rc::Shape>& out);

}  // namespace game
