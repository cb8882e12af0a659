// Why tiles are merged: a floor of 40 solid tiles read from a map (one chain loop) against the
// same floor as 40 separate tile boxes. A box or a ball slid across the merged floor keeps its
// speed and never leaves the surface; across the tile boxes it catches on the seams (measured
// below), and a ray along the floor never stops at a seam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "game/level/level_builder.h"
#include "game/level/level_loader.h"
#include "game/level/tiled_reader.h"
#include "level_test_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace tile_seams_test {

constexpr int kTiles = 40;

// A 40 x 3 map of 1 m tiles whose bottom row is solid (its top face at y = -2), or a 3 x 40
// one whose left column is (its face at x = 1): a floor, or a wall for a top-down game.
game::Level tileStrip(bool floor) {
  std::string data;
  const int w = floor ? kTiles : 3, h = floor ? 3 : kTiles;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool solid = floor ? y == 2 : x == 0;
      data += std::string(data.empty() ? "" : ",") + (solid ? "1" : "0");
    }
  const std::string text = R"({"type": "map", "orientation": "orthogonal", "width": )" +
                           std::to_string(w) + R"(, "height": )" + std::to_string(h) +
                           R"(, "tilewidth": 32, "tileheight": 32,
    "tilesets": [{"firstgid": 1, "name": "t", "tilewidth": 32, "tileheight": 32, "tilecount": 1,
                  "tiles": [{"id": 0, "properties": [{"name": "solid", "type": "bool", "value": true}]}]}],
    "layers": [{"id": 1, "name": "walls", "type": "tilelayer", "width": )" +
                           std::to_string(w) + R"(, "height": )" + std::to_string(h) +
                           R"(, "data": [)" + data + "]}]}";
  return game::levelFromMap(game::parseTiledMap(text, "strip.tmj", "."));
}

// The level's tiles as one box per solid tile instead (what merging replaces).
void addTileBoxes(rc::World& world, bool floor, float friction) {
  const rc::BodyId ground = world.createBody({});
  rc::ShapeDef def;
  def.friction = friction;
  for (int i = 0; i < kTiles; ++i) {
    const float f = static_cast<float>(i);
    world.createShape(
        ground,
        rc::makeBox(0.5f, 0.5f, floor ? rc::Vec2{f + 0.5f, -2.5f} : rc::Vec2{0.5f, -f - 0.5f}),
        def);
  }
}

struct Slide {
  float maxVy = 0;     // m/s off the surface
  float minVx = 1e9f;  // along it
  float maxSpin = 0;   // rad/s
  float travelled = 0;
};

// A body slid along the floor with no friction under gravity: nothing should change its speed.
Slide slideAcrossFloor(bool merged, bool ball, float speed) {
  rc::WorldDef def;
  def.gravity = {0, -10};
  rc::World world(def);
  if (merged) {
    game::Level level = tileStrip(true);
    level.objects[0].material.friction = 0;
    game::buildLevel(level, world);
  } else {
    addTileBoxes(world, true, 0);
  }
  rc::BodyDef bd;
  bd.type = rc::BodyType::dynamicBody;
  bd.position = {1.0f, -2.0f + 0.25f};
  bd.linearVelocity = {speed, 0};
  const rc::BodyId body = world.createBody(bd);
  rc::ShapeDef sd;
  sd.friction = 0;
  if (ball)
    world.createShape(body, rc::makeCircle({0, 0}, 0.25f), sd);
  else
    world.createShape(body, rc::makeBox(0.25f, 0.25f), sd);
  Slide s;
  for (int step = 0; step < 600 && world.position(body).x < kTiles - 2.0f; ++step) {
    world.step(1.0f / 60.0f);
    const rc::Vec2 v = world.linearVelocity(body);
    s.maxVy = std::max(s.maxVy, std::fabs(v.y));
    s.minVx = std::min(s.minVx, v.x);
    s.maxSpin = std::max(s.maxSpin, std::fabs(world.angularVelocity(body)));
  }
  s.travelled = world.position(body).x - 1.0f;
  return s;
}

TEST(TileSeams, BoxSlidesAcrossMergedFloorWithoutCatching) {
  for (const float speed : {2.0f, 5.0f, 10.0f, 20.0f})
    for (const bool ball : {false, true}) {
      SCOPED_TRACE(std::string(ball ? "ball" : "box") + " at " + std::to_string(speed) + " m/s");
      const Slide merged = slideAcrossFloor(true, ball, speed);
      const Slide tiles = slideAcrossFloor(false, ball, speed);
      std::printf(
          "%-4s %4.0f m/s  merged: min vx %.4f max |vy| %.4f spin %.4f travelled %.2f m"
          "  |  tile boxes: min vx %.4f max |vy| %.4f spin %.4f travelled %.2f m\n",
          ball ? "ball" : "box", speed, merged.minVx, merged.maxVy, merged.maxSpin,
          merged.travelled, tiles.minVx, tiles.maxVy, tiles.maxSpin, tiles.travelled);
      EXPECT_NEAR(merged.minVx, speed, 1e-4f * speed);
      EXPECT_LT(merged.maxVy, 1e-3f);
      EXPECT_LT(merged.maxSpin, 1e-3f);
      EXPECT_GE(merged.travelled, std::min(speed * 10.0f, kTiles - 3.0f) - 0.01f);
      // What merging is for: the tile boxes' seams take at least a fifth of the speed or throw
      // the body up at 0.5 m/s (measured: a box at 5 m/s stops within 3.2 m).
      EXPECT_TRUE(tiles.minVx < 0.8f * speed || tiles.maxVy > 0.5f);
    }
}

// Top-down: no gravity, a body running along a wall of tiles while pushed into it (a player
// holding a diagonal). Along the merged wall it keeps the speed it is driven at.
TEST(TileSeams, BodyRunsAlongMergedWallWithoutCatching) {
  for (const bool merged : {true, false})
    for (const bool ball : {false, true}) {
      rc::WorldDef def;
      def.gravity = {0, 0};
      rc::World world(def);
      if (merged) {
        game::Level level = tileStrip(false);
        level.objects[0].material.friction = 0;
        game::buildLevel(level, world);
      } else {
        addTileBoxes(world, false, 0);
      }
      rc::BodyDef bd;
      bd.type = rc::BodyType::dynamicBody;
      bd.position = {1.4f, -38.0f};
      bd.fixedRotation = ball;
      const rc::BodyId body = world.createBody(bd);
      rc::ShapeDef sd;
      sd.friction = 0;
      if (ball)
        world.createShape(body, rc::makeCircle({0, 0}, 0.4f), sd);
      else
        world.createShape(body, rc::makeBox(0.4f, 0.4f), sd);
      float minVy = 1e9f, maxVx = 0;
      for (int step = 0; step < 330; ++step) {
        const float m = world.mass(body), vy = world.linearVelocity(body).y;
        world.applyForceToCenter(body, {-20.0f * m, 40.0f * (6.0f - vy) * m});
        world.step(1.0f / 60.0f);
        if (step > 60) {
          minVy = std::min(minVy, world.linearVelocity(body).y);
          maxVx = std::max(maxVx, std::fabs(world.linearVelocity(body).x));
        }
      }
      std::printf("%-6s %-4s along a wall at 6 m/s: min vy %.3f, max |vx| off the wall %.3f\n",
                  merged ? "merged" : "tiles", ball ? "ball" : "box", minVy, maxVx);
      if (merged) {
        EXPECT_NEAR(minVy, 6.0f, 1e-3f);
        EXPECT_LT(maxVx, 1e-3f);
      }
    }
}

// Rays along the floor: just above it, and exactly along its top face (grazing), from every
// starting point over the floor; and rays coming down at shallow angles onto seams. The merged
// floor is hit only on its top face, where expected, and never stops a ray along it.
TEST(TileSeams, RayAlongMergedFloorNeverStopsAtASeam) {
  rc::World merged(rc::WorldDef{});
  game::buildLevel(tileStrip(true), merged);
  rc::World tiles(rc::WorldDef{});
  addTileBoxes(tiles, true, 0.6f);
  for (const float above : {1e-3f, 1e-5f, 0.0f})
    for (float x = 0.1f; x < kTiles - 1; x += 0.7f) {
      const rc::Vec2 origin{x, -2.0f + above};
      EXPECT_FALSE(merged.castRay(origin, {kTiles - 0.2f - x, 0}).has_value())
          << "from x " << x << " at " << above << " m above";
    }
  const auto grazing = tiles.castRay({0.2f, -2.0f}, {39.6f, 0});
  std::printf("tile boxes, ray exactly along the top face: %s\n",
              grazing ? "stops at once (starts on a box's face)" : "passes");
  int offFace = 0;
  for (const float slope : {1e-3f, 0.05f, 1.0f})
    for (int k = 0; k < 400; ++k) {
      // Half of the rays land exactly on a seam.
      const float target = k % 2 == 0 ? 2.0f + static_cast<float>(k % 72) / 2.0f
                                      : 1.0f + 37.0f * static_cast<float>(k) / 400.0f;
      const auto hit = merged.castRay({target - 1.0f, -2.0f + slope}, {2.0f, -2.0f * slope});
      ASSERT_TRUE(hit.has_value());
      if (hit->normal.y < 0.9999f || std::fabs(hit->point.y + 2.0f) > 1e-5f ||
          std::fabs(hit->point.x - target) > 1e-3f)
        ++offFace;
    }
  EXPECT_EQ(offFace, 0);
}

}  // namespace tile_seams_test
