#include "game/level/level_builder.h"

#include <algorithm>

#include "game/level/level_error.h"

namespace game {

rc::WorldDef levelWorldDef(const Level& level, rc::WorldDef base) {
  base.gravity = level.settings.gravity;
  const rc::AABB& b = level.settings.bounds;
  const float side = std::max(b.upper.x - b.lower.x, b.upper.y - b.lower.y);
  const float half = 0.75f * side + 1.0f;
  const rc::Vec2 c = b.center();
  base.bounds = {{c.x - half, c.y - half}, {c.x + half, c.y + half}};
  return base;
}

BuiltLevel buildLevel(const Level& level, rc::World& world, const LevelFilters& filters) {
  BuiltLevel built;
  built.bodies.reserve(level.objects.size());
  for (std::size_t i = 0; i < level.objects.size(); ++i) {
    const LevelObject& o = level.objects[i];
    const std::uint64_t userData = levelUserData(o.kind, i);
    rc::BodyDef body;
    body.type = o.bodyType;
    body.position = o.position;
    body.angle = o.angle;
    body.linearDamping = o.linearDamping;
    body.angularDamping = o.angularDamping;
    body.userData = userData;
    rc::ShapeDef shape;
    shape.density = o.material.density;
    shape.friction = o.material.friction;
    shape.restitution = o.material.restitution;
    shape.isSensor = o.kind == LevelObjectKind::trigger;
    shape.filter = o.kind == LevelObjectKind::prop      ? filters.props
                   : o.kind == LevelObjectKind::trigger ? filters.triggers
                                                        : filters.walls;
    shape.userData = userData;
    try {
      const rc::BodyId id = world.createBody(body);
      for (const rc::Shape& s : o.shapes)
        world.createShape(id, s, shape);
      built.bodies.push_back(id);
    } catch (const std::invalid_argument& e) {  // rc::InvalidDefinition, rc::InvalidShape
      const std::string what =
          o.kind == LevelObjectKind::tiles
              ? "the tiles of layer " + quoteName(o.layer)
              : "layer " + quoteName(o.layer) + ": object " + std::to_string(o.tiledId);
      throw LevelError(level.source + ": " + what + ": the world refuses it: " + e.what());
    }
  }
  built.settings = level.settings;
  built.spawns = level.spawns;
  built.pickups = level.pickups;
  for (const LevelTrigger& t : level.triggers)
    built.triggers.push_back({t.object, built.bodies[t.object], t.action, t.damagePerSecond,
                              level.objects[t.object].properties});
  built.paths = level.paths;
  built.markers = level.markers;
  return built;
}

}  // namespace game
