#include "game/level/tile_walls.h"

#include <map>

#include "game/level/convex_decomposition.h"
#include "game/level/level_properties.h"
#include "game/level/tile_outline.h"
#include "physics/trig.h"

namespace game {

namespace {

// What a gid means for collision, worked out once per gid of the layer.
struct TileCollision {
  bool solid = false;
  bool full = false;      // a full square: merged into the outlines
  std::size_t group = 0;  // index of its material among the layer's
  const TiledTile* tile = nullptr;
  const TiledTileset* tileset = nullptr;
};

struct Point {
  double x, y;
};

// Where a tile's collision shapes go: its image drawn with its bottom-left at the cell's
// bottom-left (Tiled's rule for tiles larger than the grid), moved by the tileset's offset and
// the layer's, and mirrored by the cell's flip flags.
struct TilePlacement {
  double left = 0, top = 0;      // the image's top-left, map pixels
  double width = 0, height = 0;  // the image's size, pixels
  std::uint32_t flips = 0;
  const MapUnits* units = nullptr;

  // A point of the tile image (pixels from its top-left, y down) in world metres.
  rc::Vec2 world(Point p) const {
    double w = width, h = height;
    if ((flips & kFlipDiagonal) != 0) {  // Tiled mirrors about the diagonal first
      p = {p.y, p.x};
      std::swap(w, h);
    }
    if ((flips & kFlipHorizontal) != 0) p.x = w - p.x;
    if ((flips & kFlipVertical) != 0) p.y = h - p.y;
    return units->point(left + p.x, top + p.y);
  }
};

// An object of the tile's collision group turned about its (x, y) by its rotation, in tile
// pixels.
Point turnedAbout(const TiledObject& o, double dx, double dy) {
  if (o.rotation == 0) return {o.x + dx, o.y + dy};
  // Tiled turns clockwise on screen, y down: (dx, dy) -> (dx c - dy s, dx s + dy c).
  const rc::SinCos sc =
      rc::sincos(static_cast<float>(o.rotation * (3.14159265358979323846 / 180.0)));
  return {o.x + dx * sc.cosine - dy * sc.sine, o.y + dx * sc.sine + dy * sc.cosine};
}

void appendCollisionShape(const TiledObject& o, const TilePlacement& place,
                          std::vector<rc::Shape>& out) {
  switch (o.shape) {
    case TiledShape::rectangle:
    case TiledShape::ellipse: {
      if (o.width <= 0 || o.height <= 0) throw rc::InvalidShape("has no width or height");
      if (o.rotation == 0) {
        // Mirrors keep an unrotated rectangle or ellipse axis-aligned: its corners say where.
        const rc::Vec2 a = place.world({o.x, o.y}),
                       b = place.world({o.x + o.width, o.y + o.height});
        const rc::Vec2 center = 0.5f * (a + b);
        const float hw = 0.5f * std::fabs(b.x - a.x), hh = 0.5f * std::fabs(b.y - a.y);
        out.push_back(o.shape == TiledShape::rectangle ? rc::Shape(rc::makeBox(hw, hh, center))
                                                       : ellipseShape(center, hw, hh));
        return;
      }
      std::vector<rc::Vec2> corners;
      if (o.shape == TiledShape::rectangle) {
        for (const Point d :
             {Point{0, 0}, Point{o.width, 0}, Point{o.width, o.height}, Point{0, o.height}})
          corners.push_back(place.world(turnedAbout(o, d.x, d.y)));
      } else {
        const std::vector<rc::Vec2> octagon =
            ellipseOctagon({static_cast<float>(o.width / 2), static_cast<float>(o.height / 2)},
                           static_cast<float>(o.width / 2), static_cast<float>(o.height / 2));
        for (const rc::Vec2 v : octagon)
          corners.push_back(place.world(turnedAbout(o, v.x, v.y)));
      }
      out.push_back(rc::makePolygon(corners));
      return;
    }
    case TiledShape::polygon:
    case TiledShape::polyline: {
      std::vector<rc::Vec2> points;
      for (const TiledPoint& p : o.points)
        points.push_back(place.world(turnedAbout(o, p.x, p.y)));
      if (o.shape == TiledShape::polygon) {
        appendPolygonShapes(points, out);
      } else {
        for (const rc::ChainSegment& link : rc::makeChain(points, false, false))
          out.push_back(link);
      }
      return;
    }
    case TiledShape::point:
    case TiledShape::tile:
    case TiledShape::text:
      return;  // no area: not collision
  }
}

bool hasCollisionShapes(const TiledTile* tile) {
  if (tile == nullptr) return false;
  for (const TiledObject& o : tile->collision)
    if (o.shape != TiledShape::point && o.shape != TiledShape::text && o.shape != TiledShape::tile)
      return true;
  return false;
}

// The tile's only shape is an unrotated rectangle over its whole cell.
bool coversCell(const TiledMap& map, const TiledTileset& ts, const TiledTile& tile) {
  if (tile.collision.size() != 1) return false;
  const TiledObject& o = tile.collision[0];
  return o.shape == TiledShape::rectangle && o.rotation == 0 && o.x == 0 && o.y == 0 &&
         o.width == ts.tileWidth && o.height == ts.tileHeight && ts.tileWidth == map.tileWidth &&
         ts.tileHeight == map.tileHeight && ts.offsetX == 0 && ts.offsetY == 0;
}

std::string tileLabel(const TiledTileset& ts, std::int64_t id) {
  return "tile " + std::to_string(id) + " of tileset " + quoteName(ts.name);
}

}  // namespace

void appendTileWalls(const TiledMap& map, const TiledLayer& layer, const MapUnits& units,
                     Level& level, const ErrorContext& at) {
  const int width = layer.width, height = layer.height;
  std::map<std::uint32_t, TileCollision> byGid;  // ordered: no hash order anywhere
  std::vector<LevelMaterial> materials;          // in order of first use
  std::vector<std::vector<std::uint8_t>> grids;  // full squares, one grid per material
  std::vector<std::vector<rc::Shape>> shapes;    // other solid tiles' shapes, per material

  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      const std::size_t cell = static_cast<std::size_t>(row) * width + col;
      const std::uint32_t raw = layer.gids[cell], gid = raw & ~kGidFlags;
      if (gid == 0) continue;
      const ErrorContext cellAt =
          at.in("tile at column " + std::to_string(col) + ", row " + std::to_string(row));
      auto found = byGid.find(gid);
      if (found == byGid.end()) {
        const TileRef ref = findTile(map, gid);
        if (ref.tileset == nullptr)
          cellAt.fail("gid " + std::to_string(gid) + " belongs to no tileset of the map");
        TileCollision info;
        info.tileset = ref.tileset;
        info.tile = ref.tileset->tile(ref.localId);
        const ErrorContext tileAt = at.in(tileLabel(*ref.tileset, ref.localId));
        TiledProperties props;
        if (info.tile != nullptr) props = info.tile->properties;
        props.inherit(ref.tileset->properties);
        props.inherit(layer.properties);
        const bool drawn = hasCollisionShapes(info.tile);
        info.solid = boolProperty(props, "solid", drawn, tileAt);
        info.full = info.solid && (!drawn || coversCell(map, *ref.tileset, *info.tile));
        if (info.solid) {
          const LevelMaterial material = readMaterial(props, LevelMaterial{}, tileAt);
          std::size_t g = 0;
          while (g < materials.size() && !(materials[g] == material))
            ++g;
          if (g == materials.size()) {
            materials.push_back(material);
            grids.emplace_back(static_cast<std::size_t>(width) * height, 0);
            shapes.emplace_back();
          }
          info.group = g;
        }
        found = byGid.emplace(gid, info).first;
      }
      const TileCollision& info = found->second;
      if (!info.solid) continue;
      if (info.full) {
        grids[info.group][cell] = 1;
        continue;
      }
      const TiledTileset& ts = *info.tileset;
      TilePlacement place;
      place.left = layer.offsetX + static_cast<double>(col) * map.tileWidth + ts.offsetX;
      place.top = layer.offsetY + static_cast<double>(row + 1) * map.tileHeight - ts.tileHeight +
                  ts.offsetY;
      place.width = ts.tileWidth;
      place.height = ts.tileHeight;
      place.flips = raw & kGidFlags;
      place.units = &units;
      if (shapes[info.group].size() > kMaxLevelShapes)
        cellAt.fail("the layer's tiles have more than " + std::to_string(kMaxLevelShapes) +
                    " collision shapes, the most a level may have");
      for (const TiledObject& o : info.tile->collision) {
        try {
          appendCollisionShape(o, place, shapes[info.group]);
        } catch (const std::invalid_argument& e) {  // rc::InvalidShape, DecompositionError
          cellAt.in(tileLabel(ts, info.tile->id))
              .in("collision object " + std::to_string(o.id))
              .fail(std::string(tiledShapeName(o.shape)) + ": " + e.what());
        }
      }
    }

  std::size_t corners = 0;
  for (std::size_t g = 0; g < materials.size(); ++g)
    corners += countOutlineCorners(width, height, grids[g]) + shapes[g].size();
  if (corners > kMaxLevelShapes)
    at.fail("the layer's solid tiles make " + std::to_string(corners) + " shapes, more than the " +
            std::to_string(kMaxLevelShapes) + " a level may have");
  for (std::size_t g = 0; g < materials.size(); ++g) {
    LevelObject object;
    object.kind = LevelObjectKind::tiles;
    object.tiledId = layer.id;
    object.layer = layer.name;
    object.name = layer.name;
    object.type = "tiles";
    object.material = materials[g];
    object.properties = layer.properties;
    for (const std::vector<GridCorner>& loop : traceOutlines(width, height, grids[g])) {
      std::vector<rc::Vec2> points;
      for (const GridCorner c : loop)
        points.push_back(units.point(layer.offsetX + static_cast<double>(c.x) * map.tileWidth,
                                     layer.offsetY + static_cast<double>(c.y) * map.tileHeight));
      try {
        for (const rc::ChainSegment& link : rc::makeChain(points, true, true))
          object.shapes.push_back(link);
      } catch (const rc::InvalidShape& e) {
        at.fail(std::string("merged outline at column ") + std::to_string(loop[0].x) + ", row " +
                std::to_string(loop[0].y) + ": " + e.what());
      }
    }
    for (const rc::Shape& s : shapes[g])
      object.shapes.push_back(s);
    if (!object.shapes.empty()) level.objects.push_back(std::move(object));
  }
}

}  // namespace game
