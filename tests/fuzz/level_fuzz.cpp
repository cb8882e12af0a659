// libFuzzer target: the Tiled level reader on arbitrary bytes (a .tmj map; its external tileset
// is the bundled assets/levels/tiles.tsj), and every level it accepts built into a world and
// stepped, under ASan+UBSan. A bad map is a LevelError: one line, never a crash, a hang or an
// allocation beyond the map's declared limits. Seed corpus: assets/levels; dictionary:
// level.dict.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "game/level/level_builder.h"
#include "game/level/level_error.h"
#include "game/level/level_loader.h"
#include "game/level/tiled_reader.h"
#include "physics/world.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const game::TiledMap map =
        game::parseTiledMap(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz",
                            std::string(RICOCHET_SOURCE_DIR) + "/assets/levels");
    const game::Level level = game::levelFromMap(map);
    rc::World world(game::levelWorldDef(level));
    game::buildLevel(level, world);
    for (int i = 0; i < 2; ++i)
      world.step(1.0f / 60.0f);
  } catch (const game::LevelError&) {
  }
  return 0;
}
