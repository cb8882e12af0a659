#include "game/view/level_view.h"

#include <algorithm>
#include <cmath>

#include "game/view/palette.h"
#include "game/view/shape_draw.h"

namespace game {

std::vector<rc::AABB> fillLoops(std::span<const rc::Segment> links) {
  std::vector<float> heights;
  for (const rc::Segment& s : links) {
    heights.push_back(s.point1.y);
    heights.push_back(s.point2.y);
  }
  std::sort(heights.begin(), heights.end());
  heights.erase(std::unique(heights.begin(), heights.end()), heights.end());
  std::vector<rc::AABB> out;
  std::vector<float> crossings;
  for (std::size_t band = 0; band + 1 < heights.size(); ++band) {
    const float y0 = heights[band], y1 = heights[band + 1];
    const float y = 0.5f * (y0 + y1);
    crossings.clear();
    for (const rc::Segment& s : links) {
      const rc::Vec2 a = s.point1, b = s.point2;
      if ((a.y <= y) == (b.y <= y)) continue;  // does not cross the band's middle
      crossings.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
      if (crossings[k] < crossings[k + 1])
        out.push_back({{crossings[k], y0}, {crossings[k + 1], y1}});
  }
  return out;
}

namespace {

// A box's or a sharp polygon's corners in the world, in order; empty for other shapes.
std::vector<rc::Vec2> polygonOf(const rc::Shape& s, const rc::Transform& xf) {
  std::vector<rc::Vec2> out;
  if (s.type == rc::ShapeType::box) {
    const rc::Vec2 c = s.box.center, h = s.box.halfExtents;
    for (const rc::Vec2 k : {rc::Vec2{-1, -1}, rc::Vec2{1, -1}, rc::Vec2{1, 1}, rc::Vec2{-1, 1}})
      out.push_back(rc::apply(xf, c + rc::Vec2{k.x * h.x, k.y * h.y}));
  } else if (s.type == rc::ShapeType::polygon && s.polygon.radius == 0.0f) {
    for (int i = 0; i < s.polygon.count; ++i)
      out.push_back(rc::apply(xf, s.polygon.vertices[i]));
  }
  return out;
}

}  // namespace

render::DrawList drawLevelStatics(const Level& level, const BuiltLevel& built,
                                  const rc::World& world, const rc::AABB& visible, float pixel) {
  namespace pal = palette;
  render::DrawList list;
  const rc::AABB bounds = level.settings.bounds;
  if (bounds.isValid() && bounds.lower.x < bounds.upper.x && bounds.lower.y < bounds.upper.y) {
    // What the frame shows beyond the map, in up to four bands around it, each a capsule whose
    // round ends lie beyond the frame: a capsule's distance is a few operations a pixel, a
    // polygon's a loop over its edges, and these bands can be a third of the frame.
    const rc::Vec2 grow{visible.upper.x - visible.lower.x, visible.upper.y - visible.lower.y};
    auto band = [&](rc::Vec2 a, rc::Vec2 b, float radius) {
      if (radius > 0.0f) list.capsule(a, b, radius, render::Style::filled(pal::kOutside));
    };
    const float left = 0.5f * (bounds.lower.x - visible.lower.x);
    const float right = 0.5f * (visible.upper.x - bounds.upper.x);
    const float below = 0.5f * (bounds.lower.y - visible.lower.y);
    const float above = 0.5f * (visible.upper.y - bounds.upper.y);
    band({visible.lower.x + left, visible.lower.y - grow.y},
         {visible.lower.x + left, visible.upper.y + grow.y}, left);
    band({visible.upper.x - right, visible.lower.y - grow.y},
         {visible.upper.x - right, visible.upper.y + grow.y}, right);
    band({visible.lower.x - grow.x, visible.lower.y + below},
         {visible.upper.x + grow.x, visible.lower.y + below}, below);
    band({visible.lower.x - grow.x, visible.upper.y - above},
         {visible.upper.x + grow.x, visible.upper.y - above}, above);
    // The tile grid, when its lines would be at least 12 pixels apart (denser is noise, and
    // costs as much to draw as the rest of the level).
    const float tw = level.settings.tileWidth, th = level.settings.tileHeight;
    if (tw >= 12.0f * pixel && th >= 12.0f * pixel) {
      for (float x = bounds.lower.x + tw; x < bounds.upper.x - 0.5f * tw; x += tw)
        list.segment({x, bounds.lower.y}, {x, bounds.upper.y}, 1.0f, pal::kGrid);
      for (float y = bounds.upper.y - th; y > bounds.lower.y + 0.5f * th; y -= th)
        list.segment({bounds.lower.x, y}, {bounds.upper.x, y}, 1.0f, pal::kGrid);
    }
  }
  const rc::Vec2 seam{0.5f * pixel, 0.5f * pixel};
  for (std::size_t i = 0; i < level.objects.size() && i < built.bodies.size(); ++i) {
    const LevelObject& o = level.objects[i];
    const rc::BodyId body = built.bodies[i];
    if (!world.isValid(body) || world.type(body) != rc::BodyType::staticBody) continue;
    if (o.kind == LevelObjectKind::prop) continue;  // may be destroyed: drawn every frame
    const rc::Transform xf = world.transform(body);
    if (o.kind == LevelObjectKind::trigger) {
      const bool hurts =
          std::any_of(built.triggers.begin(), built.triggers.end(), [&](const BuiltTrigger& t) {
            return t.object == i && (t.action == "kill" || t.action == "hurt");
          });
      const render::Color c = hurts ? pal::kHazard : pal::kZone;
      for (const rc::Shape& s : o.shapes)
        drawShape(list, s, xf, render::Style::both(pal::fade(c, 0.16f), pal::fade(c, 0.7f), 1.5f));
      continue;
    }
    // Merged tiles: their one-sided loops filled, then edged; every other shape as itself.
    std::vector<rc::Segment> loops;
    for (const rc::Shape& s : o.shapes)
      if (s.type == rc::ShapeType::chainSegment && s.chainSegment.oneSided)
        loops.push_back({rc::apply(xf, s.chainSegment.segment.point1),
                         rc::apply(xf, s.chainSegment.segment.point2)});
    for (const rc::AABB& r : fillLoops(loops))
      list.rect({r.lower - seam, r.upper + seam}, render::Style::filled(pal::kWall));
    for (const rc::Segment& link : loops)
      list.segment(link.point1, link.point2, 1.5f, pal::kWallEdge);
    // Boxes and polygons filled, then edged where no other piece of the wall continues them: a
    // concave wall split into convex pieces reads as one outline, its inner seams hidden.
    std::vector<rc::Segment> edges;
    for (const rc::Shape& s : o.shapes) {
      if (s.type == rc::ShapeType::chainSegment && s.chainSegment.oneSided) continue;
      const std::vector<rc::Vec2> corners = polygonOf(s, xf);
      if (!corners.empty()) {
        list.polygon(corners, render::Style::filled(pal::kWall));
        for (std::size_t k = 0; k < corners.size(); ++k)
          edges.push_back({corners[k], corners[(k + 1) % corners.size()]});
        continue;
      }
      const bool line = s.type == rc::ShapeType::segment || s.type == rc::ShapeType::chainSegment;
      drawShape(list, s, xf,
                line ? render::Style::filled(pal::kWallEdge)
                     : render::Style::both(pal::kWall, pal::kWallEdge, 1.5f),
                3.0f);
    }
    for (const bool inner : {true, false})
      for (const rc::Segment& e : edges) {
        const bool shared = std::any_of(edges.begin(), edges.end(), [&](const rc::Segment& f) {
          return rc::distanceSquared(e.point1, f.point2) < 1e-8f &&
                 rc::distanceSquared(e.point2, f.point1) < 1e-8f;
        });
        if (shared == inner)
          list.segment(e.point1, e.point2, 1.5f, inner ? pal::kWall : pal::kWallEdge);
      }
  }
  return list;
}

}  // namespace game
