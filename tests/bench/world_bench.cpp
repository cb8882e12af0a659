// The world race: our World (physics/world.h) against Box2D 2.4.1's b2World stepping the same
// seeded scenes at 60 Hz, in the same run. Not part of ctest; run
//   ./build/release/tests/world_bench [--benchmark_filter=...] [--table=FILE.md]
//
// Scenes (the issue's), built from one description so both engines get the same bodies:
//   arena/N      a 200 m box of walls with 20 static box obstacles, N circles of radius 0.5 m
//                at 5 m/s, restitution 0.5, friction 0.2, no gravity. Time per step.
//   bullets      the 1000-circle arena plus 500 circles of radius 0.05 m at 100 m/s with
//                continuous collision (Box2D: bullet bodies), respawned when slower than
//                20 m/s. Counter: bullets that left the arena (escapes: the centre more than
//                the radius past a wall's inner face). Time per step.
//   pyramid/B    touching 1 m boxes, base B, friction 0.6, on a static ground box, gravity -10,
//                1000 steps, sleeping off (and again with sleeping on in both engines). Counters:
//                the top box's drift from its exact resting height and its creep sideways from
//                where it was placed (m). Time per step.
// What a scene lacks costs nothing (the rows to read against arena/N=1000 and pyramid/base 20):
//   arena, 20k static boxes outside   20,000 more static boxes beyond the walls
//   arena, continuous off             no continuous collision in either engine
//   arena, fixed rotation             every circle with fixed rotation
//   pyramid asleep/base 20            the base-20 pyramid after it has fallen asleep
// Each engine runs with its defaults: Box2D 8 velocity and 3 position iterations, ours 4
// substeps. The scenes and both engines' builders are in world_scenes.h.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench/ratio_table.h"
#include "bench/world_scenes.h"

namespace {

using world_scenes::arena;
using world_scenes::pyramid;
using world_scenes::SceneDesc;
using world_scenes::Vec2;

// ------------------------------------------------------------------------------- benchmarks

template <class Engine>
void runArena(benchmark::State& state, const SceneDesc& scene, int steps) {
  double escapes = 0;
  for (auto _ : state) {
    state.PauseTiming();
    world_scenes::Run<Engine> run(scene);
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k)
      run.step();
    state.PauseTiming();
    escapes += run.escapes();
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * steps);
  if (scene.bulletCount > 0)
    state.counters["escapes"] = escapes / static_cast<double>(state.iterations());
}

template <class Engine>
void runPyramid(benchmark::State& state, const SceneDesc& scene, int steps) {
  double drift = 0, creep = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Engine engine(scene);
    for (int k = 0; k < scene.settleSteps; ++k)
      engine.step();
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k)
      engine.step();
    state.PauseTiming();
    const Vec2 top = engine.position(scene.bodies.size() - 1);
    drift += std::abs(top.y - scene.bodies.back().position.y);
    creep += std::abs(top.x - scene.bodies.back().position.x);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * steps);
  state.counters["top_drift_m"] = drift / static_cast<double>(state.iterations());
  state.counters["top_creep_m"] = creep / static_cast<double>(state.iterations());
}

enum class Kind { arena, pyramid };

// Registers "name/ours" and "name/box2d" on the same scene (or ours alone).
void race(const std::string& name, const SceneDesc* s, Kind kind, bool withBox2D = true) {
  auto run = [s, kind]<class Engine>(benchmark::State& st) {
    if (kind == Kind::arena)
      runArena<Engine>(st, *s, 300);
    else
      runPyramid<Engine>(st, *s, 1000);
  };
  auto* ours = benchmark::RegisterBenchmark(
      (name + (withBox2D ? "/ours" : "")).c_str(),
      [run](benchmark::State& st) { run.template operator()<world_scenes::Ours>(st); });
  ours->Unit(benchmark::kMillisecond);
  if (kind == Kind::pyramid) ours->Iterations(1);  // 1000 steps of a pyramid is long enough
  if (!withBox2D) return;
  auto* theirs = benchmark::RegisterBenchmark(
      (name + "/box2d").c_str(),
      [run](benchmark::State& st) { run.template operator()<world_scenes::Box2D>(st); });
  theirs->Unit(benchmark::kMillisecond);
  if (kind == Kind::pyramid) theirs->Iterations(1);
}

void registerAll() {
  static std::vector<std::unique_ptr<SceneDesc>> scenes;
  auto add = [](SceneDesc s) {
    scenes.push_back(std::make_unique<SceneDesc>(std::move(s)));
    return scenes.back().get();
  };
  for (int n : {100, 1000, 5000})
    race("arena/N=" + std::to_string(n), add(arena(n, 0, 0, 7)), Kind::arena);
  // What a scene that does not turn saves: the same 1000-circle arena with fixed rotation.
  SceneDesc still = arena(1000, 0, 0, 7);
  still.fixedRotation = true;
  race("arena, fixed rotation/N=1000", add(still), Kind::arena);
  // Static geometry never enters a per-step loop: 20,000 more static boxes outside the walls,
  // where nothing reaches them, should cost nothing per step.
  SceneDesc decorated = arena(1000, 0, 0, 7);
  for (float x = -126.5f; x <= 126.5f; x += 1.0f)
    for (float y = -126.5f; y <= 126.5f; y += 1.0f)
      if (std::max(std::abs(x), std::abs(y)) > 103.0f)
        decorated.statics.push_back({{x, y}, {0.2f, 0.2f}});
  race("arena, 20k static boxes outside/N=1000", add(decorated), Kind::arena);
  // No fast bodies, no continuous work: the same arena with continuous collision off.
  SceneDesc discrete = arena(1000, 0, 0, 7);
  discrete.continuous = false;
  race("arena, continuous off/N=1000", add(discrete), Kind::arena);
  race("bullets/100 m per s", add(arena(1000, 500, 100.0f, 8)), Kind::arena);
  // Ours alone at 1000 m/s (Box2D 2.4.1 caps motion at 2 m per step: 120 m/s).
  race("bullets 1000 m per s (ours alone)", add(arena(1000, 500, 1000.0f, 8)), Kind::arena, false);
  for (int base : {20, 40}) {
    race("pyramid/base " + std::to_string(base), add(pyramid(base)), Kind::pyramid);
    // The same pyramid with sleeping on in both engines: what a scene at rest costs.
    SceneDesc sleeping = pyramid(base);
    sleeping.sleep = true;
    race("pyramid, sleeping on/base " + std::to_string(base), add(sleeping), Kind::pyramid);
  }
  // Nothing awake costs almost nothing: the base-20 pyramid once it has fallen asleep in both
  // engines (untimed 1200 steps first), then 1000 timed steps.
  SceneDesc asleep = pyramid(20);
  asleep.sleep = true;
  asleep.settleSteps = 1200;
  race("pyramid asleep/base 20", add(asleep), Kind::pyramid);
}

}  // namespace

int main(int argc, char** argv) {
  return rc::bench::runWithRatioTable(argc, argv, "world_bench", registerAll);
}
