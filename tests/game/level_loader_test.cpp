// The bundled levels against counts worked out by hand from their layouts (see the comments),
// and the world built from them: a body per object with its user data, props dynamic,
// triggers sensors, the same world every time.
#include <gtest/gtest.h>

#include <cmath>

#include "physics/trig.h"

#include "game/level/level_builder.h"
#include "game/level/level_loader.h"
#include "game/level/tiled_reader.h"
#include "level_test_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace level_loader_test {

using game::Level;
using game::LevelObjectKind;
using level_test::chainLoopSizes;
using level_test::countShapes;
using level_test::levelPath;
using rc::ShapeType;

constexpr float kEps = 1e-5f;

void expectNear(rc::Vec2 a, rc::Vec2 b, float eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
}

int spawnsOf(const Level& level, game::SpawnKind kind) {
  int n = 0;
  for (const game::LevelSpawn& s : level.spawns)
    n += s.kind == kind ? 1 : 0;
  return n;
}

// corridors.tmj, 40 x 24 tiles of 32 px at 32 px/m. Walls: the border ring, a band A over
// rows 6-7 from the left border to column 29 with glass at columns 12-15 (cutting A into a
// part joined to the border and an island of columns 16-29), a band B over rows 14-15 from
// column 10 to the right border, a 2x2 metal block (tiles whose collision shape is a full
// rectangle: merged like plain solid tiles). Wall material: outer loop 4 links, the inside
// of the border 12 (corners (1,1) (39,1) (39,14) (10,14) (10,16) (39,16) (39,23) (1,23)
// (1,8) (12,8) (12,6) (1,6)), the island 4; plus two thin walls (one flipped diagonally),
// two corner triangles (flipped) and a pillar circle. Glass and metal: 4 links each.
TEST(LevelLoader, CorridorsAsCountedByHand) {
  const Level level = game::loadLevel(levelPath("corridors.tmj"));
  ASSERT_EQ(level.objects.size(), 7u);
  const game::LevelObject& walls = level.objects[0];
  EXPECT_EQ(walls.kind, LevelObjectKind::tiles);
  EXPECT_EQ(walls.layer, "walls");
  EXPECT_EQ(chainLoopSizes(walls.shapes), (std::vector<int>{4, 12, 4}));
  EXPECT_EQ(countShapes(walls.shapes, ShapeType::box), 2);
  EXPECT_EQ(countShapes(walls.shapes, ShapeType::polygon), 2);
  EXPECT_EQ(countShapes(walls.shapes, ShapeType::circle), 1);
  EXPECT_EQ(walls.shapes.size(), 25u);
  const game::LevelObject& glass = level.objects[1];
  EXPECT_EQ(chainLoopSizes(glass.shapes), (std::vector<int>{4}));
  EXPECT_FLOAT_EQ(glass.material.thickness, 0.05f);
  EXPECT_FALSE(glass.material.hard);
  EXPECT_FLOAT_EQ(glass.material.health, 20.0f);
  const game::LevelObject& metal = level.objects[2];
  EXPECT_EQ(chainLoopSizes(metal.shapes), (std::vector<int>{4}));
  EXPECT_FLOAT_EQ(metal.material.restitution, 0.5f);

  // The thin wall at column 20, row 10: its rectangle (0, 12, 32, 8) in the tile; the one at
  // column 25 is flipped diagonally, so it stands upright.
  std::vector<rc::Box> boxes;
  for (const rc::Shape& s : walls.shapes)
    if (s.type == ShapeType::box) boxes.push_back(s.box);
  ASSERT_EQ(boxes.size(), 2u);
  expectNear(boxes[0].center, {20.5f, -10.5f});
  expectNear(boxes[0].halfExtents, {0.5f, 0.125f});
  expectNear(boxes[1].center, {25.5f, -10.5f});
  expectNear(boxes[1].halfExtents, {0.125f, 0.5f});
  // The corner tiles: the triangle (0,0) (32,0) (0,32) of the tile, flipped horizontally at
  // column 38, row 1 (the top-right corner of the cell) and vertically at column 1, row 22
  // (the bottom-left).
  std::vector<std::vector<rc::Vec2>> triangles;
  for (const rc::Shape& s : walls.shapes)
    if (s.type == ShapeType::polygon)
      triangles.push_back({s.polygon.vertices, s.polygon.vertices + s.polygon.count});
  const std::vector<std::vector<rc::Vec2>> corners = {{{39, -1}, {38, -1}, {39, -2}},
                                                      {{1, -23}, {2, -23}, {1, -22}}};
  ASSERT_EQ(triangles.size(), 2u);
  for (std::size_t t = 0; t < 2; ++t) {
    ASSERT_EQ(triangles[t].size(), 3u);
    for (const rc::Vec2 want : corners[t]) {
      bool found = false;
      for (const rc::Vec2 v : triangles[t])
        found = found || (std::fabs(v.x - want.x) < kEps && std::fabs(v.y - want.y) < kEps);
      EXPECT_TRUE(found) << "triangle " << t << " lacks (" << want.x << ", " << want.y << ")";
    }
  }
  // The pillar: an ellipse (4, 4, 24, 24) in the tile at column 5, row 11.
  for (const rc::Shape& s : walls.shapes)
    if (s.type == ShapeType::circle) {
      expectNear(s.circle.center, {5.5f, -11.5f});
      EXPECT_NEAR(s.circle.radius, 0.375f, kEps);
    }

  EXPECT_EQ(level.objects[3].kind, LevelObjectKind::trigger);
  expectNear(level.objects[3].position, {2.0f, -22.0f});
  EXPECT_EQ(level.objects[4].kind, LevelObjectKind::trigger);
  EXPECT_EQ(level.objects[4].shapes[0].type, ShapeType::polygon);
  EXPECT_EQ(level.objects[5].kind, LevelObjectKind::prop);
  EXPECT_FLOAT_EQ(level.objects[5].material.health, 40.0f);
  EXPECT_EQ(level.objects[6].kind, LevelObjectKind::prop);
  EXPECT_NEAR(level.objects[6].angle, -15.0f * 3.14159265f / 180.0f, 1e-6f);

  EXPECT_EQ(spawnsOf(level, game::SpawnKind::player), 3);
  EXPECT_EQ(spawnsOf(level, game::SpawnKind::bot), 3);
  expectNear(level.spawns[0].position, {2.5f, -3.0f});
  EXPECT_EQ(level.spawns[0].team, 0);
  EXPECT_EQ(level.spawns[3].kind, game::SpawnKind::bot);
  EXPECT_EQ(level.spawns[3].team, 1);
  EXPECT_NEAR(level.spawns[3].facing, -3.14159265f, 1e-6f);  // 180 degrees either way
  ASSERT_EQ(level.pickups.size(), 2u);
  EXPECT_EQ(level.pickups[0].item, "health");
  EXPECT_FLOAT_EQ(level.pickups[0].amount, 25.0f);
  EXPECT_FLOAT_EQ(level.pickups[0].respawn, 20.0f);
  ASSERT_EQ(level.triggers.size(), 2u);
  EXPECT_EQ(level.triggers[0].action, "exit");
  EXPECT_EQ(level.triggers[0].object, 3u);
  EXPECT_EQ(level.triggers[1].action, "kill");
  ASSERT_EQ(level.paths.size(), 1u);
  EXPECT_EQ(level.paths[0].points.size(), 5u);
  EXPECT_FALSE(level.paths[0].loop);
  ASSERT_EQ(level.markers.size(), 1u);
  EXPECT_EQ(level.markers[0].type, "camera");

  EXPECT_EQ(level.settings.gravity, (rc::Vec2{0, 0}));
  EXPECT_FLOAT_EQ(level.settings.pixelsPerMeter, 32.0f);
  expectNear(level.settings.bounds.lower, {0, -24});
  expectNear(level.settings.bounds.upper, {40, 0});
}

// arena.tmj, 48 x 32 tiles: a border ring (2 loops of 4) with 4 pillar tiles; a group layer
// "cover" (friction 0.5, inherited) of 9 walls: a box, a box turned 45 degrees, a box turned
// 90 (extents swapped, angle 0), a round ellipse (circle), a flat one (octagon), an L (2
// convex pieces), a U (3), a hexagon, an open fence polyline (2 links); 10 props: 4 crates, 3
// barrels and 3 tile objects (2 crates, a barrel: boxes); a hazard trigger (circle).
TEST(LevelLoader, ArenaAsCountedByHand) {
  const Level level = game::loadLevel(levelPath("arena.tmj"));
  // The files it was read from, which the commands never write over: the map and its tileset.
  EXPECT_EQ(level.files,
            (std::vector<std::string>{levelPath("arena.tmj"), levelPath("tiles.tsj")}));
  ASSERT_EQ(level.objects.size(), 21u);
  const auto& o = level.objects;
  EXPECT_EQ(chainLoopSizes(o[0].shapes), (std::vector<int>{4, 4}));
  EXPECT_EQ(countShapes(o[0].shapes, ShapeType::circle), 4);
  const std::vector<ShapeType> cover = {
      ShapeType::box,     ShapeType::box,     ShapeType::box,
      ShapeType::circle,  ShapeType::polygon, ShapeType::polygon,
      ShapeType::polygon, ShapeType::polygon, ShapeType::chainSegment};
  const std::vector<std::size_t> pieces = {1, 1, 1, 1, 1, 2, 3, 1, 2};
  for (std::size_t i = 0; i < cover.size(); ++i) {
    SCOPED_TRACE("cover object " + std::to_string(i + 1));
    EXPECT_EQ(o[1 + i].kind, LevelObjectKind::wall);
    EXPECT_EQ(o[1 + i].layer, "cover/blocks");
    EXPECT_FLOAT_EQ(o[1 + i].material.friction, 0.5f);
    ASSERT_EQ(o[1 + i].shapes.size(), pieces[i]);
    EXPECT_EQ(o[1 + i].shapes[0].type, cover[i]);
  }
  // The 45-degree wall: 128 x 32 at (700, 300), turned clockwise about its top-left corner.
  EXPECT_NEAR(o[2].angle, -3.14159265f / 4, 1e-6f);
  expectNear(o[2].position,
             {(700 + (64 - 16) * 0.70710678f) / 32, -(300 + (64 + 16) * 0.70710678f) / 32}, 1e-4f);
  // The 90-degree wall: 96 x 32 at (1100, 600); its centre lands at (1084, 648) px.
  EXPECT_EQ(o[3].angle, 0.0f);
  expectNear(o[3].position, {1084.0f / 32, -648.0f / 32});
  expectNear(o[3].shapes[0].box.halfExtents, {0.5f, 1.5f});
  EXPECT_EQ(chainLoopSizes(o[9].shapes), (std::vector<int>{-2}));  // open: two-sided links
  for (std::size_t i = 10; i < 20; ++i) {
    EXPECT_EQ(o[i].kind, LevelObjectKind::prop);
    EXPECT_EQ(o[i].bodyType, rc::BodyType::dynamicBody);
    EXPECT_GT(o[i].linearDamping, 0.0f);
  }
  EXPECT_EQ(o[14].shapes[0].type, ShapeType::circle);  // barrel
  // A tile object: its (x, y) is its bottom-left; type and material from the tile.
  EXPECT_EQ(o[17].type, "crate");
  expectNear(o[17].position, {1016.0f / 32, -884.0f / 32});
  EXPECT_FLOAT_EQ(o[17].material.density, 0.8f);
  EXPECT_FLOAT_EQ(o[17].material.thickness, 0.3f);
  EXPECT_EQ(o[19].type, "barrel");
  EXPECT_EQ(o[20].kind, LevelObjectKind::trigger);
  EXPECT_EQ(o[20].shapes[0].type, ShapeType::circle);
  ASSERT_EQ(level.triggers.size(), 1u);
  EXPECT_EQ(level.triggers[0].action, "hurt");

  EXPECT_EQ(spawnsOf(level, game::SpawnKind::player), 4);
  EXPECT_EQ(spawnsOf(level, game::SpawnKind::bot), 8);
  EXPECT_EQ(level.pickups.size(), 4u);
  EXPECT_TRUE(level.paths.empty());
}

// maze.tmj: a 33 x 33 perfect maze (a tree of passages), so its walls are one region with one
// hole: two loops, the outside a square of 4 links; its inside has as many links as corners.
TEST(LevelLoader, MazeIsTwoLoops) {
  const Level level = game::loadLevel(levelPath("maze.tmj"));
  ASSERT_EQ(level.objects.size(), 2u);
  const std::vector<int> loops = chainLoopSizes(level.objects[0].shapes);
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0], 4);
  EXPECT_EQ(level.objects[0].shapes.size(), static_cast<std::size_t>(loops[0] + loops[1]));
  EXPECT_GT(loops[1], 100);
  EXPECT_EQ(level.objects[1].kind, LevelObjectKind::trigger);
  EXPECT_EQ(spawnsOf(level, game::SpawnKind::player), 3);
  EXPECT_EQ(spawnsOf(level, game::SpawnKind::bot), 4);
  EXPECT_EQ(level.pickups.size(), 3u);
}

TEST(LevelBuilder, EveryObjectIsABodyNamedByItsUserData) {
  for (const char* name : {"corridors.tmj", "arena.tmj", "maze.tmj"}) {
    SCOPED_TRACE(name);
    const Level level = game::loadLevel(levelPath(name));
    rc::World world(game::levelWorldDef(level));
    const game::BuiltLevel built = game::buildLevel(level, world);
    ASSERT_EQ(built.bodies.size(), level.objects.size());
    EXPECT_EQ(world.bodyCount(), static_cast<int>(level.objects.size()));
    std::size_t shapes = 0;
    for (std::size_t i = 0; i < level.objects.size(); ++i) {
      const game::LevelObject& o = level.objects[i];
      const rc::BodyId id = built.bodies[i];
      shapes += o.shapes.size();
      const auto ref = game::levelRefOf(world.userData(id));
      ASSERT_TRUE(ref.has_value());
      EXPECT_EQ(ref->index, i);
      EXPECT_EQ(ref->kind, o.kind);
      EXPECT_EQ(world.type(id), o.bodyType);
      for (const rc::ShapeId s : world.shapesOf(id)) {
        EXPECT_EQ(world.userData(s), world.userData(id));
        EXPECT_EQ(world.isSensor(s), o.kind == LevelObjectKind::trigger);
        EXPECT_FLOAT_EQ(world.friction(s), o.material.friction);
      }
      if (o.bodyType == rc::BodyType::dynamicBody) {
        EXPECT_GT(world.mass(id), 0.0f);
      }
    }
    EXPECT_EQ(world.shapeCount(), static_cast<int>(shapes));
    EXPECT_EQ(built.spawns.size(), level.spawns.size());
    ASSERT_EQ(built.triggers.size(), level.triggers.size());
    for (const game::BuiltTrigger& t : built.triggers)
      EXPECT_EQ(t.body, built.bodies[t.object]);
    EXPECT_EQ(world.def().gravity, (rc::Vec2{0, 0}));
    EXPECT_FALSE(game::levelRefOf(0).has_value());
    EXPECT_FALSE(game::levelRefOf(12345).has_value());
  }
}

TEST(LevelBuilder, SameLevelSameWorld) {
  for (const char* name : {"corridors.tmj", "arena.tmj", "maze.tmj"}) {
    SCOPED_TRACE(name);
    std::uint64_t hashes[2];
    for (std::uint64_t& hash : hashes) {
      const Level level = game::loadLevel(levelPath(name));
      rc::World world(game::levelWorldDef(level));
      game::buildLevel(level, world);
      for (int i = 0; i < 30; ++i)
        world.step(1.0f / 60.0f);
      hash = world.stateHash();
    }
    EXPECT_EQ(hashes[0], hashes[1]);
  }
}

// Props sit still in a level without gravity, and nothing starts overlapping: a level that
// opens with bodies pushing each other apart is a broken level.
TEST(LevelBuilder, BundledLevelsStartAtRest) {
  for (const char* name : {"corridors.tmj", "arena.tmj", "maze.tmj"}) {
    SCOPED_TRACE(name);
    const Level level = game::loadLevel(levelPath(name));
    rc::World world(game::levelWorldDef(level));
    const game::BuiltLevel built = game::buildLevel(level, world);
    for (int i = 0; i < 60; ++i)
      world.step(1.0f / 60.0f);
    for (std::size_t i = 0; i < level.objects.size(); ++i) {
      if (level.objects[i].bodyType != rc::BodyType::dynamicBody) continue;
      const rc::Vec2 moved = world.position(built.bodies[i]) - level.objects[i].position;
      EXPECT_LT(std::hypot(moved.x, moved.y), 1e-3f) << "object " << level.objects[i].tiledId;
    }
  }
}

// The merged walls face the right way: balls fired from the player's spawn in every direction
// bounce around inside the walls (the insides of the borders are hole loops), keep moving, and
// never leave the map. Walls facing the wrong way let the balls into the wall band, where
// they stick (continuous collision stops them at the back of a one-sided link).
TEST(LevelBuilder, BallsBounceInsideMergedWalls) {
  for (const char* name : {"corridors.tmj", "arena.tmj", "maze.tmj"}) {
    SCOPED_TRACE(name);
    const Level level = game::loadLevel(levelPath(name));
    rc::World world(game::levelWorldDef(level));
    game::buildLevel(level, world);
    std::vector<rc::BodyId> balls;
    for (int i = 0; i < 16; ++i) {
      const rc::SinCos sc = rc::sincos(static_cast<float>(i) * rc::kPi / 8.0f);
      const float speed = 10.0f + 5.0f * static_cast<float>(i % 4);
      rc::BodyDef bd;
      bd.type = rc::BodyType::dynamicBody;
      bd.position = level.spawns[0].position;
      bd.linearVelocity = {speed * sc.cosine, speed * sc.sine};
      rc::ShapeDef sd;
      sd.restitution = 1.0f;
      sd.friction = 0.0f;
      sd.filter.category = 1u << 8;
      sd.filter.mask = ~(1u << 8);  // through each other, not through walls
      balls.push_back(world.createBody(bd));
      world.createShape(balls.back(), rc::makeCircle({0, 0}, 0.2f), sd);
    }
    std::vector<float> path(balls.size(), 0.0f);  // over the last second
    for (int step = 0; step < 180; ++step) {
      std::vector<rc::Vec2> before;
      for (const rc::BodyId b : balls)
        before.push_back(world.position(b));
      world.step(1.0f / 60.0f);
      for (std::size_t i = 0; i < balls.size() && step >= 120; ++i) {
        const rc::Vec2 d = world.position(balls[i]) - before[i];
        path[i] += std::hypot(d.x, d.y);
      }
    }
    const rc::AABB& map = level.settings.bounds;
    for (std::size_t i = 0; i < balls.size(); ++i) {
      const rc::Vec2 p = world.position(balls[i]);
      EXPECT_TRUE(p.x > map.lower.x + 1 && p.x < map.upper.x - 1 && p.y > map.lower.y + 1 &&
                  p.y < map.upper.y - 1)
          << "ball " << i << " left through the border, at (" << p.x << ", " << p.y << ")";
      EXPECT_GT(path[i], 5.0f) << "ball " << i << " is stuck at (" << p.x << ", " << p.y << ")";
    }
  }
}

// Tiled turns every object about its (x, y): a rectangle, the same rectangle drawn as a
// polygon, and an ellipse in the same box, turned alike, land on the same place, whether the
// turn is a quarter (exact) or any other angle (the body's).
TEST(LevelLoader, RotatedObjectsTurnAboutTheirOrigin) {
  for (const double degrees : {0.0, 30.0, 90.0, 180.0, 270.0, -45.0, 395.0}) {
    SCOPED_TRACE("rotation " + std::to_string(degrees));
    const std::string r = std::to_string(degrees);
    const std::string text = R"({"type": "map", "orientation": "orthogonal", "width": 20,
      "height": 20, "tilewidth": 32, "tileheight": 32, "layers": [{"id": 1, "name": "o",
      "type": "objectgroup", "objects": [
        {"id": 1, "x": 100, "y": 120, "width": 64, "height": 32, "rotation": )" +
                             r + R"(},
        {"id": 2, "x": 100, "y": 120, "rotation": )" +
                             r + R"(, "polygon": [{"x": 0, "y": 0},
          {"x": 64, "y": 0}, {"x": 64, "y": 32}, {"x": 0, "y": 32}]},
        {"id": 3, "x": 100, "y": 120, "width": 64, "height": 32, "ellipse": true,
         "rotation": )" + r + R"(},
        {"id": 4, "x": 100, "y": 120, "rotation": )" +
                             r + R"(, "polyline": [{"x": 0, "y": 0},
          {"x": 64, "y": 0}, {"x": 64, "y": 32}]}]}]})";
    const Level level = game::levelFromMap(game::parseTiledMap(text, "turns.tmj", "."));
    rc::World world(game::levelWorldDef(level));
    const game::BuiltLevel built = game::buildLevel(level, world);
    // The corners by hand: (x, y) + R(clockwise) (dx, dy), in pixels, then y flipped.
    const double c = std::cos(degrees * 3.14159265358979 / 180),
                 s = std::sin(degrees * 3.14159265358979 / 180);
    auto corner = [&](double dx, double dy) {
      return rc::Vec2{static_cast<float>((100 + dx * c - dy * s) / 32),
                      static_cast<float>(-(120 + dx * s + dy * c) / 32)};
    };
    const rc::Vec2 expected[4] = {corner(0, 0), corner(64, 0), corner(64, 32), corner(0, 32)};
    // The box's corners, the polygon's vertices and the polyline's points, in the world.
    const rc::Transform box = world.transform(built.bodies[0]);
    const rc::Box& b = world.shape(world.shapesOf(built.bodies[0])[0]).box;
    std::vector<rc::Vec2> boxCorners;
    for (const rc::Vec2 k : {rc::Vec2{-1, 1}, rc::Vec2{1, 1}, rc::Vec2{1, -1}, rc::Vec2{-1, -1}})
      boxCorners.push_back(
          rc::apply(box, {b.center.x + k.x * b.halfExtents.x, b.center.y + k.y * b.halfExtents.y}));
    const rc::Transform poly = world.transform(built.bodies[1]);
    const rc::Polygon& pg = world.shape(world.shapesOf(built.bodies[1])[0]).polygon;
    ASSERT_EQ(pg.count, 4);
    const rc::Transform line = world.transform(built.bodies[3]);
    const auto links = world.shapesOf(built.bodies[3]);
    ASSERT_EQ(links.size(), 2u);
    const rc::Vec2 linePoints[3] = {
        rc::apply(line, world.shape(links[0]).chainSegment.segment.point1),
        rc::apply(line, world.shape(links[1]).chainSegment.segment.point1),
        rc::apply(line, world.shape(links[1]).chainSegment.segment.point2)};
    for (int i = 0; i < 3; ++i)
      expectNear(linePoints[i], expected[i], 1e-5f);
    for (const rc::Vec2 e : expected) {
      auto nearest = [&](const auto& points) {
        float best = 1e9f;
        for (const rc::Vec2 q : points)
          best = std::min(best, std::hypot(q.x - e.x, q.y - e.y));
        return best;
      };
      std::vector<rc::Vec2> polyCorners;
      for (int i = 0; i < pg.count; ++i)
        polyCorners.push_back(rc::apply(poly, pg.vertices[i]));
      EXPECT_LT(nearest(boxCorners), 1e-5f);
      EXPECT_LT(nearest(polyCorners), 1e-5f);
    }
    const rc::Vec2 centre = 0.5f * (expected[0] + expected[2]);
    expectNear(world.worldCenter(built.bodies[0]), centre, 1e-5f);
    expectNear(world.worldCenter(built.bodies[2]), centre, 1e-5f);
  }
}

}  // namespace level_loader_test
