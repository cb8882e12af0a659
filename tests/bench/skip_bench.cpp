// What a scene skips, measured: the same scene without and with each thing a scene may lack,
// in our World and in Box2D 2.4.1, in one run. A scene should not pay for what it lacks. Where
// what the "with" scene adds needs no work in a step (static tiles nothing reaches, bodies
// asleep far away), the ratio without / with should be close to 1, and below it the world walks
// what it need not; where it adds work (a pile under gravity, bullets), the ratio is what that
// work costs, and the "without" time should be no more than its scene needs (the phase table
// says where it goes). Not part of ctest; run
//   ./build/release/tests/skip_bench [--rounds N] [--table FILE.md] [--filter TEXT]
// (--filter keeps the rows whose "lacks" column contains TEXT.)
//
// Rows (scenes from world_scenes.h; the arena is world_bench's: 1000 circles in a 200 m box):
//   nothing awake        the base-20 pyramid asleep (sleeping on, 1200 steps to settle) / the
//                        same pile awake with sleeping off (the same 1200 steps first)
//   no rotation          the arena with every circle on fixed rotation / turning freely
//   no gravity           the arena / the same arena with gravity -10 (the box is closed: the
//                        circles fall and pile up on its floor, so "with" does more contact work)
//   no fast bodies       the arena / the arena plus 10 bullets at 1000 m/s (radius 0.05 m,
//                        fired again when slower than 20 m/s; Box2D 2.4.1 caps motion at 2 m a
//                        step, so its bullets fly at 120 m/s)
//   no sensors           the arena / the arena plus 100 static 4 m x 4 m sensor boxes inside it
//   static geometry      the arena / the arena plus world_bench's ring of static 0.4 m tiles
//                        outside its walls, where nothing reaches them
//   sleeping islands     the arena (sleeping on) / the arena plus 5,000 boxes at rest in 500
//                        blocks of 10 touching boxes, 400 to 500 m beyond the walls, asleep
//                        before the timing starts (both: the same world square, 768 m)
// Method: every configuration is built from one seeded description for both engines and
// stepped at 60 Hz with each engine's defaults (ours 4 substeps; Box2D 8 velocity and 3
// position iterations). A measurement builds the world, steps it untimed (the warm-up: settling,
// falling asleep), then times a fixed number of steps by the thread's CPU time; every round
// measures the same simulated steps. Rounds interleave the engines and configurations (row by
// row: ours without, ours with, Box2D without, Box2D with; the other way round every second
// round) so that a slow spell of the shared machine does not fall on one side; each cell is
// the median of the rounds. An untimed pass per configuration a round reads our profile by
// phase; the table gives each phase's share (medians of the rounds) of the measured CPU time.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/cpu_time.h"
#include "bench/world_scenes.h"

namespace skip_bench {

using world_scenes::arena;
using world_scenes::SceneDesc;

struct Config {
  SceneDesc scene;
  int warmup = 60;  // untimed steps first
  int steps = 300;  // timed steps
};

struct Row {
  std::string lacks, scenes;  // what the scene lacks; "without / with" in words
  Config without, with;
};

// What one engine's world held at the end of a measurement, and our phases (ms per step).
struct Work {
  int awake = 0, contacts = 0, escapes = 0;
  rc::Profile phases;
};

// One measurement: CPU seconds per step over the config's timed steps.
template <class Engine>
double measure(const Config& c, Work& work) {
  world_scenes::Run<Engine> run(c.scene);
  for (int k = 0; k < c.warmup; ++k)
    run.step();
  const double start = cpu_time::threadSeconds();
  for (int k = 0; k < c.steps; ++k)
    run.step();
  const double seconds = cpu_time::threadSeconds() - start;
  work.awake = run.engine.awakeCount();
  work.contacts = run.engine.contactCount();
  work.escapes = run.escapes();
  return seconds / c.steps;
}

// Our phases: means over the config's timed steps in an untimed pass with the profile on (its
// clocks, and ours around every step, are kept out of the timed runs), steps the machine
// preempted left out.
rc::Profile phases(const Config& c) {
  SceneDesc profiled = c.scene;
  profiled.profile = true;
  world_scenes::Run<world_scenes::Ours> run(profiled);
  for (int k = 0; k < c.warmup; ++k)
    run.step();
  world_scenes::PhaseSamples samples;
  for (int k = 0; k < c.steps; ++k) {
    const double start = cpu_time::threadSeconds();
    run.step();
    samples.add(run.engine.world->profile(), cpu_time::threadSeconds() - start);
  }
  return samples.means();
}

// Each phase's median over the rounds' passes.
rc::Profile medianPhases(const std::vector<rc::Profile>& passes) {
  auto med = [&](double rc::Profile::*field) {
    std::vector<double> v;
    for (const rc::Profile& p : passes)
      v.push_back(p.*field);
    return cpu_time::median(v);
  };
  rc::Profile m;
  for (double rc::Profile::*f : world_scenes::PhaseSamples::kPhases)
    m.*f = med(f);
  m.total = med(&rc::Profile::total);
  return m;
}

std::vector<Row> rows() {
  std::vector<Row> out;
  const SceneDesc base = arena(1000, 0, 0, 7);

  SceneDesc asleep = world_scenes::pyramid(20), awake = asleep;
  asleep.sleep = true;
  out.push_back({"nothing awake",
                 "base-20 pyramid asleep / awake (sleeping off)",
                 {asleep, 1200, 20000},
                 {awake, 1200, 300}});

  SceneDesc fixed = base;
  fixed.fixedRotation = true;
  out.push_back({"no rotation", "1000 circles, fixed rotation / turning", {fixed}, {base}});

  SceneDesc falling = base;
  falling.gravity = {0, -10};
  out.push_back({"no gravity", "1000 circles, no gravity / gravity -10", {base}, {falling}});

  out.push_back({"no fast bodies",
                 "1000 circles / + 10 bullets at 1000 m/s",
                 {base},
                 {arena(1000, 10, 1000.0f, 7)}});

  SceneDesc triggers = base;
  rc::Random rng(11);
  for (int i = 0; i < 100; ++i)
    triggers.sensors.push_back({rng.inBox({-90, -90}, {90, 90}), {2, 2}});
  out.push_back({"no sensors", "1000 circles / + 100 sensor boxes", {base}, {triggers}});

  // world_bench's ring of tiles outside the walls, within the quadtree's square (+-128 m).
  SceneDesc tiled = base;
  for (float x = -126.5f; x <= 126.5f; x += 1.0f)
    for (float y = -126.5f; y <= 126.5f; y += 1.0f)
      if (std::max(std::abs(x), std::abs(y)) > 103.0f)
        tiled.statics.push_back({{x, y}, {0.2f, 0.2f}});
  std::string tiles = std::to_string(tiled.statics.size() - base.statics.size());
  for (auto k = static_cast<std::ptrdiff_t>(tiles.size()) - 3; k > 0; k -= 3)
    tiles.insert(static_cast<std::size_t>(k), ",");
  out.push_back({"static geometry that never moves",
                 "1000 circles / + " + tiles + " static tiles around the walls",
                 {base},
                 {tiled}});

  // Blocks of 2 x 5 touching boxes, 2 m apart, in a 25 x 20 grid from x = 500 to 598 m.
  SceneDesc movers = base;
  movers.sleep = true;
  movers.bounds = {{-128, -384}, {640, 384}};
  SceneDesc far = movers;
  for (int gx = 0; gx < 25; ++gx)
    for (int gy = 0; gy < 20; ++gy)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 5; ++j) {
          world_scenes::BodyDesc b;
          b.position = {500.5f + 4.0f * static_cast<float>(gx) + static_cast<float>(i),
                        -69.5f + 7.0f * static_cast<float>(gy) + static_cast<float>(j)};
          b.half = {0.5f, 0.5f};
          far.bodies.push_back(b);
        }
  out.push_back({"sleeping islands far away",
                 "1000 circles / + 5,000 boxes asleep 400-500 m away",
                 {movers, 120, 300},
                 {far, 120, 300}});
  return out;
}

std::string micros(double seconds) {
  char s[32];
  const double us = seconds * 1e6;
  std::snprintf(s, sizeof s, us < 10.0 ? "%.2f us" : "%.1f us", us);
  return s;
}

}  // namespace skip_bench

int main(int argc, char** argv) {
  using namespace skip_bench;
  int rounds = 5;
  std::string tablePath, filter;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
      rounds = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--table") == 0 && i + 1 < argc) {
      tablePath = argv[++i];
    } else if (std::strcmp(argv[i], "--filter") == 0 && i + 1 < argc) {
      filter = argv[++i];
    } else {
      std::fprintf(stderr, "usage: skip_bench [--rounds N] [--table FILE.md] [--filter TEXT]\n");
      return 2;
    }
  }
  if (rounds < 1) {
    std::fprintf(stderr, "skip_bench: --rounds must be at least 1\n");
    return 2;
  }
  std::vector<Row> table = rows();
  std::erase_if(table, [&](const Row& row) { return row.lacks.find(filter) == std::string::npos; });
  // [row][0 ours without, 1 ours with, 2 Box2D without, 3 Box2D with][round]
  std::vector<std::vector<std::vector<double>>> times(table.size(),
                                                      std::vector<std::vector<double>>(4));
  std::vector<std::vector<Work>> work(table.size(), std::vector<Work>(4));
  std::vector<std::vector<std::vector<rc::Profile>>> passes(
      table.size(), std::vector<std::vector<rc::Profile>>(2));
  for (int r = 0; r < rounds; ++r) {
    std::fprintf(stderr, "skip_bench: round %d of %d\n", r + 1, rounds);
    for (std::size_t i = 0; i < table.size(); ++i)
      for (int k = 0; k < 4; ++k) {
        const int cell = r % 2 == 0 ? k : 3 - k;
        const Config& c = cell % 2 == 0 ? table[i].without : table[i].with;
        Work& w = work[i][static_cast<std::size_t>(cell)];
        const double t =
            cell < 2 ? measure<world_scenes::Ours>(c, w) : measure<world_scenes::Box2D>(c, w);
        times[i][static_cast<std::size_t>(cell)].push_back(t);
      }
    for (std::size_t i = 0; i < table.size(); ++i) {
      passes[i][0].push_back(phases(table[i].without));
      passes[i][1].push_back(phases(table[i].with));
    }
  }
  for (std::size_t i = 0; i < table.size(); ++i) {
    work[i][0].phases = medianPhases(passes[i][0]);
    work[i][1].phases = medianPhases(passes[i][1]);
  }

  std::string md =
      "| the scene lacks | without / with | ours without | ours with | ratio | Box2D without | "
      "Box2D with | ratio |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < table.size(); ++i) {
    double m[4];
    for (std::size_t k = 0; k < 4; ++k)
      m[k] = cpu_time::median(times[i][k]);
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %#.3g | %s | %s | %#.3g |\n",
                  table[i].lacks.c_str(), table[i].scenes.c_str(), micros(m[0]).c_str(),
                  micros(m[1]).c_str(), m[0] / m[1], micros(m[2]).c_str(), micros(m[3]).c_str(),
                  m[2] / m[3]);
    md += line;
  }
  md +=
      "\nWhat each world held at the end of its timed steps, and our step by phase (us per step: "
      "each phase's share of the phases' sum in an untimed pass a round, preempted steps left out, "
      "medians of the rounds, times the measured CPU time):\n\n"
      "| the scene lacks | config | ours awake | ours contacts | Box2D awake | Box2D contacts | "
      "pairs | narrow | solve | continuous | refit | sensors | sleep |\n"
      "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < table.size(); ++i)
    for (std::size_t with = 0; with < 2; ++with) {
      const Work& o = work[i][with];
      const Work& b = work[i][2 + with];
      const rc::Profile& p = o.phases;
      // The profile is wall-clock time, which a shared machine's preemption inflates: its
      // shares, applied to the CPU time, are distorted least. (The step's time outside its
      // phases, most of an asleep world's step, is spread over them.)
      const double us = 1e6 * cpu_time::median(times[i][with]) / p.total;
      char line[512];
      std::snprintf(line, sizeof line,
                    "| %s | %s | %d | %d | %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | "
                    "%.2f |\n",
                    table[i].lacks.c_str(), with ? "with" : "without", o.awake, o.contacts, b.awake,
                    b.contacts, us * p.updatePairs, us * p.narrowphase, us * p.solve,
                    us * p.continuous, us * p.refit, us * p.sensors, us * p.sleep);
      md += line;
    }
  for (std::size_t i = 0; i < table.size(); ++i)
    if (table[i].with.scene.bulletCount > 0) {
      char tail[160];
      std::snprintf(tail, sizeof tail, "\nBullets escaped (last round): ours %d, Box2D %d.\n",
                    work[i][1].escapes, work[i][3].escapes);
      md += tail;
    }
  std::fputs(md.c_str(), stdout);
  if (!tablePath.empty()) {
    FILE* f = std::fopen(tablePath.c_str(), "w");
    if (f == nullptr) {
      std::fprintf(stderr, "skip_bench: cannot write %s\n", tablePath.c_str());
      return 1;
    }
    std::fputs(md.c_str(), f);
    std::fclose(f);
  }
  return 0;
}
