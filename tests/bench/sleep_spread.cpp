// When a settled pile falls asleep, over copies of one pile that differ only in rounding: the
// world_bench pyramid (touching 1 m boxes, friction 0.6, gravity -10, sleeping on) moved
// sideways as a whole, ground included, by k centimetres (k = 0, 1, ...), which is the same
// scene to the physics and another sequence of roundings to both engines. Per copy, the step at
// which every body is asleep (none within --steps: "never") and the top box's drift (how far it
// sank, world_bench's top_drift_m); then the minimum, median and maximum over the copies, ours
// and Box2D 2.4.1's.
//
// Why: a tall pile's last motions are chaotic (a one-bit change anywhere moves when its top boxes
// stop swinging), so the step one pile falls asleep at is one draw from a wide spread. World
// bench's "pyramid, sleeping on" rows time one copy (k = 0): a change to the solver or to sleep
// can move that row by 2x either way by the draw alone. Judge sleep by the median here. Not part
// of ctest; run
//   ./build/release/tests/sleep_spread [--base B] [--copies K] [--steps N] [--ours-only]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "bench/world_scenes.h"

namespace sleep_spread {

using world_scenes::SceneDesc;

struct Draw {
  int asleep = -1;  // the first step with every body asleep; -1: never within the steps
  double drift = 0;
};

template <class Engine>
Draw run(const SceneDesc& scene, int steps) {
  Engine engine(scene);
  Draw d;
  for (int k = 1; k <= steps; ++k) {
    engine.step();
    if (d.asleep < 0 && engine.awakeCount() == 0) d.asleep = k;
  }
  const std::size_t top = scene.bodies.size() - 1;
  d.drift = std::abs(engine.position(top).y - scene.bodies[top].position.y);
  return d;
}

std::string stepText(int step) {
  return step < 0 ? std::string("never") : std::to_string(step);
}

// A copy's two table cells: "step | drift".
std::string drawText(const Draw& d) {
  char drift[32];
  std::snprintf(drift, sizeof drift, "%.4f", d.drift);
  return stepText(d.asleep) + " | " + drift;
}

// Min, median (the lower middle for an even count) and max; "never" sorts last.
struct Summary {
  int minStep, medianStep, maxStep;
  double minDrift, medianDrift, maxDrift;
};
Summary summarize(const std::vector<Draw>& draws) {
  std::vector<int> steps;
  std::vector<double> drifts;
  for (const Draw& d : draws) {
    steps.push_back(d.asleep < 0 ? std::numeric_limits<int>::max() : d.asleep);
    drifts.push_back(d.drift);
  }
  std::sort(steps.begin(), steps.end());
  std::sort(drifts.begin(), drifts.end());
  const std::size_t mid = (draws.size() - 1) / 2;
  auto never = [](int s) { return s == std::numeric_limits<int>::max() ? -1 : s; };
  return {never(steps.front()), never(steps[mid]), never(steps.back()),
          drifts.front(),       drifts[mid],       drifts.back()};
}

}  // namespace sleep_spread

int main(int argc, char** argv) {
  using namespace sleep_spread;
  int base = 40, copies = 16, steps = 1000;
  bool oursOnly = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--base") == 0 && i + 1 < argc) {
      base = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--copies") == 0 && i + 1 < argc) {
      copies = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
      steps = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--ours-only") == 0) {
      oursOnly = true;
    } else {
      std::fprintf(stderr,
                   "usage: sleep_spread [--base B] [--copies K] [--steps N] [--ours-only]\n");
      return 2;
    }
  }
  if (base < 1 || base > 200 || copies < 1 || steps < 1) {
    std::fprintf(stderr,
                 "sleep_spread: --base must be 1 to 200, --copies and --steps at least 1\n");
    return 2;
  }
  std::vector<Draw> ours, theirs;
  std::printf(
      "| shift (m) | ours asleep at step | ours drift (m) | Box2D 2.4.1 asleep at step | "
      "Box2D drift (m) |\n|---:|---:|---:|---:|---:|\n");
  for (int k = 0; k < copies; ++k) {
    SceneDesc scene = world_scenes::pyramid(base);
    scene.sleep = true;
    const float shift = 0.01f * static_cast<float>(k);
    for (world_scenes::BodyDesc& b : scene.bodies)
      b.position.x += shift;
    for (world_scenes::BoxDesc& b : scene.statics)
      b.center.x += shift;
    ours.push_back(run<world_scenes::Ours>(scene, steps));
    if (!oursOnly) theirs.push_back(run<world_scenes::Box2D>(scene, steps));
    std::printf("| %.2f | %s | %s |\n", static_cast<double>(shift), drawText(ours.back()).c_str(),
                oursOnly ? " | " : drawText(theirs.back()).c_str());
    std::fflush(stdout);
  }
  auto line = [](const char* who, const std::vector<Draw>& draws) {
    const Summary s = summarize(draws);
    std::printf(
        "%s: asleep at step %s / %s / %s, drift %.4f / %.4f / %.4f m (min / median / max)\n", who,
        stepText(s.minStep).c_str(), stepText(s.medianStep).c_str(), stepText(s.maxStep).c_str(),
        s.minDrift, s.medianDrift, s.maxDrift);
  };
  std::printf("\nbase %d, %d copies, %d steps\n", base, copies, steps);
  line("ours", ours);
  if (!oursOnly) line("Box2D 2.4.1", theirs);
  return 0;
}
