// A frame description: plain data that the caller builds and the Renderer draws.
//
// A DrawList holds shapes and sprites in one coordinate space and draws them in the order they
// were added (later on top), whatever their kind; then its text, on top of both. Shapes go in one
// instanced draw call and sprites in one per texture; when a list interleaves shapes and sprites
// (or sprites of different images), each run of one kind and one image is a call of its own, so
// adding sprites of one image together, apart from the shapes, keeps a frame to a few calls. A
// Frame stacks three lists: the world (camera space, y up), a debug overlay drawn only when
// switched on, and a HUD in pixel space (y down, origin top-left).
//
// Units: geometry (centres, radii, vertices) is in the list's space (world units for the world
// and overlay, pixels for the HUD). Stroke widths, line widths, arrow heads and text sizes are
// always in pixels, so a debug line stays one pixel wide at any zoom; `radiusPixels` adds a
// pixel-sized radius on top of the geometric one (a contact point as a 3-pixel dot).
//
// Outlines lie inside the shape's edge: a circle of radius r with a 2 px outline covers exactly
// the pixels a filled one would. A fill with alpha 0 draws the outline alone.
//
// Sprites: an image loaded by the Renderer (Renderer::loadSprite), drawn as a rectangle of a
// given size in the list's units around its centre, turned by an angle (radians, counter-clockwise
// as seen in the picture, in every layer; the image's top faces the top of the picture at angle
// 0), its texels multiplied by a tint (white leaves them as they are; the tint's alpha fades the
// sprite). Its edge is anti-aliased like a shape's.
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

// An image the Renderer holds (Renderer::loadSprite); valid only with the Renderer that made it.
// Zero is "no image".
struct SpriteId {
  std::uint32_t value = 0;
  bool valid() const { return value != 0; }
  friend bool operator==(SpriteId, SpriteId) = default;
};

// Part of a sprite's image, in its pixels from its top-left corner; all zero: the whole image.
struct SpriteRect {
  float x = 0.0f;
  float y = 0.0f;
  float width = 0.0f;
  float height = 0.0f;
};

// One drawn sprite; also the per-instance record uploaded to the GPU.
struct Sprite {
  rc::Vec2 center{};
  rc::Vec2 size{};      // width and height in the list's units
  float angle = 0.0f;   // radians, counter-clockwise in the picture
  SpriteRect source{};  // part of the image; all zero: the whole image
  Color tint = colors::kWhite;
  SpriteId image{};
  std::uint32_t shapesBefore = 0;  // draw order: on top of the list's first shapesBefore shapes
};
static_assert(sizeof(Sprite) == 48, "Sprite is the GPU instance layout");

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
  std::vector<Sprite> sprites;

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
  // `size` > 0 in the list's units; `source` must lie inside the image (checked when drawn).
  void sprite(SpriteId image, rc::Vec2 center, rc::Vec2 size, float angle = 0.0f,
              Color tint = colors::kWhite, const SpriteRect& source = {});

  void clear() {
    shapes.clear();
    points.clear();
    texts.clear();
    sprites.clear();
  }
  bool empty() const { return shapes.empty() && texts.empty() && sprites.empty(); }
};

struct Frame {
  Color background = colors::kDarkGray;  // frames are opaque: its alpha is ignored
  DrawList world;
  DrawList overlay;  // debug overlay, world units
  bool showOverlay = true;
  DrawList hud;  // pixels, y down
};

}  // namespace render
