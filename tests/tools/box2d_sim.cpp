// box2d_sim SCENE.json --steps N [--out STATE.json]: the same scene file run on Box2D 2.4.1,
// writing the same state format as `ricochet sim`, so any scene can be compared between the
// two engines. Built with the tests (it links Box2D); exit codes as ricochet sim's.
#include <charconv>
#include <cstdio>
#include <string>
#include <string_view>

#include "game/run_files.h"
#include "support/box2d_world.h"

int main(int argc, char** argv) {
  std::string scenePath, outPath;
  long steps = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--help" || a == "-h") {
      std::puts("usage: box2d_sim SCENE.json --steps N [--out STATE.json]");
      return 0;
    }
    if ((a == "--steps" || a == "--out") && i + 1 >= argc) {
      std::fprintf(stderr, "box2d_sim: %s needs a value\n", argv[i]);
      return 2;
    }
    if (a == "--steps") {
      const std::string_view v = argv[++i];
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), steps);
      if (ec != std::errc() || end != v.data() + v.size() || steps < 0) {
        std::fprintf(stderr, "box2d_sim: --steps must be a whole number >= 0\n");
        return 2;
      }
    } else if (a == "--out") {
      outPath = argv[++i];
    } else if (scenePath.empty() && !a.empty() && a[0] != '-') {
      scenePath = std::string(a);
    } else {
      std::fprintf(stderr, "box2d_sim: unexpected argument '%s'\n", argv[i]);
      return 2;
    }
  }
  if (scenePath.empty() || steps < 0) {
    std::fprintf(stderr, "box2d_sim: usage: box2d_sim SCENE.json --steps N [--out STATE.json]\n");
    return 2;
  }
  // --out: not the scene, not a directory, in a directory that exists; before the run, as
  // ricochet sim checks it.
  const game::RunInput inputs[] = {{"the scene", scenePath}};
  const game::RunOutput out{"--out", outPath};
  auto outError = game::outputOverwritesAnother({&out, 1}, inputs);
  if (!outError) outError = game::outputFileUnwritable(out);
  if (outError) {
    std::fprintf(stderr, "box2d_sim: %s\n", outError->message.c_str());
    return outError->exitCode;
  }
  try {
    const game::SceneDesc scene = game::loadScene(scenePath);
    rc::testing::Box2DScene box2d(scene);
    for (long k = 0; k < steps; ++k)
      box2d.step(scene.dt);
    const game::SceneState state =
        box2d.state(scene, static_cast<int>(steps), static_cast<double>(steps) * scene.dt);
    if (!outPath.empty()) game::writeFileAtomically(outPath, game::stateToJson(state));
    std::printf("steps %ld time %.6f\n", steps, state.time);
    return 0;
  } catch (const game::SceneError& e) {
    std::fprintf(stderr, "box2d_sim: %s\n", e.what());
    return 1;
  }
}
