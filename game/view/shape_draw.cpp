#include "game/view/shape_draw.h"

#include <vector>

namespace game {

void drawShape(render::DrawList& list, const rc::Shape& s, const rc::Transform& xf,
               const render::Style& style, float lineWidthPixels) {
  const render::Color line = style.fill.a > 0 ? style.fill : style.stroke;
  switch (s.type) {
    case rc::ShapeType::circle:
      list.circle(rc::apply(xf, s.circle.center), s.circle.radius, style);
      break;
    case rc::ShapeType::box: {
      const rc::Vec2 c = s.box.center, h = s.box.halfExtents;
      const rc::Vec2 corners[4] = {
          rc::apply(xf, c + rc::Vec2{-h.x, -h.y}), rc::apply(xf, c + rc::Vec2{h.x, -h.y}),
          rc::apply(xf, c + rc::Vec2{h.x, h.y}), rc::apply(xf, c + rc::Vec2{-h.x, h.y})};
      list.polygon(corners, style);
      break;
    }
    case rc::ShapeType::polygon: {
      std::vector<rc::Vec2> points;
      for (int i = 0; i < s.polygon.count; ++i)
        points.push_back(rc::apply(xf, s.polygon.vertices[i]));
      list.polygon(points, style, s.polygon.radius);
      break;
    }
    case rc::ShapeType::capsule:
      list.capsule(rc::apply(xf, s.capsule.center1), rc::apply(xf, s.capsule.center2),
                   s.capsule.radius, style);
      break;
    case rc::ShapeType::segment:
      list.segment(rc::apply(xf, s.segment.point1), rc::apply(xf, s.segment.point2),
                   lineWidthPixels, line);
      break;
    case rc::ShapeType::chainSegment:
      list.segment(rc::apply(xf, s.chainSegment.segment.point1),
                   rc::apply(xf, s.chainSegment.segment.point2), lineWidthPixels, line);
      break;
  }
}

}  // namespace game
