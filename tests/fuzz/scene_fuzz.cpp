// libFuzzer target: the scene reader on arbitrary bytes, and every scene it accepts built into
// a world and stepped, under ASan+UBSan. A bad file is a SceneError (or the world's
// std::invalid_argument for a definition it refuses): one line, never a crash, a hang or an
// allocation beyond the file's size. Seed corpus: assets/scenes; dictionary: scene.dict.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "game/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const game::SceneDesc scene =
        game::parseScene(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    // Scenes of thousands of bodies are valid and slow; the reader is what is fuzzed here.
    if (scene.bodies.size() > 64) return 0;
    game::BuiltWorld built = game::buildWorld(scene);
    for (int i = 0; i < 4; ++i)
      built.world->step(scene.dt);
  } catch (const game::SceneError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
