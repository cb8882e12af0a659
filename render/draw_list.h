// A frame description: plain data that the caller builds and the Renderer draws.
//
// A DrawList holds shapes in one coordinate space and draws them in the order they were added
// (later on top), all of them in one instanced draw call; then its text, on top of its shapes,
// in a second call. A Frame stacks three lists: the world (camera space, y up), a debug overlay
// drawn only when switched on, and a HUD in pixel space (y down, origin top-left).
//
// Units: geometry (centres, radii, vertices) is in the list's space (world units for the world
// and overlay, pixels for the HUD). Stroke widths, line widths, arrow heads and text sizes are
// always in pixels, so a debug line stays one pixel wide at any zoom; `radiusPixels` adds a
// pixel-sized radius on top of the geometric one (a contact point as a 3-pixel dot).
//
// Outlines lie inside the shape's edge: a circle of radius r with a 2 px outline covers exactly
// the pixels a filled one would. A fill with alpha 0 draws the outline alone.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "physics/math.h"
#include "render/color.h"

namespace render {

enum class ShapeKind : std::uint32_t { kCircle = 0, kCapsule = 1, kPolygon = 2, kArrow = 3 };

// One drawn shape; also the per-instance record uploaded to the GPU (hence the fixed layout).
struct Shape {
  rc::Vec2 a{};            // circle centre, capsule/segment/arrow start, polygon bounds lower
  rc::Vec2 b{};            // capsule/segment end, arrow tip, polygon bounds upper
  float radius = 0.0f;     // in the list's units; polygons: rounding radius
  float radiusPixels = 0;  // added to radius, in pixels (half a line's width)
  float strokePixels = 0;  // outline width inside the edge; 0 = no outline
  float headPixels = 0;    // arrows: head length (the head is as wide as it is long)
  Color fill;              //
  Color stroke;            //
  ShapeKind kind = ShapeKind::kCircle;
  std::uint32_t firstPoint = 0;  // polygons: vertices points[first, first + count), CCW
  std::uint32_t pointCount = 0;
};
static_assert(sizeof(Shape) == 52, "Shape is the GPU instance layout");

enum class HAlign : std::uint8_t { kLeft, kCenter, kRight };
enum class VAlign : std::uint8_t { kTop, kMiddle, kBaseline, kBottom };

struct Text {
  rc::Vec2 at{};             // anchor point, in the list's units
  std::string text;          // UTF-8; '\n' starts a new line; glyphs missing from the font show '?'
  float sizePixels = 14.0f;  // line height from descender to ascender
  Color color = colors::kWhite;
  HAlign halign = HAlign::kLeft;
  VAlign valign = VAlign::kTop;
};

// Fill and outline of a closed shape.
struct Style {
  Color fill = colors::kWhite;
  Color stroke = colors::kTransparent;
  float strokePixels = 0.0f;

  static Style filled(Color c) { return {c, colors::kTransparent, 0.0f}; }
  static Style outlined(Color c, float widthPixels = 1.0f) {
    return {colors::kTransparent, c, widthPixels};
  }
  static Style both(Color fill, Color stroke, float widthPixels = 1.0f) {
    return {fill, stroke, widthPixels};
  }
};

class DrawList {
 public:
  std::vector<Shape> shapes;
  std::vector<rc::Vec2> points;  // polygon vertices, referred to by Shape::firstPoint
  std::vector<Text> texts;

  // Every adder checks its input and throws std::invalid_argument naming the bad value
  // (non-finite coordinates, negative sizes, a polygon that is not convex).
  void circle(rc::Vec2 center, float radius, const Style& style);
  // A dot of a fixed size on screen whatever the zoom (contact points, hit points).
  void dot(rc::Vec2 center, float radiusPixels, Color color);
  void capsule(rc::Vec2 a, rc::Vec2 b, float radius, const Style& style);
  // A convex polygon, vertices in either winding (3 or more, no three collinear needed),
  // optionally rounded by `radius`.
  void polygon(std::span<const rc::Vec2> vertices, const Style& style, float radius = 0.0f);
  // Axis-aligned rectangle (an AABB, a HUD bar).
  void rect(const rc::AABB& box, const Style& style);
  // Lines with round caps, `widthPixels` wide.
  void segment(rc::Vec2 a, rc::Vec2 b, float widthPixels, Color color);
  void polyline(std::span<const rc::Vec2> points, float widthPixels, Color color,
                bool closed = false);
  // From `from` to the tip at `to`; the head is `headPixels` long and wide.
  void arrow(rc::Vec2 from, rc::Vec2 to, float widthPixels, Color color, float headPixels = 10.0f);
  void text(rc::Vec2 at, std::string text, float sizePixels, Color color,
            HAlign halign = HAlign::kLeft, VAlign valign = VAlign::kTop);

  void clear() {
    shapes.clear();
    points.clear();
    texts.clear();
  }
  bool empty() const { return shapes.empty() && texts.empty(); }
};

struct Frame {
  Color background = colors::kDarkGray;  // frames are opaque: its alpha is ignored
  DrawList world;
  DrawList overlay;  // debug overlay, world units
  bool showOverlay = true;
  DrawList hud;  // pixels, y down
};

}  // namespace render
