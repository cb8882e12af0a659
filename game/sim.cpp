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
#include "game/view/frame_output.h"
#include "physics/contact_solver.h"

#ifdef RICOCHET_HAS_RENDER
#include "game/view/scene_view.h"
#endif

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
    "  --frames DIR       render frame_000000.png, ... into DIR (step 0 and every K-th step)\n"
    "  --every K          with --frames: every K-th step (default 1)\n"
    "  --size WxH         with --frames: frame size in pixels (default 640x360)\n"
    "  --no-overlay       with --frames: without the debug overlay (AABBs, contacts,\n"
    "                     velocities)\n"
    "  --sheet FILE       with --frames: also a contact sheet of up to 24 of the frames\n"
    "  --video FILE       with --frames: also an MP4 (or a GIF, by the name) of the frames,\n"
    "                     if ffmpeg is installed; without it a warning, and the frames stay\n"
    "  --profile          also print the step's phases, milliseconds per step on average\n"
    "                     (after the summary line), and the contact solver's batch width\n"
    "  --lanes N          the contact solver's batch width, 4 or 8 (8: AVX2; the default is\n"
    "                     the widest the processor has); the hash is the same at either\n"
    "Exit codes: 0 done, 1 bad scene or unwritable output, 2 bad command line.\n";

int usageError(const std::string& what) {
  std::fprintf(stderr, "ricochet sim: %s (try ricochet sim --help)\n", what.c_str());
  return 2;
}

// A whole decimal number >= least, the whole text.
bool whole(const std::string& text, long least, long& out) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && out >= least;
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
  FrameOptions frames;
  frames.overlay = true;
  bool profile = false;
  long lanes = 0;
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
      if (!value(v) || !whole(v, 0, steps))
        return usageError("--steps must be a whole number >= 0, got '" + v + "'");
    } else if (a == "--out") {
      if (!value(outPath)) return usageError("--out needs a file name");
    } else if (a == "--csv") {
      if (!value(csvPath)) return usageError("--csv needs a file name");
    } else if (a == "--trace") {
      if (!value(trace)) return usageError("--trace needs a list of bodies");
    } else if (a == "--integrator") {
      if (!value(integrator)) return usageError("--integrator needs a name");
    } else if (a == "--frames") {
      if (!value(frames.directory)) return usageError("--frames needs a directory");
    } else if (a == "--sheet") {
      if (!value(frames.sheet)) return usageError("--sheet needs a file name");
    } else if (a == "--video") {
      if (!value(frames.video)) return usageError("--video needs a file name");
    } else if (a == "--no-overlay") {
      frames.overlay = false;
    } else if (a == "--profile") {
      profile = true;
    } else if (a == "--lanes") {
      std::string v;
      if (!value(v) || !whole(v, 4, lanes) || (lanes != 4 && lanes != 8))
        return usageError("--lanes must be 4 or 8, got '" + v + "'");
    } else if (a == "--every") {
      std::string v;
      if (!value(v)) return usageError("--every must be a whole number >= 1, got ''");
      if (const auto e = parseEvery(v, frames.every)) return usageError(*e);
    } else if (a == "--size") {
      std::string v;
      if (!value(v)) return usageError("--size needs WxH");
      if (const auto e = parseSize(v, frames.width, frames.height)) return usageError(*e);
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
  const RunInput inputs[] = {{"the scene", scenePath}};
  if (const auto e = checkFrameOptions(frames, inputs)) {
    if (e->exitCode == 2) return usageError(e->message);
    std::fprintf(stderr, "ricochet sim: %s\n", e->message.c_str());
    return e->exitCode;
  }
  if (lanes == 8 && rc::ContactSolver::widestLanes() != 8)
    return usageError("--lanes 8 needs a processor with AVX2, which this one lacks");

  try {
    SceneDesc scene = loadScene(scenePath);
    if (!integrator.empty()) {
      const auto m = rc::parseIntegrator(integrator);
      if (!m) return usageError("unknown integrator '" + integrator + "'");
      scene.world.integrator = *m;
    }
    if (lanes != 0) scene.world.maxSolverLanes = static_cast<int>(lanes);
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
    // Frames: the camera fitted once to the scene as it starts, so the view does not jump.
    FrameOutput output(frames, "ricochet sim", steps, static_cast<double>(scene.dt));
#ifdef RICOCHET_HAS_RENDER
    ViewOptions view;
    view.overlay = frames.overlay;
    view.caption = scenePath;
    const render::Camera camera = cameraForWorld(*built.world, frames.width, frames.height);
    auto frame = [&](long step) {
      if (output.due(step)) output.add(step, drawWorld(*built.world, step, view), camera);
    };
#else
    auto frame = [](long) {};
#endif
    record(0);
    frame(0);
    rc::Profile sum;
    for (long k = 1; k <= steps; ++k) {
      built.world->step(scene.dt);
      const rc::Profile& p = built.world->profile();
      sum.updatePairs += p.updatePairs;
      sum.narrowphase += p.narrowphase;
      sum.solve += p.solve;
      sum.continuous += p.continuous;
      sum.refit += p.refit;
      sum.sensors += p.sensors;
      sum.sleep += p.sleep;
      sum.total += p.total;
      record(k);
      frame(k);
      if (steps >= 10000 && k % (steps / 10) == 0)
        std::fprintf(stderr, "ricochet sim: %ld of %ld steps\n", k, steps);
    }
    output.finish();
    const SceneState state = captureState(scene, built, static_cast<int>(steps));
    if (!outPath.empty()) writeFileAtomically(outPath, stateToJson(state));
    if (!csvPath.empty()) writeFileAtomically(csvPath, csv);
    const double perStep = steps > 0 ? 1.0 / static_cast<double>(steps) : 0.0;
    std::printf("steps %ld time %.6f hash %s ms_per_step %.4f\n", steps, state.time,
                state.hash.c_str(), sum.total * perStep);
    if (profile)
      std::printf(
          "profile ms_per_step update_pairs %.4f narrowphase %.4f solve %.4f continuous %.4f "
          "refit %.4f sensors %.4f sleep %.4f total %.4f lanes %d\n",
          sum.updatePairs * perStep, sum.narrowphase * perStep, sum.solve * perStep,
          sum.continuous * perStep, sum.refit * perStep, sum.sensors * perStep, sum.sleep * perStep,
          sum.total * perStep, built.world->profile().lanes);
    return 0;
  } catch (const FrameOutputError& e) {
    std::fprintf(stderr, "ricochet sim: %s\n", e.what());
    return 1;
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
