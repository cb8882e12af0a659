#include "game/view/scene_view.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "game/view/shape_draw.h"

namespace game {
namespace {

using render::Color;

// A stable colour per body from its index, so a body keeps its colour from frame to frame;
// darker while asleep.
Color bodyColor(const rc::World& world, rc::BodyId id) {
  static constexpr Color kPalette[] = {
      {230, 90, 90, 255},   {240, 160, 70, 255},  {230, 210, 80, 255},  {150, 220, 90, 255},
      {80, 200, 140, 255},  {80, 200, 210, 255},  {90, 150, 235, 255},  {140, 110, 235, 255},
      {200, 100, 220, 255}, {235, 110, 170, 255}, {180, 180, 120, 255}, {120, 190, 190, 255}};
  switch (world.type(id)) {
    case rc::BodyType::staticBody:
      return {110, 115, 125, 255};
    case rc::BodyType::kinematicBody:
      return {70, 130, 230, 255};
    case rc::BodyType::dynamicBody:
      break;
  }
  Color c = kPalette[static_cast<std::size_t>(id.index) % std::size(kPalette)];
  if (!world.isAwake(id)) {
    c.r = static_cast<std::uint8_t>(c.r / 2);
    c.g = static_cast<std::uint8_t>(c.g / 2);
    c.b = static_cast<std::uint8_t>(c.b / 2);
  }
  return c;
}

}  // namespace

render::Frame drawWorld(const rc::World& world, long step, const ViewOptions& options) {
  render::Frame frame;
  frame.showOverlay = options.overlay;
  const render::Color outline{20, 20, 24, 255};
  for (rc::BodyId id : world.bodies()) {
    const rc::Transform xf = world.transform(id);
    const Color c = bodyColor(world, id);
    for (rc::ShapeId sid : world.shapesOf(id)) {
      const rc::Shape& s = world.shape(sid);
      const render::Style style = world.isSensor(sid) ? render::Style::outlined(c, 1.5f)
                                                      : render::Style::both(c, outline, 1.0f);
      drawShape(frame.world, s, xf, style);
      if (options.overlay)
        frame.overlay.rect(rc::computeAABB(s, xf),
                           render::Style::outlined({255, 255, 255, 60}, 1.0f));
    }
    if (options.overlay && world.type(id) == rc::BodyType::dynamicBody && world.isAwake(id)) {
      const rc::Vec2 p = world.worldCenter(id), v = world.linearVelocity(id);
      if (rc::lengthSquared(v) > 1e-4f)
        frame.overlay.arrow(p, p + 0.1f * v, 1.5f, render::colors::kYellow, 6.0f);
    }
  }
  if (options.overlay) {
    // Quadtree cells that hold something (moving tree in cyan, static in grey), then body ids.
    for (const rc::Quadtree::OccupiedCell& cell : world.broadphase().occupiedCells())
      frame.overlay.rect(
          cell.bounds,
          render::Style::outlined(
              cell.isStatic ? Color{160, 160, 160, 50} : Color{60, 200, 220, 70}, 1.0f));
    for (rc::BodyId id : world.bodies())
      if (world.type(id) != rc::BodyType::staticBody)
        frame.overlay.text(world.worldCenter(id), std::to_string(id.index), 10,
                           {255, 255, 255, 200}, render::HAlign::kCenter, render::VAlign::kMiddle);
    for (const rc::World::ContactPointView& cp : world.contactPoints()) {
      frame.overlay.dot(cp.point, 2.5f, render::colors::kRed);
      frame.overlay.arrow(cp.point, cp.point + 0.3f * cp.normal, 1.0f, render::colors::kRed, 4.0f);
    }
  }
  char line[160];
  std::snprintf(line, sizeof line, "step %ld  t = %.2f s  bodies %d  awake %d  contacts %d", step,
                world.time(), world.bodyCount(), world.awakeBodyCount(),
                world.touchingContactCount());
  if (!options.caption.empty()) frame.hud.text({8, 6}, options.caption, 14, render::colors::kWhite);
  frame.hud.text({8, options.caption.empty() ? 6.0f : 24.0f}, line, 14, {220, 220, 220, 255});
  return frame;
}

render::Camera cameraForWorld(const rc::World& world, int width, int height) {
  // What moves, if anything does (a long ground would otherwise shrink the scene to a strip),
  // with a margin of a quarter of its size around it.
  auto boundsOf = [&](bool movingOnly, rc::AABB& box) {
    bool any = false;
    for (rc::BodyId id : world.bodies()) {
      if (movingOnly && world.type(id) == rc::BodyType::staticBody) continue;
      for (rc::ShapeId sid : world.shapesOf(id)) {
        const rc::AABB b = rc::computeAABB(world.shape(sid), world.transform(id));
        box = any ? rc::unionOf(box, b) : b;
        any = true;
      }
    }
    return any;
  };
  rc::AABB box{};
  if (!boundsOf(true, box) && !boundsOf(false, box)) box = {{-10, -10}, {10, 10}};
  const rc::Vec2 grow = 0.25f * (box.upper - box.lower) + rc::Vec2{1, 1};
  // 8 pixels of margin, less in a small picture (a 16x16 frame, the smallest --size takes,
  // would have none left), as the match view does.
  const float margin = std::min(8.0f, 0.05f * static_cast<float>(std::min(width, height)));
  return render::Camera::fit({box.lower - grow, box.upper + grow}, width, height, margin);
}

}  // namespace game
