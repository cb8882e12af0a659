#include "game/level/level_loader.h"

#include "game/level/convex_decomposition.h"
#include "game/level/level_geometry.h"
#include "game/level/level_properties.h"
#include "game/level/tile_walls.h"
#include "game/level/tiled_reader.h"

namespace game {

namespace {

// Where (x, y) sits on a tile object, as fractions of its size from the top-left.
struct Anchor {
  double x = 0, y = 0;
};

Anchor tileObjectAnchor(const std::string& alignment, const ErrorContext& at) {
  if (alignment == "unspecified" || alignment == "bottomleft") return {0, 1};
  if (alignment == "topleft") return {0, 0};
  if (alignment == "top") return {0.5, 0};
  if (alignment == "topright") return {1, 0};
  if (alignment == "left") return {0, 0.5};
  if (alignment == "center") return {0.5, 0.5};
  if (alignment == "right") return {1, 0.5};
  if (alignment == "bottom") return {0.5, 1};
  if (alignment == "bottomright") return {1, 1};
  at.fail("unknown object alignment " + quoteName(alignment));
}

enum class Role : std::uint8_t { wall, prop, trigger, path };

Role roleOf(const std::string& type, TiledShape shape, const ErrorContext& at) {
  if (type.empty() || type == "wall") return Role::wall;
  if (type == "crate" || type == "barrel" || type == "prop") return Role::prop;
  if (type == "trigger") return Role::trigger;
  if (type == "path" && (shape == TiledShape::polyline || shape == TiledShape::polygon))
    return Role::path;
  at.fail("unknown type " + quoteName(type) + " for a " + tiledShapeName(shape) +
          " (known: wall, crate, barrel, prop, trigger; path for polylines and polygons; "
          "player, bot, pickup for points)");
}

// The body pose and shapes of an object, in its body's frame.
struct Placed {
  rc::Vec2 position{};
  float angle = 0.0f;
  std::vector<rc::Shape> shapes;
};

Placed placeBoxOrEllipse(const TiledObject& o, Anchor anchor, bool ellipse, const MapUnits& u) {
  if (o.width <= 0 || o.height <= 0) throw rc::InvalidShape("has no width or height");
  const Turn turn = turnFromTiled(o.rotation);
  Placed p;
  // Tiled turns the object about (x, y); its centre is half its size away from the anchor.
  p.position = u.point(o.x, o.y) +
               turned(turn, u.offset((0.5 - anchor.x) * o.width, (0.5 - anchor.y) * o.height));
  p.angle = bodyAngle(turn);
  float hw = u.length(o.width / 2), hh = u.length(o.height / 2);
  if (turn.exact && turn.quarters % 2 == 1) std::swap(hw, hh);
  p.shapes.push_back(ellipse ? ellipseShape({0, 0}, hw, hh) : rc::Shape(rc::makeBox(hw, hh)));
  return p;
}

// Polygon and polyline points about the body origin at (x, y), turned.
std::vector<rc::Vec2> localPoints(const TiledObject& o, const Turn& turn, const MapUnits& u) {
  std::vector<rc::Vec2> out;
  for (const TiledPoint& q : o.points)
    out.push_back(turned(turn, u.offset(q.x, q.y)));
  return out;
}

Placed placeOutline(const TiledObject& o, const MapUnits& u) {
  const Turn turn = turnFromTiled(o.rotation);
  Placed p;
  p.position = u.point(o.x, o.y);
  p.angle = bodyAngle(turn);
  // Quarter turns go into the points; any other turn is the body's angle.
  std::vector<rc::Vec2> points = localPoints(o, turn.exact ? turn : Turn{}, u);
  if (o.shape == TiledShape::polygon) {
    appendPolygonShapes(points, p.shapes);
    return p;
  }
  // A polyline that ends where it began is a closed loop, solid from both sides.
  const bool closed = points.size() >= 4 && points.front() == points.back();
  if (closed) points.pop_back();
  for (const rc::ChainSegment& link : rc::makeChain(points, closed, false))
    p.shapes.push_back(link);
  return p;
}

struct LoadState {
  const TiledMap& map;
  MapUnits units;
  Level& level;
};

void loadPoint(const TiledObject& o, const std::string& type, const TiledProperties& props,
               LoadState& s, const ErrorContext& at) {
  const rc::Vec2 position = s.units.point(o.x, o.y);
  if (type == "player" || type == "bot") {
    LevelSpawn spawn;
    spawn.kind = type == "player" ? SpawnKind::player : SpawnKind::bot;
    spawn.tiledId = o.id;
    spawn.name = o.name;
    spawn.position = position;
    spawn.facing = radiansFromTiled(floatProperty(props, "facing", 0.0f, -1e6f, 1e6f, at));
    spawn.team = intProperty(props, "team", defaultTeam(spawn.kind), 0, 255, at);
    spawn.properties = props;
    s.level.spawns.push_back(std::move(spawn));
  } else if (type == "pickup") {
    LevelPickup pickup;
    pickup.tiledId = o.id;
    pickup.name = o.name;
    pickup.item = stringProperty(props, "item", "", at);
    if (pickup.item.empty()) at.fail("a pickup needs a string property 'item' (health, ammo, ...)");
    pickup.amount = floatProperty(props, "amount", 0.0f, 0.0f, 1e9f, at);
    pickup.respawn = floatProperty(props, "respawn", 0.0f, 0.0f, 1e6f, at);
    pickup.radius = floatProperty(props, "radius", 0.5f, 1e-3f, 1e3f, at);
    pickup.position = position;
    pickup.properties = props;
    s.level.pickups.push_back(std::move(pickup));
  } else {
    LevelMarker marker;
    marker.tiledId = o.id;
    marker.name = o.name;
    marker.type = type;
    marker.position = position;
    marker.properties = props;
    s.level.markers.push_back(std::move(marker));
  }
}

void loadPath(const TiledObject& o, const TiledProperties& props, LoadState& s,
              const ErrorContext& at) {
  LevelPath path;
  path.tiledId = o.id;
  path.name = o.name;
  path.properties = props;
  const Turn turn = turnFromTiled(o.rotation);
  const rc::Vec2 origin = s.units.point(o.x, o.y);
  for (const rc::Vec2 v : localPoints(o, turn, s.units))
    path.points.push_back(origin + v);
  path.loop = o.shape == TiledShape::polygon || boolProperty(props, "loop", false, at);
  if (path.points.size() < 2) at.fail("a path needs at least 2 points");
  s.level.paths.push_back(std::move(path));
}

void loadObject(const TiledLayer& layer, const TiledObject& o, LoadState& s,
                const ErrorContext& layerAt) {
  const ErrorContext at = layerAt.in("object " + std::to_string(o.id));
  if (o.shape == TiledShape::text) return;  // a note for the designer
  TiledProperties props = o.properties;
  std::string type = o.type;
  Anchor anchor;
  if (o.shape == TiledShape::tile) {
    const TileRef ref = findTile(s.map, o.gid);
    if (ref.tileset == nullptr)
      at.fail("tile object's gid " + std::to_string(o.gid) + " belongs to no tileset of the map");
    if (const TiledTile* tile = ref.tileset->tile(ref.localId)) {
      props.inherit(tile->properties);
      if (type.empty()) type = tile->type;
    }
    anchor = tileObjectAnchor(ref.tileset->objectAlignment, at);
  }
  props.inherit(layer.properties);

  if (o.shape == TiledShape::point) {
    loadPoint(o, type, props, s, at);
    return;
  }
  const Role role = roleOf(type, o.shape, at);
  if (role == Role::path) {
    loadPath(o, props, s, at);
    return;
  }
  LevelObject object;
  object.tiledId = o.id;
  object.layer = layer.name;
  object.name = o.name;
  object.type = type;
  object.properties = props;
  const bool dynamic = boolProperty(props, "dynamic", role == Role::prop, at);
  LevelMaterial defaults;
  if (role == Role::prop) defaults.hard = false;  // wood and thin metal: shots go in, not off
  object.material = readMaterial(props, defaults, at);
  if (role == Role::trigger) {
    object.kind = LevelObjectKind::trigger;
  } else if (role == Role::prop || dynamic) {
    object.kind = LevelObjectKind::prop;
    object.bodyType = dynamic ? rc::BodyType::dynamicBody : rc::BodyType::staticBody;
    // A top-down floor's friction, as damping: a crate pushed at 3 m/s stops within a metre.
    object.linearDamping = floatProperty(props, "linearDamping", 3.0f, 0.0f, 1e4f, at);
    object.angularDamping = floatProperty(props, "angularDamping", 3.0f, 0.0f, 1e4f, at);
  }
  if (o.shape == TiledShape::polyline && (role == Role::trigger || dynamic))
    at.fail(std::string("a polyline cannot be ") +
            (role == Role::trigger ? "a trigger (it has no inside)" : "dynamic (it has no mass)"));
  Placed placed;
  try {
    switch (o.shape) {
      case TiledShape::rectangle:
        placed = placeBoxOrEllipse(o, {}, false, s.units);
        break;
      case TiledShape::ellipse:
        placed = placeBoxOrEllipse(o, {}, true, s.units);
        break;
      case TiledShape::tile:
        placed = placeBoxOrEllipse(o, anchor, false, s.units);
        break;
      case TiledShape::polygon:
      case TiledShape::polyline:
        placed = placeOutline(o, s.units);
        break;
      case TiledShape::point:
      case TiledShape::text:
        break;
    }
  } catch (const std::invalid_argument& e) {  // rc::InvalidShape, DecompositionError
    at.fail(std::string(tiledShapeName(o.shape)) + ": " + e.what());
  }
  object.position = placed.position;
  object.angle = placed.angle;
  object.shapes = std::move(placed.shapes);
  const std::size_t index = s.level.objects.size();
  if (object.kind == LevelObjectKind::trigger)
    s.level.triggers.push_back(
        {index, stringProperty(props, "action", "", at),
         floatProperty(props, "damagePerSecond", kDefaultDamagePerSecond, 0.0f, 1e6f, at)});
  s.level.objects.push_back(std::move(object));
}

// Counts what the level holds as it grows, and refuses a level with more shapes or things than
// any game needs before a hostile file makes it allocate without bound.
struct Budget {
  std::size_t objectsCounted = 0, shapes = 0;
  void check(const Level& level, const ErrorContext& at) {
    for (; objectsCounted < level.objects.size(); ++objectsCounted)
      shapes += level.objects[objectsCounted].shapes.size();
    if (shapes > kMaxLevelShapes)
      at.fail("the level has more than " + std::to_string(kMaxLevelShapes) + " shapes");
    const std::size_t things = level.objects.size() + level.spawns.size() + level.pickups.size() +
                               level.paths.size() + level.markers.size();
    if (things > kMaxLevelShapes)
      at.fail("the level has more than " + std::to_string(kMaxLevelShapes) + " objects");
  }
};

}  // namespace

Level levelFromMap(const TiledMap& map) {
  const ErrorContext at(map.file);
  Level level;
  level.source = map.file;
  level.files = map.files;
  LevelSettings& settings = level.settings;
  const ErrorContext mapAt = at.in("map");
  settings.pixelsPerMeter =
      floatProperty(map.properties, "pixelsPerMeter", 32.0f, 1e-3f, 1e6f, mapAt);
  settings.gravity = {floatProperty(map.properties, "gravityX", 0.0f, -1e4f, 1e4f, mapAt),
                      floatProperty(map.properties, "gravityY", 0.0f, -1e4f, 1e4f, mapAt)};
  settings.properties = map.properties;
  settings.width = map.width;
  settings.height = map.height;
  const MapUnits units{settings.pixelsPerMeter};
  settings.tileWidth = units.length(map.tileWidth);
  settings.tileHeight = units.length(map.tileHeight);
  settings.bounds = {units.point(0, static_cast<double>(map.height) * map.tileHeight),
                     units.point(static_cast<double>(map.width) * map.tileWidth, 0)};
  LoadState state{map, units, level};
  Budget budget;
  for (const TiledLayer& layer : map.layers) {
    const ErrorContext layerAt = at.in("layer " + quoteName(layer.name));
    if (layer.kind == TiledLayer::Kind::tiles) appendTileWalls(map, layer, units, level, layerAt);
    budget.check(level, layerAt);
    if (layer.kind == TiledLayer::Kind::objects)
      for (const TiledObject& o : layer.objects) {
        loadObject(layer, o, state, layerAt);
        budget.check(level, layerAt);
      }
  }
  return level;
}

Level loadLevel(const std::string& path) {
  return levelFromMap(readTiledMap(path));
}

}  // namespace game
