// A Level put into a world: a body per LevelObject, in the level's order, with its shapes,
// material and user data (levelUserData: the object's kind and index, on the body and on
// every shape, so contact and sensor events and ray hits lead back to the map's object).
// Static walls and merged tiles are static bodies, props dynamic ones with their damping,
// triggers static sensors. What is not physics (spawns, pickups, triggers' actions, paths,
// markers, the map's settings) comes back as plain data beside the bodies.
#pragma once

#include <vector>

#include "game/level/level.h"
#include "physics/world.h"

namespace game {

// Collision categories of what a level builds; the game may choose others.
struct LevelFilters {
  rc::ProxyFilter walls{1u << 0, 0xFFFFFFFFu};  // object walls and tiles
  rc::ProxyFilter props{1u << 1, 0xFFFFFFFFu};
  rc::ProxyFilter triggers{1u << 2, 0xFFFFFFFFu};
};

struct BuiltTrigger {
  std::size_t object = 0;  // index in Level::objects and BuiltLevel::bodies
  rc::BodyId body;
  std::string action;
  float damagePerSecond = kDefaultDamagePerSecond;  // LevelTrigger's
  TiledProperties properties;
};

struct BuiltLevel {
  std::vector<rc::BodyId> bodies;  // bodies[i] is Level::objects[i]'s
  LevelSettings settings;
  std::vector<LevelSpawn> spawns;
  std::vector<LevelPickup> pickups;
  std::vector<BuiltTrigger> triggers;
  std::vector<LevelPath> paths;
  std::vector<LevelMarker> markers;
};

// A world definition for the level: its gravity, and the broadphase's square fitted around
// the map (a quarter of its size to spare on each side). Everything else as in `base`.
rc::WorldDef levelWorldDef(const Level& level, rc::WorldDef base = {});

// Creates the level's bodies in `world`; throws LevelError naming the object if the world
// refuses one (it should not: the loader checked every shape).
BuiltLevel buildLevel(const Level& level, rc::World& world, const LevelFilters& filters = {});

}  // namespace game
