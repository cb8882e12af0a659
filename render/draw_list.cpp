#include "render/draw_list.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace render {

namespace {

[[noreturn]] void fail(const char* what, const std::string& detail) {
  throw std::invalid_argument(std::string("render: DrawList::") + what + ": " + detail);
}

std::string str(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(v));
  return buffer;
}

void checkPoint(const char* what, const char* name, rc::Vec2 p) {
  if (!rc::isFinite(p))
    fail(what, std::string(name) + " must be finite, got (" + str(p.x) + ", " + str(p.y) + ")");
}

void checkSize(const char* what, const char* name, float v) {
  if (!(std::isfinite(v) && v >= 0.0f))
    fail(what, std::string(name) + " must be finite and >= 0, got " + str(v));
}

void checkStyle(const char* what, const Style& style) {
  checkSize(what, "stroke width", style.strokePixels);
}

Shape styled(ShapeKind kind, const Style& style) {
  Shape s;
  s.kind = kind;
  s.fill = style.fill;
  s.stroke = style.strokePixels > 0.0f ? style.stroke : colors::kTransparent;
  s.strokePixels = style.strokePixels;
  return s;
}

}  // namespace

void DrawList::circle(rc::Vec2 center, float radius, const Style& style) {
  checkPoint("circle", "centre", center);
  checkSize("circle", "radius", radius);
  checkStyle("circle", style);
  Shape s = styled(ShapeKind::kCircle, style);
  s.a = center;
  s.b = center;
  s.radius = radius;
  shapes.push_back(s);
}

void DrawList::dot(rc::Vec2 center, float radiusPixels, Color color) {
  checkPoint("dot", "centre", center);
  checkSize("dot", "radius", radiusPixels);
  Shape s = styled(ShapeKind::kCircle, Style::filled(color));
  s.a = center;
  s.b = center;
  s.radiusPixels = radiusPixels;
  shapes.push_back(s);
}

void DrawList::capsule(rc::Vec2 a, rc::Vec2 b, float radius, const Style& style) {
  checkPoint("capsule", "first centre", a);
  checkPoint("capsule", "second centre", b);
  checkSize("capsule", "radius", radius);
  checkStyle("capsule", style);
  Shape s = styled(ShapeKind::kCapsule, style);
  s.a = a;
  s.b = b;
  s.radius = radius;
  shapes.push_back(s);
}

void DrawList::polygon(std::span<const rc::Vec2> vertices, const Style& style, float radius) {
  const int n = static_cast<int>(vertices.size());
  if (n < 3) fail("polygon", "needs at least 3 vertices, got " + std::to_string(n));
  checkSize("polygon", "radius", radius);
  checkStyle("polygon", style);
  rc::AABB box{vertices[0], vertices[0]};
  float area2 = 0.0f;
  for (int i = 0; i < n; ++i) {
    checkPoint("polygon", ("vertex " + std::to_string(i)).c_str(), vertices[i]);
    box.lower = rc::min(box.lower, vertices[i]);
    box.upper = rc::max(box.upper, vertices[i]);
    area2 += rc::cross(vertices[i], vertices[rc::nextIndex(i, n)]);
  }
  // Convex: every turn has the sign of the winding (collinear vertices allowed).
  const float sign = area2 >= 0.0f ? 1.0f : -1.0f;
  for (int i = 0; i < n; ++i) {
    rc::Vec2 p = vertices[i];
    rc::Vec2 q = vertices[rc::nextIndex(i, n)];
    rc::Vec2 r = vertices[rc::nextIndex(rc::nextIndex(i, n), n)];
    float turn = sign * rc::cross(q - p, r - q);
    float scale = rc::lengthSquared(q - p) + rc::lengthSquared(r - q);
    if (turn < -1e-6f * scale) {
      fail("polygon", "vertices must form a convex polygon (vertex " +
                          std::to_string(rc::nextIndex(i, n)) + " turns the other way)");
    }
  }
  Shape s = styled(ShapeKind::kPolygon, style);
  s.a = box.lower;
  s.b = box.upper;
  s.radius = radius;
  s.firstPoint = static_cast<std::uint32_t>(points.size());
  s.pointCount = static_cast<std::uint32_t>(n);
  // The shader wants counter-clockwise vertices.
  if (sign > 0.0f) {
    points.insert(points.end(), vertices.begin(), vertices.end());
  } else {
    points.insert(points.end(), vertices.rbegin(), vertices.rend());
  }
  shapes.push_back(s);
}

void DrawList::rect(const rc::AABB& box, const Style& style) {
  if (!box.isValid()) fail("rect", "box must be finite with lower <= upper");
  const rc::Vec2 corners[4] = {
      box.lower, {box.upper.x, box.lower.y}, box.upper, {box.lower.x, box.upper.y}};
  polygon(corners, style);
}

void DrawList::segment(rc::Vec2 a, rc::Vec2 b, float widthPixels, Color color) {
  checkPoint("segment", "start", a);
  checkPoint("segment", "end", b);
  checkSize("segment", "width", widthPixels);
  Shape s = styled(ShapeKind::kCapsule, Style::filled(color));
  s.a = a;
  s.b = b;
  s.radiusPixels = 0.5f * widthPixels;
  shapes.push_back(s);
}

void DrawList::polyline(std::span<const rc::Vec2> line, float widthPixels, Color color,
                        bool closed) {
  const std::size_t n = line.size();
  if (n < 2) fail("polyline", "needs at least 2 points, got " + std::to_string(n));
  // One round-capped segment per link: joins come out round. (Translucent lines show their joins
  // twice as dark; a joined-stroke shader can come later if that matters.)
  for (std::size_t i = 0; i + 1 < n; ++i)
    segment(line[i], line[i + 1], widthPixels, color);
  if (closed && n > 2) segment(line[n - 1], line[0], widthPixels, color);
}

void DrawList::arrow(rc::Vec2 from, rc::Vec2 to, float widthPixels, Color color, float headPixels) {
  checkPoint("arrow", "start", from);
  checkPoint("arrow", "tip", to);
  checkSize("arrow", "width", widthPixels);
  checkSize("arrow", "head length", headPixels);
  Shape s = styled(ShapeKind::kArrow, Style::filled(color));
  s.a = from;
  s.b = to;
  s.radiusPixels = 0.5f * widthPixels;
  s.headPixels = headPixels;
  shapes.push_back(s);
}

void DrawList::text(rc::Vec2 at, std::string string, float sizePixels, Color color, HAlign halign,
                    VAlign valign) {
  checkPoint("text", "position", at);
  if (!(std::isfinite(sizePixels) && sizePixels > 0.0f)) {
    fail("text", "size must be finite and > 0, got " + str(sizePixels));
  }
  texts.push_back(Text{at, std::move(string), sizePixels, color, halign, valign});
}

void DrawList::sprite(SpriteId image, rc::Vec2 center, rc::Vec2 size, float angle, Color tint,
                      const SpriteRect& source) {
  if (!image.valid()) fail("sprite", "no image (a SpriteId from Renderer::loadSprite)");
  checkPoint("sprite", "centre", center);
  if (!(rc::isFinite(size) && size.x > 0.0f && size.y > 0.0f)) {
    fail("sprite", "size must be finite and > 0, got (" + str(size.x) + ", " + str(size.y) + ")");
  }
  if (!std::isfinite(angle)) fail("sprite", "angle must be finite, got " + str(angle));
  checkSize("sprite", "source x", source.x);
  checkSize("sprite", "source y", source.y);
  checkSize("sprite", "source width", source.width);
  checkSize("sprite", "source height", source.height);
  if ((source.width > 0.0f) != (source.height > 0.0f)) {
    fail("sprite", "source width and height must both be > 0, or both 0 for the whole image");
  }
  sprites.push_back(
      Sprite{center, size, angle, source, tint, image, static_cast<std::uint32_t>(shapes.size())});
}

}  // namespace render
