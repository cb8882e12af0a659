// A level as the game uses it: plain data in metres with y up, read from a Tiled map by
// loadLevel (level_loader.h) and put into a world by buildLevel (level_builder.h).
//
// Every physical thing of the map is a LevelObject: a static wall, a tile layer's merged walls
// of one material, a dynamic prop (crate, barrel), a trigger zone. Points become spawns,
// pickups and markers; patrol polylines become paths. All lists keep the map's order (layers
// bottom to top, objects as listed), so building the same level always creates the same
// bodies in the same order.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "game/level/tiled_map.h"
#include "physics/world.h"

namespace game {

// More shapes than this in one level are refused (a hostile checkerboard of 2^22 tiles would
// otherwise ask for tens of millions of chain links).
inline constexpr std::size_t kMaxLevelShapes = std::size_t{1} << 18;

// A shot spends this much of its penetration budget to cross a material: never.
inline constexpr float kImpenetrable = std::numeric_limits<float>::infinity();

struct LevelMaterial {
  float density = 1.0f;  // kg/m^2
  float friction = 0.6f;
  float restitution = 0.0f;
  float thickness = kImpenetrable;  // penetration budget a shot spends crossing it
  float health = 0.0f;              // hit points; 0: indestructible
  bool hard = true;                 // shots ricochet off it at grazing angles
  friend bool operator==(const LevelMaterial&, const LevelMaterial&) = default;
};

enum class LevelObjectKind : std::uint8_t {
  wall,     // a static object of an object layer
  tiles,    // the solid tiles of one tile layer that share a material
  prop,     // a dynamic body: crate, barrel, or any object with dynamic = true
  trigger,  // a sensor zone
};
const char* levelObjectKindName(LevelObjectKind kind);

struct LevelObject {
  LevelObjectKind kind = LevelObjectKind::wall;
  std::int64_t tiledId = 0;  // the Tiled object's id; for tiles, the layer's id
  std::string layer, name, type;
  rc::BodyType bodyType = rc::BodyType::staticBody;
  rc::Vec2 position{};  // body origin
  float angle = 0.0f;
  float linearDamping = 0.0f, angularDamping = 0.0f;
  LevelMaterial material;
  std::vector<rc::Shape> shapes;  // in the body's frame; a chain as its links
  // Tiled's custom properties as the game sees them: the object's own, then those of its tile,
  // layer and groups that it does not override.
  TiledProperties properties;
};

enum class SpawnKind : std::uint8_t { player, bot };
// The team of a spawn the level gives none: players 0, bots 1.
constexpr int defaultTeam(SpawnKind kind) {
  return kind == SpawnKind::player ? 0 : 1;
}

struct LevelSpawn {
  SpawnKind kind = SpawnKind::player;
  std::int64_t tiledId = 0;
  std::string name;
  rc::Vec2 position{};
  float facing = 0.0f;  // radians, counter-clockwise from +x
  int team = -1;        // the actor's team; -1: defaultTeam(kind)
  TiledProperties properties;
};

struct LevelPickup {
  std::int64_t tiledId = 0;
  std::string name;
  std::string item;  // "health", "ammo", ...: the game decides what it means
  float amount = 0.0f;
  float respawn = 0.0f;  // seconds until it comes back; 0: never
  float radius = 0.5f;   // m
  rc::Vec2 position{};
  TiledProperties properties;
};

inline constexpr float kDefaultDamagePerSecond = 10.0f;  // a "hurt" zone's, unless it says

struct LevelTrigger {
  std::size_t object = 0;  // index in Level::objects (its sensor body)
  std::string action;      // "kill", "exit", "hurt", ...: the game decides what it means
  float damagePerSecond = kDefaultDamagePerSecond;  // what a "hurt" zone takes off each actor
};

// A polyline of type "path": a route for bots, not geometry.
struct LevelPath {
  std::int64_t tiledId = 0;
  std::string name;
  std::vector<rc::Vec2> points;
  bool loop = false;
  TiledProperties properties;
};

// Any other point: a named place the game may look up (a waypoint, a camera, a sound source).
struct LevelMarker {
  std::int64_t tiledId = 0;
  std::string name, type;
  rc::Vec2 position{};
  TiledProperties properties;
};

struct LevelSettings {
  float pixelsPerMeter = 32.0f;
  rc::Vec2 gravity{0.0f, 0.0f};               // m/s^2; a top-down shooter has none
  int width = 0, height = 0;                  // tiles
  float tileWidth = 0.0f, tileHeight = 0.0f;  // m
  rc::AABB bounds{};                          // the map's area, m
  TiledProperties properties;                 // the map's own
};

struct Level {
  std::string source;  // the map file
  // Every file it was read from: the map, then its external tilesets (TiledMap::files). The
  // commands refuse an output that names one of them.
  std::vector<std::string> files;
  LevelSettings settings;
  std::vector<LevelObject> objects;
  std::vector<LevelSpawn> spawns;
  std::vector<LevelPickup> pickups;
  std::vector<LevelTrigger> triggers;
  std::vector<LevelPath> paths;
  std::vector<LevelMarker> markers;
};

// The user data of every body and shape a level builds: a tag in the top byte, the object's
// kind, and its index in Level::objects, so a contact or hit leads back to the map's object
// (and its material) in constant time.
inline constexpr std::uint64_t kLevelUserDataTag = std::uint64_t{0x4C} << 56;  // 'L'
constexpr std::uint64_t levelUserData(LevelObjectKind kind, std::size_t index) {
  return kLevelUserDataTag | std::uint64_t{static_cast<std::uint8_t>(kind)} << 48 |
         static_cast<std::uint32_t>(index);
}
struct LevelRef {
  LevelObjectKind kind;
  std::size_t index;
};
// The object named by user data, or nothing for user data that is not a level's.
std::optional<LevelRef> levelRefOf(std::uint64_t userData);

}  // namespace game
