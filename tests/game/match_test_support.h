// What the match, bot, weapon and rules tests share: levels built in code (an empty one, a walled
// room), the bundled weapon table, and a match configuration by bot count and seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "game/level/level.h"
#include "game/match/match.h"
#include "game/weapons/weapon_table.h"
#include "physics/shapes.h"

namespace match_test_support {

// assets/weapons.json, read once.
inline const game::WeaponTable& bundled() {
  static const game::WeaponTable table =
      game::loadWeaponTable(std::string(RICOCHET_SOURCE_DIR) + "/assets/weapons.json");
  return table;
}

// A level with nothing in it, 60 x 60 m.
inline game::Level emptyLevel() {
  game::Level level;
  level.source = "test";
  level.settings.bounds = {{-30, -30}, {30, 30}};
  return level;
}

struct Box {
  rc::Vec2 at, half;
};

// A closed 40 x 40 m room (walls 1 m thick around it) with a player spawn at `player`, bot spawns
// (team 1) at `bots`, and the walls asked for.
inline game::Level room(rc::Vec2 player, const std::vector<rc::Vec2>& bots,
                        const std::vector<Box>& walls = {}) {
  game::Level level;
  level.source = "room";
  level.settings.bounds = {{-20, -20}, {20, 20}};
  auto addWall = [&](rc::Vec2 at, rc::Vec2 half) {
    game::LevelObject o;
    o.kind = game::LevelObjectKind::wall;
    o.position = at;
    o.shapes.push_back(rc::makeBox(half.x, half.y));
    level.objects.push_back(o);
  };
  addWall({0, 20.5f}, {21, 0.5f});
  addWall({0, -20.5f}, {21, 0.5f});
  addWall({20.5f, 0}, {0.5f, 21});
  addWall({-20.5f, 0}, {0.5f, 21});
  for (const Box& w : walls)
    addWall(w.at, w.half);
  game::LevelSpawn p;
  p.kind = game::SpawnKind::player;
  p.position = player;
  level.spawns.push_back(p);
  for (rc::Vec2 b : bots) {
    game::LevelSpawn s;
    s.kind = game::SpawnKind::bot;
    s.position = b;
    s.team = 1;
    level.spawns.push_back(s);
  }
  return level;
}

// A pickup (Tiled id in order of adding), of the weapon named when it is ammo for another than
// the table's first.
inline void addPickup(game::Level& level, const std::string& item, float amount, float respawn,
                      rc::Vec2 at, const std::string& weapon = "") {
  game::LevelPickup p;
  p.tiledId = static_cast<std::int64_t>(level.pickups.size()) + 1;
  p.item = item;
  p.amount = amount;
  p.respawn = respawn;
  p.position = at;
  if (!weapon.empty()) {
    game::TiledProperty prop;
    prop.name = "weapon";
    prop.text = weapon;
    p.properties.list.push_back(prop);
  }
  level.pickups.push_back(p);
}

// A trigger zone of `shape` at `at`, acting as `trigger` says (its object index is set here).
inline void addTrigger(game::Level& level, rc::Vec2 at, const rc::Shape& shape,
                       game::LevelTrigger trigger) {
  game::LevelObject zone;
  zone.kind = game::LevelObjectKind::trigger;
  zone.position = at;
  zone.shapes.push_back(shape);
  level.objects.push_back(zone);
  trigger.object = level.objects.size() - 1;
  level.triggers.push_back(trigger);
}

inline game::MatchConfig config(int bots, std::uint64_t seed = 1) {
  game::MatchConfig c;
  c.bots = bots;
  c.seed = seed;
  return c;
}

}  // namespace match_test_support
