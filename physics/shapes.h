// Ricochet physics: shape definitions, validation, bounding boxes and mass properties.
//
// Every solid shape is a convex set, possibly rounded by a radius:
//   Circle   a point and a radius;
//   Box      an axis-aligned box in the body frame (the fast path for walls and non-rotating
//            boxes: pairs of boxes on unrotated bodies never touch the general polygon code);
//   Polygon  a convex polygon of 3..8 vertices in counter-clockwise order, built from any point
//            cloud by a convex hull, with an optional rounding radius. Oriented boxes and
//            triangles are polygons (makeOrientedBox, makeTriangle);
//   Capsule  a segment swept by a radius.
// Segment and ChainSegment have no area and no mass; they are static geometry. A ChainSegment is
// one link of a chain and knows its neighbours (ghost vertices), which lets the manifold code
// avoid ghost collisions at the joints of a wall made of segments.
//
// The factories check every number is finite and every extent positive and throw InvalidShape
// with a message naming the shape, the field and the value. The checks run in release builds.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "physics/constants.h"
#include "physics/math.h"

namespace rc {

class InvalidShape : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

enum class ShapeType : std::uint8_t { circle, box, polygon, capsule, segment, chainSegment };
inline constexpr int kShapeTypeCount = 6;
const char* shapeTypeName(ShapeType type);

struct Circle {
  Vec2 center{};
  float radius = 0.5f;
};

struct Box {
  Vec2 center{};
  Vec2 halfExtents{0.5f, 0.5f};
};

struct Capsule {
  Vec2 center1{};
  Vec2 center2{};
  float radius = 0.5f;
};

struct Segment {
  Vec2 point1{};
  Vec2 point2{};
};

struct Polygon {
  Vec2 vertices[kMaxPolygonVertices]{};
  Vec2 normals[kMaxPolygonVertices]{};  // normals[i] is the outward normal of edge i -> i+1
  Vec2 centroid{};
  float radius = 0.0f;
  int count = 0;
  // Set by makeOrientedBox only: the half extents along normals[1] and normals[2] (the box's own
  // x and y axes) about the centroid, which lets a ray cross the box as two slabs. Zero for every
  // other polygon, which then takes the general edge-by-edge paths.
  Vec2 boxHalfExtents{};
};

// One link of a chain: segment from point1 to point2, with ghost1 the point before point1 and
// ghost2 the point after point2 (equal to the endpoint itself at an open end). A one-sided link
// collides only with shapes on its right side (outside of a counter-clockwise loop is left).
struct ChainSegment {
  Vec2 ghost1{};
  Segment segment{};
  Vec2 ghost2{};
  bool oneSided = false;
};

struct MassData {
  float mass = 0.0f;
  Vec2 center{};         // centre of mass in the body frame
  float inertia = 0.0f;  // rotational inertia about the centre of mass
  float area = 0.0f;
};

// Factories: validate and build. Each throws InvalidShape on bad input.
Circle makeCircle(Vec2 center, float radius);
Box makeBox(float halfWidth, float halfHeight, Vec2 center = {});
Capsule makeCapsule(Vec2 center1, Vec2 center2, float radius);
Segment makeSegment(Vec2 point1, Vec2 point2);
// Convex hull of the points, in O(n log n): hull vertices closer than kLinearSlop/2 (or 1% of
// the points' extent, when smaller) welded, points collinear within float rounding dropped.
// Throws when the hull is degenerate (fewer than 3 vertices or no area) or would need more than
// kMaxPolygonVertices vertices (the message says how many).
Polygon makePolygon(std::span<const Vec2> points, float radius = 0.0f);
Polygon makeOrientedBox(float halfWidth, float halfHeight, Vec2 center = {}, float angle = 0.0f,
                        float radius = 0.0f);
Polygon makeTriangle(Vec2 a, Vec2 b, Vec2 c, float radius = 0.0f);
Polygon boxToPolygon(const Box& box);
// Chain links along an open polyline (loop = false) or a closed loop. Consecutive duplicate
// points are rejected; a loop needs at least 3 points, an open chain at least 2.
std::vector<ChainSegment> makeChain(std::span<const Vec2> points, bool loop, bool oneSided = false);

// A shape of any type. Trivially copyable; the type tag selects the active member.
struct Shape {
  ShapeType type;
  union {
    Circle circle;
    Box box;
    Polygon polygon;
    Capsule capsule;
    Segment segment;
    ChainSegment chainSegment;
  };

  Shape(const Circle& s) : type(ShapeType::circle), circle(s) {}
  Shape(const Box& s) : type(ShapeType::box), box(s) {}
  Shape(const Polygon& s) : type(ShapeType::polygon), polygon(s) {}
  Shape(const Capsule& s) : type(ShapeType::capsule), capsule(s) {}
  Shape(const Segment& s) : type(ShapeType::segment), segment(s) {}
  Shape(const ChainSegment& s) : type(ShapeType::chainSegment), chainSegment(s) {}

  bool isSolid() const { return type != ShapeType::segment && type != ShapeType::chainSegment; }
};

AABB computeAABB(const Circle& s, const Transform& xf);
AABB computeAABB(const Box& s, const Transform& xf);
AABB computeAABB(const Polygon& s, const Transform& xf);
AABB computeAABB(const Capsule& s, const Transform& xf);
AABB computeAABB(const Segment& s, const Transform& xf);
AABB computeAABB(const Shape& s, const Transform& xf);

// Mass properties at the given density (kg/m^2). Segments and chain links have none.
MassData computeMass(const Circle& s, float density);
MassData computeMass(const Box& s, float density);
MassData computeMass(const Polygon& s, float density);  // exact for rounded polygons
MassData computeMass(const Capsule& s, float density);
MassData computeMass(const Shape& s, float density);
// Mass properties of a compound body: masses add, centres average by mass, inertias move to the
// common centre by the parallel-axis theorem.
MassData combineMass(std::span<const MassData> parts);

// Point containment for solid shapes (boundary counts as inside). Segments contain nothing.
bool containsPoint(const Shape& s, const Transform& xf, Vec2 point);

// Bounding circle in the shape's own frame: the cheap first test of the collision hierarchy.
struct BoundingCircle {
  Vec2 center;
  float radius;
};
BoundingCircle computeBoundingCircle(const Shape& s);

// Throws InvalidShape unless every field of the shape is finite and in range.
void validate(const Shape& s);

}  // namespace rc
