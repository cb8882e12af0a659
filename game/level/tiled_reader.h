// Reads a Tiled JSON map (.tmj) and the external JSON tilesets (.tsj) it names into a TiledMap.
//
// Supported: orthogonal, finite maps; tile layers as CSV arrays or base64 text, uncompressed,
// zlib or gzip; object layers with rectangles, ellipses, points, polygons, polylines, tile
// objects and text (kept, for the loader to skip); group layers (flattened); image layers (kept
// empty); embedded tilesets and external .tsj files resolved relative to the map; custom
// properties of every type. Refused with a LevelError naming the file and the place: infinite,
// isometric, staggered and hexagonal maps, zstd data, XML tilesets (.tsx), object templates,
// pre-1.2 property objects, a missing or unreadable file, invalid JSON, wrong types, sizes and
// numbers outside the guards below. Everything is read in file order.
#pragma once

#include <string>
#include <string_view>

#include "game/level/tiled_map.h"

namespace game {

// Guards against hostile files (each refused with a message, never a crash or a huge
// allocation).
inline constexpr int kMaxMapSide = 4096;               // tiles, either way
inline constexpr std::int64_t kMaxMapTiles = 1 << 22;  // width * height
inline constexpr int kMaxTileSize = 4096;              // pixels
inline constexpr int kMaxGroupDepth = 16;              // group layers inside group layers
inline constexpr std::size_t kMaxObjectPoints = 1024;  // polygon and polyline vertices

TiledMap readTiledMap(const std::string& path);
// The same from text; `name` stands for the file in messages, external tilesets are looked up
// relative to `directory`.
TiledMap parseTiledMap(std::string_view text, const std::string& name,
                       const std::string& directory);

}  // namespace game
