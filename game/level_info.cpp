// `ricochet level LEVEL.tmj [--json]`
// Reads a Tiled level, builds its world and prints what it holds: the map's size, bodies and
// shapes by kind, spawns, pickups, triggers, paths and the built world's state hash. The quick
// check of a level a designer just saved, and what scripts use to compare two levels.
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/level/level_builder.h"
#include "game/level/level_error.h"
#include "game/level/level_loader.h"

namespace game {
namespace {

// A path as a JSON string's contents: quotes, backslashes and control characters escaped.
std::string jsonEscaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", static_cast<unsigned>(c));
      out += code;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

int runLevel(std::span<const std::string_view> args) {
  CLI::App app{
      "Reads a Tiled map (orthogonal, finite; JSON map and tilesets), builds its world and\n"
      "prints one summary line on stdout: the map's size, bodies and shapes, spawns, pickups,\n"
      "triggers, paths, markers and the world's state hash. game/level/README.md lists what a\n"
      "map may hold.\n"
      "Exit codes: 0 done, 1 bad level (one line on stderr naming the file, the layer and the\n"
      "object), 2 bad command line.",
      "ricochet level"};
  std::string path;
  bool json = false;
  app.add_option("level", path, "the level (.tmj)")->required();
  app.add_flag("--json", json, "the summary as a JSON object instead");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet level", args)) return *exit;
  try {
    const Level level = loadLevel(path);
    rc::World world(levelWorldDef(level));
    const BuiltLevel built = buildLevel(level, world);
    int kinds[4] = {};
    for (const LevelObject& o : level.objects)
      ++kinds[static_cast<int>(o.kind)];
    int players = 0, bots = 0;
    for (const LevelSpawn& s : level.spawns)
      ++(s.kind == SpawnKind::player ? players : bots);
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(world.stateHash()));
    const LevelSettings& m = level.settings;
    if (json) {
      std::printf(
          "{\"level\": \"%s\", \"width\": %d, \"height\": %d, \"tileWidth\": %g, "
          "\"tileHeight\": %g, \"gravity\": [%g, %g], \"bodies\": %d, \"shapes\": %d, "
          "\"tiles\": %d, \"walls\": %d, \"props\": %d, \"triggers\": %d, \"players\": %d, "
          "\"bots\": %d, \"pickups\": %zu, \"paths\": %zu, \"markers\": %zu, \"hash\": \"%s\"}\n",
          jsonEscaped(path).c_str(), m.width, m.height, static_cast<double>(m.tileWidth),
          static_cast<double>(m.tileHeight), static_cast<double>(m.gravity.x),
          static_cast<double>(m.gravity.y), world.bodyCount(), world.shapeCount(), kinds[1],
          kinds[0], kinds[2], kinds[3], players, bots, built.pickups.size(), built.paths.size(),
          built.markers.size(), hash);
    } else {
      std::printf(
          "level %s size %dx%d tiles of %gx%g m bodies %d shapes %d (tiles %d walls %d props %d "
          "triggers %d) players %d bots %d pickups %zu paths %zu markers %zu hash %s\n",
          path.c_str(), m.width, m.height, static_cast<double>(m.tileWidth),
          static_cast<double>(m.tileHeight), world.bodyCount(), world.shapeCount(), kinds[1],
          kinds[0], kinds[2], kinds[3], players, bots, built.pickups.size(), built.paths.size(),
          built.markers.size(), hash);
    }
    return 0;
  } catch (const LevelError& e) {
    std::fprintf(stderr, "ricochet level: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ricochet level: %s: %s\n", path.c_str(), e.what());
    return 1;
  }
}

}  // namespace game
