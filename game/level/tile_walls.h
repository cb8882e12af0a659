// A tile layer's collision: which tiles are solid, merged into chain loops.
//
// A tile is solid when its `solid` property says so (looked up on the tile, then its tileset,
// then the layer and its groups) or, without one, when it has collision shapes drawn in
// Tiled's tile collision editor. A solid tile without shapes, or whose only shape is an
// unrotated rectangle covering the whole cell, is a full square: full squares of the same
// material are merged into one-sided chain loops around each region (tile_outline.h), so
// nothing catches on the seams between them. Any other solid tile keeps its own shapes,
// flipped as the tile is. Each material of the layer becomes one LevelObject of kind tiles:
// a static body at the origin with its shapes in world coordinates.
#pragma once

#include "game/level/level.h"
#include "game/level/level_error.h"
#include "game/level/level_geometry.h"
#include "game/level/tiled_map.h"

namespace game {

void appendTileWalls(const TiledMap& map, const TiledLayer& layer, const MapUnits& units,
                     Level& level, const ErrorContext& at);

}  // namespace game
