// A Tiled map as the file says it, in Tiled's units (pixels, y down, degrees clockwise): what
// readTiledMap (tiled_reader.h) makes of a .tmj file and its external .tsj tilesets, before
// anything becomes physics. Only what a level uses is kept; editor-only fields (colours,
// opacity, parallax, wang sets) are skipped. Layers inside group layers are flattened in file
// order, their offsets summed and the groups' properties inherited.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace game {

struct TiledProperty {
  enum class Type : std::uint8_t {
    string,
    integer,
    floating,
    boolean,
    color,
    file,
    object,
    custom
  };
  std::string name;
  Type type = Type::string;
  std::string text;   // string, color, file; the class name of a custom (class) property
  double number = 0;  // integer, floating, object (its id)
  bool flag = false;  // boolean
};
const char* propertyTypeName(TiledProperty::Type type);

// Custom properties in file order. Lookups take the first of a name, so a list built as
// "own, then inherited" lets the nearest definition win.
struct TiledProperties {
  std::vector<TiledProperty> list;
  const TiledProperty* find(const std::string& name) const;
  // Appends those of `inherited` whose names are not here yet.
  void inherit(const TiledProperties& inherited);
};

struct TiledPoint {
  double x = 0, y = 0;
};

enum class TiledShape : std::uint8_t { rectangle, ellipse, point, polygon, polyline, tile, text };
const char* tiledShapeName(TiledShape shape);

struct TiledObject {
  std::int64_t id = 0;
  std::string name;
  std::string type;  // "type" up to Tiled 1.8 and from 1.10, "class" in 1.9
  TiledShape shape = TiledShape::rectangle;
  // Rectangles and ellipses: top-left corner and size. Tile objects: bottom-left corner and size.
  // Points: the point. Polygons and polylines: the origin of `points`. Rotation turns the whole
  // object about (x, y), in degrees clockwise on screen.
  double x = 0, y = 0, width = 0, height = 0, rotation = 0;
  std::vector<TiledPoint> points;  // polygon and polyline, relative to (x, y)
  std::uint32_t gid = 0;           // tile objects: the tile, flip flags masked off
  TiledProperties properties;
};

// A tile of a tileset that says more than its image: properties, a type, collision shapes.
struct TiledTile {
  std::int64_t id = 0;  // local id in its tileset
  std::string type;
  TiledProperties properties;
  // The objects drawn in Tiled's tile collision editor, relative to the tile image's top-left.
  std::vector<TiledObject> collision;
};

struct TiledTileset {
  std::string name;
  std::string file;  // the .tsj for an external tileset, else the map: for messages
  std::uint32_t firstGid = 1;
  std::int64_t tileCount = 0;
  int tileWidth = 0, tileHeight = 0;
  int offsetX = 0, offsetY = 0;  // tileoffset: where tiles are drawn relative to their cell
  // Which point of a tile object its (x, y) is: "unspecified" (bottom-left on orthogonal
  // maps), "topleft", "top", ..., "bottomright".
  std::string objectAlignment = "unspecified";
  TiledProperties properties;
  std::vector<TiledTile> tiles;  // sorted by id
  const TiledTile* tile(std::int64_t id) const;
};

// Gids in tile layers and tile objects carry flip flags in their top bits (horizontal,
// vertical, diagonal, and the hexagonal 120-degree turn).
inline constexpr std::uint32_t kFlipHorizontal = 0x80000000u;
inline constexpr std::uint32_t kFlipVertical = 0x40000000u;
inline constexpr std::uint32_t kFlipDiagonal = 0x20000000u;
inline constexpr std::uint32_t kGidFlags = 0xF0000000u;

struct TiledLayer {
  enum class Kind : std::uint8_t { tiles, objects, image };
  Kind kind = Kind::tiles;
  std::int64_t id = 0;
  std::string name;                 // with its groups' names before it: "level1/walls"
  double offsetX = 0, offsetY = 0;  // pixels, its groups' included
  TiledProperties properties;       // its own, then its groups'
  // Tile layers: width x height gids, row by row from the top, flip flags kept.
  int width = 0, height = 0;
  std::vector<std::uint32_t> gids;
  // Object layers.
  std::vector<TiledObject> objects;
};

struct TiledMap {
  std::string file;
  // Every file read to make it, for the commands that must never write over one: the map (when
  // read from a file), then each external tileset once, in the order the map names them.
  std::vector<std::string> files;
  int width = 0, height = 0;          // tiles
  int tileWidth = 0, tileHeight = 0;  // pixels
  TiledProperties properties;
  std::vector<TiledTileset> tilesets;  // by firstGid, ascending
  std::vector<TiledLayer> layers;      // in file order, bottom first
};

// The tileset a gid (flags masked off) belongs to and the local id in it, or nullptr when no
// tileset holds it.
struct TileRef {
  const TiledTileset* tileset = nullptr;
  std::int64_t localId = 0;
};
TileRef findTile(const TiledMap& map, std::uint32_t gid);

}  // namespace game
