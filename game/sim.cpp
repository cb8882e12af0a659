// `ricochet sim SCENE.json --steps N [--integrator NAME] [--out STATE.json]
//                [--trace BODY,BODY,... --csv FILE]`
// Steps a scene file and writes the final state (and a trajectory of chosen bodies).
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/scene.h"

namespace game {
namespace {

constexpr const char* kSimUsage =
    "usage: ricochet sim SCENE.json --steps N [--integrator NAME] [--out STATE.json]\n"
    "                    [--trace BODY,BODY,... --csv FILE]\n"
    "\n"
    "Steps the scene N times at its dt and prints one summary line (steps, simulated time,\n"
    "state hash, milliseconds per step) on stdout.\n"
    "  --integrator NAME  explicit-euler, semi-implicit-euler, verlet or rk4 (overrides the\n"
    "                     scene's setting)\n"
    "  --out FILE         the final state as JSON (every body's position, angle, velocities)\n"
    "  --trace LIST       bodies to record every step, by index or name, comma-separated\n"
    "  --csv FILE         where the trace goes: step,time,body,x,y,angle,vx,vy,w\n"
    "Exit codes: 0 done, 1 bad scene or unwritable output, 2 bad command line.\n";

int usageError(const std::string& what) {
  std::fprintf(stderr, "ricochet sim: %s (try ricochet sim --help)\n", what.c_str());
  return 2;
}

// Body indices from a list of indices or names.
bool resolveTrace(const std::string& list, const SceneDesc& scene, std::vector<std::size_t>& out,
                  std::string& error) {
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), index);
    bool found =
        ec == std::errc() && end == item.data() + item.size() && index < scene.bodies.size();
    for (std::size_t i = 0; !found && i < scene.bodies.size(); ++i)
      if (!item.empty() && scene.bodies[i].name == item) {
        index = i;
        found = true;
      }
    if (!found) {
      error = "--trace: no body \"" + item + "\" in the scene";
      return false;
    }
    out.push_back(index);
    start = comma + 1;
  }
  return true;
}

}  // namespace

int runSim(std::span<const std::string_view> args) {
  std::string scenePath, outPath, csvPath, trace, integrator;
  long steps = -1;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    auto value = [&](std::string& into) {
      if (i + 1 >= args.size()) return false;
      into = std::string(args[++i]);
      return true;
    };
    if (a == "--help" || a == "-h") {
      std::fputs(kSimUsage, stdout);
      return 0;
    } else if (a == "--steps") {
      std::string v;
      if (!value(v)) return usageError("--steps needs a number");
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), steps);
      if (ec != std::errc() || end != v.data() + v.size() || steps < 0)
        return usageError("--steps must be a whole number >= 0, got '" + v + "'");
    } else if (a == "--out") {
      if (!value(outPath)) return usageError("--out needs a file name");
    } else if (a == "--csv") {
      if (!value(csvPath)) return usageError("--csv needs a file name");
    } else if (a == "--trace") {
      if (!value(trace)) return usageError("--trace needs a list of bodies");
    } else if (a == "--integrator") {
      if (!value(integrator)) return usageError("--integrator needs a name");
    } else if (!a.empty() && a[0] == '-') {
      return usageError("unknown option '" + std::string(a) + "'");
    } else if (scenePath.empty()) {
      scenePath = std::string(a);
    } else {
      return usageError("more than one scene file");
    }
  }
  if (scenePath.empty()) return usageError("no scene file");
  if (steps < 0) return usageError("--steps is required");
  if (trace.empty() != csvPath.empty()) return usageError("--trace and --csv go together");

  try {
    SceneDesc scene = loadScene(scenePath);
    if (!integrator.empty()) {
      const auto m = rc::parseIntegrator(integrator);
      if (!m) return usageError("unknown integrator '" + integrator + "'");
      scene.world.integrator = *m;
    }
    std::vector<std::size_t> traced;
    std::string error;
    if (!trace.empty() && !resolveTrace(trace, scene, traced, error)) return usageError(error);
    BuiltWorld built = buildWorld(scene);
    std::string csv = "step,time,body,x,y,angle,vx,vy,w\n";
    auto record = [&](long step) {
      for (std::size_t i : traced) {
        const rc::BodyId id = built.ids[i];
        const rc::Vec2 p = built.world->position(id), v = built.world->linearVelocity(id);
        char line[256];
        std::snprintf(line, sizeof line, "%ld,%.9g,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", step,
                      built.world->time(), i, static_cast<double>(p.x), static_cast<double>(p.y),
                      static_cast<double>(built.world->angle(id)), static_cast<double>(v.x),
                      static_cast<double>(v.y),
                      static_cast<double>(built.world->angularVelocity(id)));
        csv += line;
      }
    };
    record(0);
    double total = 0;
    for (long k = 1; k <= steps; ++k) {
      built.world->step(scene.dt);
      total += built.world->profile().total;
      record(k);
      if (steps >= 10000 && k % (steps / 10) == 0)
        std::fprintf(stderr, "ricochet sim: %ld of %ld steps\n", k, steps);
    }
    const SceneState state = captureState(scene, built, static_cast<int>(steps));
    if (!outPath.empty()) writeFileAtomically(outPath, stateToJson(state));
    if (!csvPath.empty()) writeFileAtomically(csvPath, csv);
    std::printf("steps %ld time %.6f hash %s ms_per_step %.4f\n", steps, state.time,
                state.hash.c_str(), steps > 0 ? total / static_cast<double>(steps) : 0.0);
    return 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "ricochet sim: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    // Anything the world refuses mid-run (it validates in release builds too).
    std::fprintf(stderr, "ricochet sim: %s: %s\n", scenePath.c_str(), e.what());
    return 1;
  }
}

}  // namespace game
