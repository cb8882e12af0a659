#include "game/level/tiled_reader.h"

#include <algorithm>
#include <filesystem>

#include "game/level/json_fields.h"
#include "game/level/tile_data.h"

namespace game {

namespace {

using namespace json_fields;
namespace fs = std::filesystem;

// Tiled's gids are 32-bit with four flag bits on top: at most 2^28 - 1 tiles in all tilesets.
constexpr std::int64_t kMaxGid = 0x0FFFFFFF;

std::string layerLabel(const std::string& name) {
  return "layer " + quoteName(name);
}

TiledProperties readProperties(const Json& owner, const ErrorContext& at) {
  TiledProperties out;
  const Json* list = find(owner, "properties");
  if (list == nullptr) return out;
  if (list->is_object())
    at.fail(
        "'properties' is in the format of Tiled before 1.2 (an object); open and save the "
        "file in a newer Tiled");
  if (!list->is_array()) at.fail("'properties' must be an array, got " + describe(*list));
  for (std::size_t i = 0; i < list->size(); ++i) {
    const Json& p = (*list)[i];
    requireObject(p, at, "properties[" + std::to_string(i) + "]");
    TiledProperty prop;
    prop.name = text(p, "name", at.in("properties[" + std::to_string(i) + "]"));
    const ErrorContext here = at.in("property " + quoteName(prop.name));
    const std::string type = text(p, "type", here, std::string("string"));
    const Json* value = find(p, "value");
    if (value == nullptr) here.fail("'value' is missing");
    if (type == "string" || type == "color" || type == "file") {
      prop.type = type == "string"  ? TiledProperty::Type::string
                  : type == "color" ? TiledProperty::Type::color
                                    : TiledProperty::Type::file;
      prop.text = json_fields::text(p, "value", here);
    } else if (type == "int" || type == "object") {
      prop.type = type == "int" ? TiledProperty::Type::integer : TiledProperty::Type::object;
      prop.number = static_cast<double>(
          integer(p, "value", here, -(std::int64_t{1} << 53), std::int64_t{1} << 53));
    } else if (type == "float") {
      prop.type = TiledProperty::Type::floating;
      prop.number = number(p, "value", here, std::nullopt, 3.0e38);
    } else if (type == "bool") {
      prop.type = TiledProperty::Type::boolean;
      prop.flag = boolean(p, "value", here);
    } else if (type == "class") {
      // A Tiled 1.8+ custom class: kept by name for the game; its members are not read.
      prop.type = TiledProperty::Type::custom;
      prop.text = json_fields::text(p, "propertytype", here, std::string());
    } else {
      here.fail("unknown property type " + quoteName(type) +
                " (Tiled writes string, int, float, bool, color, file, object or class)");
    }
    out.list.push_back(std::move(prop));
  }
  return out;
}

TiledObject readObject(const Json& j, const ErrorContext& parent, std::size_t index) {
  requireObject(j, parent, "object [" + std::to_string(index) + "]");
  TiledObject o;
  o.id = integer(j, "id", parent.in("object [" + std::to_string(index) + "]"), 0, 0x7FFFFFFF);
  const ErrorContext at = parent.in("object " + std::to_string(o.id));
  if (find(j, "template") != nullptr)
    at.fail(
        "object templates are not supported: detach the template in Tiled (Replace With "
        "Template's object: right-click, Detach) or export with --detach-templates");
  o.name = text(j, "name", at, std::string());
  o.type = text(j, "type", at, std::string());
  if (o.type.empty()) o.type = text(j, "class", at, std::string());
  o.x = number(j, "x", at, 0.0);
  o.y = number(j, "y", at, 0.0);
  o.width = number(j, "width", at, 0.0);
  o.height = number(j, "height", at, 0.0);
  o.rotation = number(j, "rotation", at, 0.0);
  if (o.width < 0 || o.height < 0) at.fail("width and height must not be negative");
  o.properties = readProperties(j, at);
  const bool ellipse = boolean(j, "ellipse", at, false), point = boolean(j, "point", at, false);
  const Json* polygon = array(j, "polygon", at, false);
  const Json* polyline = array(j, "polyline", at, false);
  const bool tile = find(j, "gid") != nullptr, isText = find(j, "text") != nullptr;
  const int kinds = int(ellipse) + int(point) + int(polygon != nullptr) + int(polyline != nullptr) +
                    int(tile) + int(isText);
  if (kinds > 1)
    at.fail("is more than one of ellipse, point, polygon, polyline, tile and text at once");
  if (ellipse) o.shape = TiledShape::ellipse;
  if (point) o.shape = TiledShape::point;
  if (isText) o.shape = TiledShape::text;
  if (tile) {
    o.shape = TiledShape::tile;
    o.gid = static_cast<std::uint32_t>(integer(j, "gid", at, 0, 0xFFFFFFFF)) & ~kGidFlags;
  }
  if (const Json* pts = polygon != nullptr ? polygon : polyline) {
    o.shape = polygon != nullptr ? TiledShape::polygon : TiledShape::polyline;
    const char* key = polygon != nullptr ? "polygon" : "polyline";
    if (pts->size() > kMaxObjectPoints)
      at.fail(std::string(key) + " has " + std::to_string(pts->size()) + " points, more than the " +
              std::to_string(kMaxObjectPoints) + " supported");
    for (std::size_t i = 0; i < pts->size(); ++i) {
      const ErrorContext pointAt = at.in(std::string(key) + "[" + std::to_string(i) + "]");
      requireObject((*pts)[i], pointAt, "a point");
      o.points.push_back({number((*pts)[i], "x", pointAt), number((*pts)[i], "y", pointAt)});
    }
  }
  return o;
}

std::vector<TiledObject> readObjects(const Json& owner, const ErrorContext& at) {
  std::vector<TiledObject> out;
  if (const Json* objects = array(owner, "objects", at, false))
    for (std::size_t i = 0; i < objects->size(); ++i)
      out.push_back(readObject((*objects)[i], at, i));
  return out;
}

// A tileset's content, from the map (embedded) or from its own file (`at` names that file).
void readTilesetBody(const Json& j, TiledTileset& ts, const ErrorContext& at) {
  ts.name = text(j, "name", at, std::string());
  ts.tileWidth = static_cast<int>(integer(j, "tilewidth", at, 1, kMaxTileSize));
  ts.tileHeight = static_cast<int>(integer(j, "tileheight", at, 1, kMaxTileSize));
  ts.tileCount = integer(j, "tilecount", at, 0, kMaxGid);
  if (const Json* offset = find(j, "tileoffset")) {
    requireObject(*offset, at, "'tileoffset'");
    ts.offsetX = static_cast<int>(
        integer(*offset, "x", at.in("tileoffset"), -kMaxTileSize, kMaxTileSize, 0));
    ts.offsetY = static_cast<int>(
        integer(*offset, "y", at.in("tileoffset"), -kMaxTileSize, kMaxTileSize, 0));
  }
  ts.objectAlignment = text(j, "objectalignment", at, std::string("unspecified"));
  ts.properties = readProperties(j, at);
  if (const Json* tiles = find(j, "tiles")) {
    if (!tiles->is_array())
      at.fail(
          "'tiles' must be an array (an object is the format of Tiled before 1.2; open "
          "and save the tileset in a newer Tiled)");
    for (std::size_t i = 0; i < tiles->size(); ++i) {
      const Json& t = (*tiles)[i];
      requireObject(t, at, "tiles[" + std::to_string(i) + "]");
      TiledTile tile;
      tile.id = integer(t, "id", at.in("tiles[" + std::to_string(i) + "]"), 0, kMaxGid);
      const ErrorContext tileAt = at.in("tile " + std::to_string(tile.id));
      tile.type = text(t, "type", tileAt, std::string());
      if (tile.type.empty()) tile.type = text(t, "class", tileAt, std::string());
      tile.properties = readProperties(t, tileAt);
      if (const Json* group = find(t, "objectgroup")) {
        requireObject(*group, tileAt, "'objectgroup'");
        tile.collision = readObjects(*group, tileAt.in("collision"));
      }
      ts.tiles.push_back(std::move(tile));
    }
  }
  std::stable_sort(ts.tiles.begin(), ts.tiles.end(),
                   [](const TiledTile& a, const TiledTile& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < ts.tiles.size(); ++i)
    if (ts.tiles[i].id == ts.tiles[i - 1].id)
      at.fail("tile " + std::to_string(ts.tiles[i].id) + " is described twice");
  // Image-collection tilesets keep the ids of deleted tiles: an id may exceed the count.
  if (!ts.tiles.empty()) ts.tileCount = std::max(ts.tileCount, ts.tiles.back().id + 1);
  if (ts.tileCount > kMaxGid) at.fail("more tiles than Tiled's gids can address");
}

TiledTileset readTileset(const Json& j, const ErrorContext& mapAt, const std::string& directory,
                         std::size_t index) {
  const ErrorContext at = mapAt.in("tileset [" + std::to_string(index) + "]");
  requireObject(j, at, "a tileset");
  TiledTileset ts;
  ts.firstGid = static_cast<std::uint32_t>(integer(j, "firstgid", at, 1, kMaxGid));
  const Json* source = find(j, "source");
  if (source == nullptr) {
    ts.file = mapAt.file();
    readTilesetBody(j, ts, at);
    return ts;
  }
  const std::string name = text(j, "source", at);
  const ErrorContext named = mapAt.in("tileset " + quoteName(name));
  const std::string extension = fs::path(name).extension().string();
  if (extension == ".tsx" || extension == ".xml")
    named.fail(
        "XML tilesets are not supported: export the tileset as JSON (.tsj) in Tiled and "
        "point the map at it");
  const std::string path = (fs::path(directory) / name).lexically_normal().string();
  std::error_code ec;
  if (!fs::exists(path, ec))
    named.fail("cannot open the tileset file " + quoteName(path) + ": it does not exist");
  const ErrorContext fileAt(path);
  const Json root = parseFile(path, fileAt);
  requireObject(root, fileAt, "a tileset file");
  const std::string type = text(root, "type", fileAt, std::string("tileset"));
  if (type != "tileset") fileAt.fail("not a tileset ('type' is " + quoteName(type) + ")");
  ts.file = path;
  readTilesetBody(root, ts, fileAt);
  return ts;
}

std::vector<std::uint32_t> readTileData(const Json& j, std::size_t count, const ErrorContext& at) {
  const std::string encoding = text(j, "encoding", at, std::string("csv"));
  const std::string compression = text(j, "compression", at, std::string());
  const Json* data = find(j, "data");
  if (data == nullptr) at.fail("'data' is missing");
  if (encoding == "csv") {
    if (!compression.empty()) at.fail("CSV data cannot be compressed ('compression' is set)");
    if (!data->is_array())
      at.fail("'data' must be an array of gids with encoding csv, got " + describe(*data));
    if (data->size() != count)
      at.fail("'data' holds " + std::to_string(data->size()) + " tiles, the layer needs " +
              std::to_string(count));
    std::vector<std::uint32_t> gids(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Json& g = (*data)[i];
      if (!g.is_number_unsigned() || g.get<std::uint64_t>() > 0xFFFFFFFFull)
        at.fail("data[" + std::to_string(i) + "] must be a gid (an integer from 0 to " +
                "4294967295), got " + describe(g));
      gids[i] = static_cast<std::uint32_t>(g.get<std::uint64_t>());
    }
    return gids;
  }
  if (encoding != "base64")
    at.fail("unknown encoding " + quoteName(encoding) + " (Tiled writes csv or base64)");
  if (!data->is_string())
    at.fail("'data' must be a string with encoding base64, got " + describe(*data));
  TileCompression how = TileCompression::none;
  if (compression == "zlib") {
    how = TileCompression::zlib;
  } else if (compression == "gzip") {
    how = TileCompression::gzip;
  } else if (compression == "zstd") {
    at.fail(
        "zstd compression is not supported: choose zlib, gzip or none for the tile layer "
        "format in Tiled (Map > Map Properties > Tile Layer Format)");
  } else if (!compression.empty()) {
    at.fail("unknown compression " + quoteName(compression) + " (Tiled writes zlib, gzip or zstd)");
  }
  const std::vector<std::uint8_t> bytes = decodeBase64(data->get_ref<const std::string&>(), at);
  if (how == TileCompression::none) return gidsFromBytes(bytes, count, at);
  return gidsFromBytes(inflateExactly(bytes, how, 4 * count, at), count, at);
}

struct LayerScope {
  std::string prefix;  // the groups' names: "level1/"
  double offsetX = 0, offsetY = 0;
  TiledProperties properties;
  int depth = 0;
};

void readLayers(const Json& owner, const LayerScope& scope, TiledMap& map,
                const ErrorContext& mapAt) {
  const Json* layers = array(owner, "layers", mapAt, scope.depth == 0);
  if (layers == nullptr) return;
  for (std::size_t i = 0; i < layers->size(); ++i) {
    const Json& j = (*layers)[i];
    requireObject(j, mapAt.in(scope.prefix.empty() ? "layers" : layerLabel(scope.prefix)),
                  "layer [" + std::to_string(i) + "]");
    TiledLayer layer;
    layer.name = scope.prefix +
                 text(j, "name", mapAt.in("layer [" + std::to_string(i) + "]"), std::string());
    const ErrorContext at = mapAt.in(layerLabel(layer.name));
    layer.id = integer(j, "id", at, 0, kMaxGid, 0);
    layer.offsetX = scope.offsetX + number(j, "offsetx", at, 0.0);
    layer.offsetY = scope.offsetY + number(j, "offsety", at, 0.0);
    layer.properties = readProperties(j, at);
    layer.properties.inherit(scope.properties);
    const std::string type = text(j, "type", at);
    if (type == "group") {
      if (scope.depth + 1 > kMaxGroupDepth)
        at.fail("group layers nested deeper than " + std::to_string(kMaxGroupDepth));
      LayerScope inner{layer.name + "/", layer.offsetX, layer.offsetY, layer.properties,
                       scope.depth + 1};
      readLayers(j, inner, map, mapAt);
      continue;
    }
    if (type == "tilelayer") {
      layer.kind = TiledLayer::Kind::tiles;
      if (find(j, "chunks") != nullptr)
        at.fail("chunked tile data (an infinite map) is not supported");
      layer.width = static_cast<int>(integer(j, "width", at, 1, kMaxMapSide));
      layer.height = static_cast<int>(integer(j, "height", at, 1, kMaxMapSide));
      if (layer.width != map.width || layer.height != map.height)
        at.fail("is " + std::to_string(layer.width) + "x" + std::to_string(layer.height) +
                " tiles, the map " + std::to_string(map.width) + "x" + std::to_string(map.height));
      layer.gids = readTileData(j, static_cast<std::size_t>(map.width) * map.height, at);
    } else if (type == "objectgroup") {
      layer.kind = TiledLayer::Kind::objects;
      layer.objects = readObjects(j, at);
    } else if (type == "imagelayer") {
      layer.kind = TiledLayer::Kind::image;
    } else {
      at.fail("unknown layer type " + quoteName(type) +
              " (Tiled writes tilelayer, objectgroup, imagelayer or group)");
    }
    map.layers.push_back(std::move(layer));
  }
}

TiledMap mapFromJson(const Json& root, const std::string& name, const std::string& directory) {
  const ErrorContext at(name);
  requireObject(root, at, "a Tiled map");
  const std::string type = text(root, "type", at, std::string("map"));
  if (type == "tileset") at.fail("this is a tileset, not a map");
  if (type != "map") at.fail("not a Tiled map ('type' is " + quoteName(type) + ")");
  const std::string orientation = text(root, "orientation", at);
  if (orientation != "orthogonal")
    at.fail(quoteName(orientation) + " maps are not supported, only orthogonal ones");
  if (boolean(root, "infinite", at, false))
    at.fail("infinite maps are not supported: untick Map > Map Properties > Infinite in Tiled");
  TiledMap map;
  map.file = name;
  map.width = static_cast<int>(integer(root, "width", at, 1, kMaxMapSide));
  map.height = static_cast<int>(integer(root, "height", at, 1, kMaxMapSide));
  if (std::int64_t{map.width} * map.height > kMaxMapTiles)
    at.fail("the map is " + std::to_string(map.width) + "x" + std::to_string(map.height) +
            " tiles, more than the " + std::to_string(kMaxMapTiles) + " supported");
  map.tileWidth = static_cast<int>(integer(root, "tilewidth", at, 1, kMaxTileSize));
  map.tileHeight = static_cast<int>(integer(root, "tileheight", at, 1, kMaxTileSize));
  map.properties = readProperties(root, at);
  if (const Json* tilesets = array(root, "tilesets", at, false)) {
    for (std::size_t i = 0; i < tilesets->size(); ++i) {
      map.tilesets.push_back(readTileset((*tilesets)[i], at, directory, i));
      const std::string& file = map.tilesets.back().file;
      if (file != name && std::find(map.files.begin(), map.files.end(), file) == map.files.end())
        map.files.push_back(file);
      if (i > 0 && map.tilesets[i].firstGid <= map.tilesets[i - 1].firstGid)
        at.fail("tileset [" + std::to_string(i) + "]: 'firstgid' " +
                std::to_string(map.tilesets[i].firstGid) +
                " is not above the previous tileset's (Tiled lists them in ascending order)");
    }
  }
  readLayers(root, LayerScope{}, map, at);
  return map;
}

}  // namespace

TiledMap parseTiledMap(std::string_view text, const std::string& name,
                       const std::string& directory) {
  return mapFromJson(parseText(text, ErrorContext(name)), name, directory);
}

TiledMap readTiledMap(const std::string& path) {
  const std::string directory = fs::path(path).parent_path().string();
  TiledMap map =
      mapFromJson(parseFile(path, ErrorContext(path)), path, directory.empty() ? "." : directory);
  map.files.insert(map.files.begin(), path);
  return map;
}

}  // namespace game
