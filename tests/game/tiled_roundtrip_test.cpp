// The bundled levels open in the real Tiled editor: Tiled loads each one and exports it again
// (`tiled --export-map json`, headless), and the exported map builds the same world as the
// original: the same bodies, shapes, spawns, pickups, triggers and paths at the same places,
// and the same world state hash. Skipped when Tiled is not installed (Debian's `tiled`).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "game/level/level_builder.h"
#include "game/level/level_loader.h"
#include "level_test_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace tiled_roundtrip_test {

std::string findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return "";
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(dir) / program;
    std::error_code ec;
    if (!dir.empty() && std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
  }
  return "";
}

struct Built {
  game::Level level;
  std::uint64_t hash = 0;
  int bodies = 0, shapes = 0;
};

Built build(const std::string& path) {
  Built b;
  b.level = game::loadLevel(path);
  rc::World world(game::levelWorldDef(b.level));
  game::buildLevel(b.level, world);
  b.hash = world.stateHash();
  b.bodies = world.bodyCount();
  b.shapes = world.shapeCount();
  return b;
}

TEST(TiledRoundTrip, ExportedLevelsBuildTheSameWorld) {
  const std::string tiled = findOnPath("tiled");
  if (tiled.empty()) GTEST_SKIP() << "tiled is not installed (apt-get install tiled)";
  level_test::ScratchDir dir;
  for (const char* name : {"corridors.tmj", "arena.tmj", "maze.tmj"}) {
    SCOPED_TRACE(name);
    const std::string original = level_test::levelPath(name), exported = dir.file(name);
    // Offscreen: no display needed. Tiled rewrites the tileset's path relative to the copy.
    const std::string command = "QT_QPA_PLATFORM=offscreen '" + tiled + "' --export-map json '" +
                                original + "' '" + exported + "' > '" + dir.file("log") + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    ASSERT_TRUE(std::filesystem::exists(exported));
    const Built a = build(original), b = build(exported);
    EXPECT_EQ(a.bodies, b.bodies);
    EXPECT_EQ(a.shapes, b.shapes);
    ASSERT_EQ(a.level.objects.size(), b.level.objects.size());
    for (std::size_t i = 0; i < a.level.objects.size(); ++i) {
      EXPECT_EQ(a.level.objects[i].position, b.level.objects[i].position);
      EXPECT_EQ(a.level.objects[i].angle, b.level.objects[i].angle);
      EXPECT_EQ(a.level.objects[i].shapes.size(), b.level.objects[i].shapes.size());
      EXPECT_EQ(a.level.objects[i].material, b.level.objects[i].material);
    }
    ASSERT_EQ(a.level.spawns.size(), b.level.spawns.size());
    for (std::size_t i = 0; i < a.level.spawns.size(); ++i)
      EXPECT_EQ(a.level.spawns[i].position, b.level.spawns[i].position);
    EXPECT_EQ(a.level.pickups.size(), b.level.pickups.size());
    EXPECT_EQ(a.level.triggers.size(), b.level.triggers.size());
    EXPECT_EQ(a.level.paths.size(), b.level.paths.size());
    EXPECT_EQ(a.level.markers.size(), b.level.markers.size());
    // Everything that decides the simulation, bit for bit.
    EXPECT_EQ(a.hash, b.hash);
  }
}

}  // namespace tiled_roundtrip_test
