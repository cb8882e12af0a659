#include "game/level/tiled_map.h"

#include <algorithm>

namespace game {

const char* propertyTypeName(TiledProperty::Type type) {
  switch (type) {
    case TiledProperty::Type::string:
      return "string";
    case TiledProperty::Type::integer:
      return "int";
    case TiledProperty::Type::floating:
      return "float";
    case TiledProperty::Type::boolean:
      return "bool";
    case TiledProperty::Type::color:
      return "color";
    case TiledProperty::Type::file:
      return "file";
    case TiledProperty::Type::object:
      return "object";
    case TiledProperty::Type::custom:
      return "class";
  }
  return "?";
}

const char* tiledShapeName(TiledShape shape) {
  switch (shape) {
    case TiledShape::rectangle:
      return "rectangle";
    case TiledShape::ellipse:
      return "ellipse";
    case TiledShape::point:
      return "point";
    case TiledShape::polygon:
      return "polygon";
    case TiledShape::polyline:
      return "polyline";
    case TiledShape::tile:
      return "tile object";
    case TiledShape::text:
      return "text object";
  }
  return "?";
}

const TiledProperty* TiledProperties::find(const std::string& name) const {
  for (const TiledProperty& p : list)
    if (p.name == name) return &p;
  return nullptr;
}

void TiledProperties::inherit(const TiledProperties& inherited) {
  for (const TiledProperty& p : inherited.list)
    if (find(p.name) == nullptr) list.push_back(p);
}

const TiledTile* TiledTileset::tile(std::int64_t id) const {
  const auto it = std::lower_bound(tiles.begin(), tiles.end(), id,
                                   [](const TiledTile& t, std::int64_t v) { return t.id < v; });
  return it != tiles.end() && it->id == id ? &*it : nullptr;
}

TileRef findTile(const TiledMap& map, std::uint32_t gid) {
  // The tileset with the largest first gid not above this one (Tiled's rule).
  const TiledTileset* owner = nullptr;
  for (const TiledTileset& t : map.tilesets)
    if (t.firstGid <= gid) owner = &t;
  if (owner == nullptr) return {};
  const std::int64_t local = static_cast<std::int64_t>(gid) - owner->firstGid;
  if (local >= owner->tileCount) return {};
  return {owner, local};
}

}  // namespace game
