// Scaling: the cost per body-step against the number of bodies, ours and Box2D 2.4.1's, in one
// run. Not part of ctest; run
//   ./build/release/tests/scaling_bench [--rounds N] [--csv FILE] [--plot FILE.png]
// writes the CSV (part,engine,n,steps,ns_per_item,bytes_per_item) and, when gnuplot is
// installed, a plot of both parts against N (log x, log y).
//
// Two parts:
//   world       world_bench's arena at its density for every N (world_scenes.h: the 1000-circle
//               arena's 200 m box, 20 obstacles and 5 m/s circles, the box's side and the
//               obstacles grown with N so that each circle meets as many others as at 1000):
//               N = 100 to 20,000 circles. Time per step over N. A measurement builds the world,
//               steps it 45 times untimed, then times 90 steps (the same simulated steps in
//               every round), repeated within a round until it has timed 50 ms.
//   broadphase  the pair update alone, driven as broadphase_bench drives it (circles of radius
//               0.5 m, one per 8 m^2, at 5 m/s bouncing in a walled square; every proxy moved
//               with its displacement, then the new pairs collected): our quadtree against
//               Box2D's b2BroadPhase (its b2DynamicTree), N = 1,024 to 262,144 proxies. Each
//               structure is built once, stepped 10 times untimed, and every round steps it on
//               (the motion is steady: nothing slows down); the motion of a step is computed
//               untimed. Time per step over N.
// Method: CPU time of this thread; rounds interleave the engines and the sizes (the order
// reversed every second round); each point is the median of the rounds. bytes_per_item is the
// heap a world or broadphase of that size holds once warmed up, over N: the working set a step
// walks through, to read against the cache sizes.
#include <box2d/b2_broad_phase.h>
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "bench/broadphase_arena.h"
#include "bench/cpu_time.h"
#include "bench/world_scenes.h"
#include "physics/broadphase.h"
#include "physics/random.h"

namespace scaling_bench {

using rc::AABB;
using rc::Vec2;

// Bytes of heap in use (glibc): what a world or tree holds, to read against the cache sizes.
double heapBytes() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks) + static_cast<double>(m.hblkhd);
}

// ------------------------------------------------------------------------------------ world

constexpr int kWorldWarmup = 45, kWorldSteps = 90;
constexpr double kMinRoundSeconds = 0.05;

world_scenes::SceneDesc scaledArena(int n) {
  const float scale = std::sqrt(static_cast<float>(n) / 1000.0f);
  const int obstacles = std::max(1, static_cast<int>(std::lround(20.0 * n / 1000.0)));
  return world_scenes::arena(n, 0, 0, 7, 200.0f * scale, obstacles);
}

// CPU seconds per step of one round: as many measurements as fill kMinRoundSeconds. Ours also
// gives its profile's phases, from a world of its own with the profile on (its clocks, and ours
// around every step, are kept out of the timed runs; see PhaseSamples).
template <class Engine>
double worldRound(const world_scenes::SceneDesc& scene, double* bytes, rc::Profile& phases) {
  double seconds = 0;
  long steps = 0;
  do {
    const double before = heapBytes();
    Engine engine(scene);
    for (int k = 0; k < kWorldWarmup; ++k)
      engine.step();
    if (bytes != nullptr && *bytes == 0) *bytes = heapBytes() - before;
    const double start = cpu_time::threadSeconds();
    for (int k = 0; k < kWorldSteps; ++k)
      engine.step();
    seconds += cpu_time::threadSeconds() - start;
    steps += kWorldSteps;
  } while (seconds < kMinRoundSeconds);
  if constexpr (std::is_same_v<Engine, world_scenes::Ours>) {
    world_scenes::SceneDesc profiled = scene;
    profiled.profile = true;
    world_scenes::Ours engine(profiled);
    for (int k = 0; k < kWorldWarmup; ++k)
      engine.step();
    world_scenes::PhaseSamples samples;
    for (int k = 0; k < kWorldSteps; ++k) {
      const double start = cpu_time::threadSeconds();
      engine.step();
      samples.add(engine.world->profile(), cpu_time::threadSeconds() - start);
    }
    phases = samples.means();
  }
  return seconds / static_cast<double>(steps);
}

// ------------------------------------------------------------------------------ broadphase

using rc::bench::circleBox;
using rc::bench::kDt;
using rc::bench::kRadius;
using rc::bench::kSpeed;
using rc::bench::toB2;
constexpr int kPairWarmup = 10;  // more than a proxy's 6-9 steps between re-insertions

// Circles bouncing in a square of side sqrt(8 n): the same seed gives both engines the same
// positions step after step. Each proxy is created with its box stretched along its motion by
// a random 0 to 7 steps of it, as if it had entered the tree at a random earlier step: created
// with their tight boxes, every proxy would leave its fat AABB on the same step, every 7th step
// (for us; every 5th or 6th for Box2D), and a round's few steps would time a wave or miss it.
struct Motion {
  float side = 0;
  std::vector<Vec2> p, v, before;
  std::vector<AABB> initial;  // the boxes the proxies are created with
  Motion(int n, std::uint64_t seed) : side(std::sqrt(8.0f * static_cast<float>(n))) {
    rc::Random rng(seed);
    for (int i = 0; i < n; ++i) {
      p.push_back(rng.inBox({kRadius, kRadius}, {side - kRadius, side - kRadius}));
      const float angle = rng.uniform(0.0f, 6.2831853f);
      v.push_back(kSpeed * Vec2{std::cos(angle), std::sin(angle)});
      const AABB now = circleBox(p.back()),
                 ahead = circleBox(p.back() + rng.uniform(0.0f, 7.0f) * kDt * v.back());
      initial.push_back({rc::min(now.lower, ahead.lower), rc::max(now.upper, ahead.upper)});
    }
  }
  std::vector<AABB> walls() const {
    const float s = side;
    return {
        {{-1, -1}, {0, s + 1}}, {{s, -1}, {s + 1, s + 1}}, {{0, -1}, {s, 0}}, {{0, s}, {s, s + 1}}};
  }
  void advance() {
    before = p;
    const Vec2 lo{kRadius, kRadius}, hi{side - kRadius, side - kRadius};
    for (std::size_t i = 0; i < p.size(); ++i) {
      p[i] += kDt * v[i];
      if (p[i].x < lo.x || p[i].x > hi.x) v[i].x = -v[i].x;
      if (p[i].y < lo.y || p[i].y > hi.y) v[i].y = -v[i].y;
      p[i] = rc::max(lo, rc::min(hi, p[i]));
    }
  }
};

struct OurPairs {
  Motion motion;
  rc::Quadtree tree;
  std::vector<rc::ProxyId> ids;
  std::vector<rc::ProxyPair> pairs;
  OurPairs(int n, std::uint64_t seed)
      : motion(n, seed), tree(AABB{{-1, -1}, {motion.side + 1, motion.side + 1}}) {
    for (const AABB& w : motion.walls())
      tree.createProxy({w, {}, true, 0});
    for (const AABB& box : motion.initial)
      ids.push_back(tree.createProxy({box, {}, false, 0}));
    tree.updatePairs(pairs);
  }
  void step() {
    for (std::size_t i = 0; i < ids.size(); ++i)
      tree.moveProxy(ids[i], circleBox(motion.p[i]), motion.p[i] - motion.before[i]);
    tree.updatePairs(pairs);
  }
};

struct Box2DPairs {
  struct Collector {
    std::vector<std::pair<void*, void*>> pairs;
    void AddPair(void* a, void* b) { pairs.emplace_back(a, b); }
  };
  Motion motion;
  b2BroadPhase bp;
  std::vector<int32> ids;
  Collector collector;
  Box2DPairs(int n, std::uint64_t seed) : motion(n, seed) {
    // User data: the index plus one (Box2D hands the pointers back, never reads them).
    auto tag = [](std::size_t i) { return reinterpret_cast<void*>(i + 1); };
    const std::vector<AABB> walls = motion.walls();
    for (std::size_t w = 0; w < walls.size(); ++w)
      bp.CreateProxy(toB2(walls[w]), tag(motion.p.size() + w));
    for (std::size_t i = 0; i < motion.p.size(); ++i)
      ids.push_back(bp.CreateProxy(toB2(motion.initial[i]), tag(i)));
    bp.UpdatePairs(&collector);
  }
  void step() {
    collector.pairs.clear();
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const Vec2 d = motion.p[i] - motion.before[i];
      bp.MoveProxy(ids[i], toB2(circleBox(motion.p[i])), b2Vec2(d.x, d.y));
    }
    bp.UpdatePairs(&collector);
  }
  int height() const { return bp.GetTreeHeight(); }
};

// Timed steps per round: about 2^20 proxy moves, at least 8 steps.
int pairSteps(int n) {
  return std::clamp((1 << 20) / n, 8, 512);
}

template <class Pairs>
double pairRound(Pairs& s, int steps) {
  double seconds = 0;
  for (int k = 0; k < steps; ++k) {
    s.motion.advance();
    const double start = cpu_time::threadSeconds();
    s.step();
    seconds += cpu_time::threadSeconds() - start;
  }
  return seconds / steps;
}

struct Point {
  std::string part, engine;
  int n = 0, steps = 0;
  std::vector<double> perItem;  // seconds, one per round
  double bytes = 0;
  std::vector<rc::Profile> phases;  // ours, world: per step, one per round
};

}  // namespace scaling_bench

int main(int argc, char** argv) {
  using namespace scaling_bench;
  int rounds = 5;
  std::string csvPath = "scaling.csv", plotPath = "scaling.png";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc)
      rounds = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
      csvPath = argv[++i];
    else if (std::strcmp(argv[i], "--plot") == 0 && i + 1 < argc)
      plotPath = argv[++i];
    else {
      std::fprintf(stderr, "usage: scaling_bench [--rounds N] [--csv FILE] [--plot FILE.png]\n");
      return 2;
    }
  }
  if (rounds < 1) {
    std::fprintf(stderr, "scaling_bench: --rounds must be at least 1\n");
    return 2;
  }
  std::ofstream csv(csvPath);
  if (!csv) {
    std::fprintf(stderr, "scaling_bench: %s: cannot write\n", csvPath.c_str());
    return 1;
  }

  const std::vector<int> worldSizes = {100, 300, 1000, 3000, 10000, 20000};
  std::vector<world_scenes::SceneDesc> scenes;
  for (int n : worldSizes)
    scenes.push_back(scaledArena(n));
  std::vector<int> pairSizes;
  for (int n = 1024; n <= 262144; n *= 2)
    pairSizes.push_back(n);

  std::vector<Point> points;
  for (int n : worldSizes)
    for (const char* engine : {"ours", "box2d"})
      points.push_back({"world", engine, n, kWorldSteps, {}, 0, {}});
  for (int n : pairSizes)
    for (const char* engine : {"ours", "box2d"})
      points.push_back({"broadphase", engine, n, pairSteps(n), {}, 0, {}});

  // The broadphases live for the whole run (each round steps them on).
  std::vector<std::unique_ptr<OurPairs>> ours;
  std::vector<std::unique_ptr<Box2DPairs>> theirs;
  std::vector<int> ourDepth, theirHeight;
  for (std::size_t i = 0; i < pairSizes.size(); ++i) {
    const int n = pairSizes[i];
    const auto seed = 100 + static_cast<std::uint64_t>(n);
    Point& po = points[2 * (worldSizes.size() + i)];
    Point& pb = points[2 * (worldSizes.size() + i) + 1];
    double before = heapBytes();
    ours.push_back(std::make_unique<OurPairs>(n, seed));
    for (int k = 0; k < kPairWarmup; ++k) {
      ours.back()->motion.advance();
      ours.back()->step();
    }
    po.bytes = heapBytes() - before;
    before = heapBytes();
    theirs.push_back(std::make_unique<Box2DPairs>(n, seed));
    for (int k = 0; k < kPairWarmup; ++k) {
      theirs.back()->motion.advance();
      theirs.back()->step();
    }
    pb.bytes = heapBytes() - before;
    ourDepth.push_back(ours.back()->tree.maxDepth());
    theirHeight.push_back(theirs.back()->height());
  }

  for (int r = 0; r < rounds; ++r) {
    std::fprintf(stderr, "scaling_bench: round %d of %d\n", r + 1, rounds);
    for (std::size_t j = 0; j < points.size(); ++j) {
      const std::size_t k = r % 2 == 0 ? j : points.size() - 1 - j;
      Point& p = points[k];
      const bool mine = p.engine == "ours";
      double* bytes = r == 0 ? &p.bytes : nullptr;
      double perStep = 0;
      if (p.part == "world") {
        const world_scenes::SceneDesc& scene = scenes[k / 2];
        rc::Profile phases;
        perStep = mine ? worldRound<world_scenes::Ours>(scene, bytes, phases)
                       : worldRound<world_scenes::Box2D>(scene, bytes, phases);
        p.phases.push_back(phases);
      } else {
        const std::size_t i = k / 2 - worldSizes.size();
        perStep = mine ? pairRound(*ours[i], p.steps) : pairRound(*theirs[i], p.steps);
      }
      p.perItem.push_back(perStep / p.n);
    }
  }

  // The CSV a series after the other (gnuplot joins the points of a series only when they are
  // consecutive rows).
  csv << "part,engine,n,steps,ns_per_item,bytes_per_item\n";
  for (const char* part : {"world", "broadphase"})
    for (const char* engine : {"ours", "box2d"})
      for (const Point& p : points) {
        if (p.part != part || p.engine != engine) continue;
        char line[160];
        std::snprintf(line, sizeof line, "%s,%s,%d,%d,%.4g,%.0f\n", part, engine, p.n, p.steps,
                      1e9 * cpu_time::median(p.perItem), p.bytes / p.n);
        csv << line;
      }
  csv.close();
  std::printf(
      "| part | N | ours ns per item | Box2D ns per item | Box2D / ours | ours bytes per "
      "item | Box2D bytes per item |\n|---|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < points.size(); k += 2) {
    const Point& o = points[k];
    const Point& b = points[k + 1];
    const double no = 1e9 * cpu_time::median(o.perItem), nb = 1e9 * cpu_time::median(b.perItem);
    std::printf("| %s | %d | %.1f | %.1f | %.2fx | %.0f | %.0f |\n", o.part.c_str(), o.n, no, nb,
                nb / no, o.bytes / o.n, b.bytes / b.n);
  }
  // The profile's phases are wall-clock times: their shares of each round's step, applied to
  // that round's CPU time, are what a shared machine's preemption distorts least.
  std::printf(
      "\nOur world's step by phase, ns per body-step (each phase's share of the phases' sum in an "
      "untimed pass a round with the profile on, preempted steps left out, times the round's CPU "
      "time; medians of the rounds), and the quadtree's world square and finest cells (the "
      "square halved depth times):\n\n"
      "| N | square | finest cell | pairs | narrowphase | solve | continuous | refit | sleep |\n"
      "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point& p = points[k];
    if (p.part != "world" || p.engine != "ours") continue;
    const rc::AABB& bounds = scenes[k / 2].bounds;
    const float square = bounds.upper.x - bounds.lower.x;
    const int depth = rc::Quadtree(bounds).maxDepth();
    auto med = [&](double rc::Profile::*field) {
      std::vector<double> v;
      for (std::size_t r = 0; r < p.phases.size(); ++r)
        v.push_back(1e9 * p.perItem[r] * p.phases[r].*field / p.phases[r].total);
      return cpu_time::median(v);
    };
    std::printf("| %d | %.0f m | %.2f m | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", p.n,
                static_cast<double>(square), std::ldexp(static_cast<double>(square), -depth),
                med(&rc::Profile::updatePairs), med(&rc::Profile::narrowphase),
                med(&rc::Profile::solve), med(&rc::Profile::continuous), med(&rc::Profile::refit),
                med(&rc::Profile::sleep));
  }
  std::printf("\nBroadphase: our quadtree's depth and finest cells / Box2D's tree height, by N:\n");
  for (std::size_t i = 0; i < pairSizes.size(); ++i)
    std::printf("%d: %d, %.2f m / %d\n", pairSizes[i], ourDepth[i],
                std::ldexp(static_cast<double>(ours[i]->motion.side) + 2.0, -ourDepth[i]),
                theirHeight[i]);

  // The plot: time per item against N, one panel per part, log x and y; a dashed line where our
  // heap reaches the L2 cache's 1 MiB (the bytes per item at the largest N).
  const std::string script = csvPath + ".gp";
  std::ofstream gp(script);
  gp << "set terminal pngcairo noenhanced size 1600,700 font 'DejaVu Sans,11'\n"
     << "set output '" << plotPath << "'\n"
     << "set datafile separator ','\n"
     << "set logscale xy\nset grid\nset key top left\nset yrange [40:4000]\n"
     << "set xlabel 'N'\nset format x '%.0s%c'\n"
     << "set multiplot layout 1,2 title 'Ricochet against Box2D 2.4.1: cost per item against N "
        "(CPU time, median of "
     << rounds << " rounds)'\n";
  struct Panel {
    const char* part;
    const char* title;
    const char* ylabel;
    double xmin, xmax;
  };
  const Panel panels[] = {
      {"world", "whole step: world_bench arena at constant density", "ns per body-step", 70, 30000},
      {"broadphase", "broadphase alone: pair update, every proxy moving", "ns per proxy-step", 700,
       400000}};
  for (const Panel& panel : panels) {
    double bytes = 0;
    int n = 0;
    for (const Point& p : points)
      if (p.part == panel.part && p.engine == "ours" && p.n > n) {
        n = p.n;
        bytes = p.bytes / p.n;
      }
    gp << "set title '" << panel.title << "'\nset ylabel '" << panel.ylabel << "'\n"
       << "set xrange [" << panel.xmin << ":" << panel.xmax << "]\nunset arrow\nunset label\n";
    if (bytes > 0) {
      const double l2 = 1048576.0 / bytes;
      gp << "set arrow from " << l2 << ", graph 0 to " << l2
         << ", graph 1 nohead dt 2 lc 'gray40'\n"
         << "set label 'our heap = L2 (1 MiB)' at " << l2 * 1.08 << ", graph 0.06 tc 'gray40'\n";
    }
    gp << "plot ";
    const char* engines[] = {"ours", "box2d"};
    const char* names[] = {"Ricochet", "Box2D 2.4.1"};
    for (int e = 0; e < 2; ++e)
      gp << (e ? ", " : "") << "'" << csvPath << "' using ((strcol(1) eq '" << panel.part
         << "' && strcol(2) eq '" << engines[e] << "') ? $3 : 1/0):5 with linespoints lw 2 pt 7 "
         << "title '" << names[e] << "'";
    gp << "\n";
  }
  gp << "unset multiplot\n";
  gp.close();
  const std::string command = "gnuplot '" + script + "' 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "scaling_bench: gnuplot failed or is not installed; the CSV is %s\n",
                 csvPath.c_str());
    return 0;
  }
  std::fprintf(stderr, "scaling_bench: wrote %s and %s\n", csvPath.c_str(), plotPath.c_str());
  return 0;
}
