// A Tiled map made into a Level: every layer in file order, objects by their type (Tiled's
// "type", or "class" in Tiled 1.9), tile layers merged into chain loops (tile_walls.h). The
// types, properties and units a level designer uses are in game/level/README.md. Every
// problem is a LevelError naming the file, the layer and the object.
#pragma once

#include <string>

#include "game/level/level.h"
#include "game/level/tiled_map.h"

namespace game {

// readTiledMap then levelFromMap.
Level loadLevel(const std::string& path);
Level levelFromMap(const TiledMap& map);

}  // namespace game
