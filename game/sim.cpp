// `ricochet sim SCENE.json --steps N [--integrator NAME] [--out STATE.json]
//                [--trace BODY,BODY,... --csv FILE]`
// Steps a scene file and writes the final state (and a trajectory of chosen bodies).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/quote.h"
#include "game/scene.h"
#include "game/view/frame_output.h"
#include "physics/contact_solver.h"

#ifdef RICOCHET_HAS_RENDER
#include "game/view/scene_view.h"
#endif

namespace game {
namespace {

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

// A body the world had to take out of the run (its state not finite or beyond the world's
// quarantine speed, physics/world.h): the scene cannot be run as written, so the run stops with
// one line naming the body as the scene does, "body 3 ("ball")", and the step.
std::string quarantineMessage(const SceneDesc& scene, const BuiltWorld& built,
                              const std::vector<rc::QuarantineEvent>& events, long step) {
  const rc::QuarantineEvent& e = events.front();
  std::string body = "a body";
  for (std::size_t i = 0; i < built.ids.size(); ++i)
    if (built.ids[i] == e.body) {
      const std::string& name = scene.bodies[i].name;
      body = "body " + std::to_string(i) + (name.empty() ? "" : " (" + quoteName(name, '"') + ")");
    }
  char speed[32];
  std::snprintf(speed, sizeof speed, "%.0f", static_cast<double>(scene.world.quarantineSpeed));
  std::string what;
  switch (e.cause) {
    case rc::QuarantineCause::motion:
      what = "its motion left it not finite or faster than " + std::string(speed) + " m/s";
      break;
    case rc::QuarantineCause::contact:
      what = "its contacts left it not finite or faster than " + std::string(speed) + " m/s";
      break;
    case rc::QuarantineCause::forceField:
      what = "a force on it was not finite";
      break;
  }
  std::string more;
  if (events.size() > 1) more = " (and " + std::to_string(events.size() - 1) + " more bodies)";
  return scene.source + ": " + body + ": quarantined in step " + std::to_string(step) + ", " +
         what + more + "; the run stops";
}

}  // namespace

int runSim(std::span<const std::string_view> args) {
  CLI::App app{
      "Steps a scene file N times at its dt and prints one summary line (steps, simulated\n"
      "time, state hash, milliseconds per step) on stdout. Scene files: game/README.md.\n"
      "Exit codes: 0 done, 1 bad scene (a body the world had to quarantine mid-run too) or\n"
      "unwritable output, 2 bad command line.",
      "ricochet sim"};
  std::string scenePath, outPath, csvPath, trace, integrator;
  long steps = -1;
  bool profile = false, noOverlay = false;
  int lanes = 0;
  app.add_option("scene", scenePath, "the scene file (.json)")->required();
  app.add_option("--steps", steps, "steps to take (required)")
      ->required()
      ->check(CLI::Range(0L, 1L << 40));
  app.add_option("--integrator", integrator,
                 "explicit-euler, semi-implicit-euler, verlet or rk4 (overrides the scene's)");
  app.add_option("--out", outPath,
                 "the final state as JSON (every body's position, angle, "
                 "velocities)");
  app.add_option("--trace", trace,
                 "bodies to record every step, by index or name, comma-separated");
  app.add_option("--csv", csvPath, "where the trace goes: step,time,body,x,y,angle,vx,vy,w");
  app.add_flag("--profile", profile,
               "also print the step's phases in milliseconds per step (after the summary line) "
               "and the contact solver's batch width");
  app.add_option("--lanes", lanes,
                 "the contact solver's batch width, 4 or 8 (8: AVX2; default the widest the "
                 "processor has); the hash is the same at either")
      ->check(CLI::IsMember({4, 8}));
  FrameArgs frameArgs;
  addFrameOptions(app, frameArgs, "step");
  app.remove_option(app.get_option("--overlay"));  // a scene's overlay is on unless refused
  app.add_flag("--no-overlay", noOverlay,
               "with --frames: without the debug overlay (AABBs, contacts, velocities)");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet sim", args)) return *exit;
  FrameOptions frames;
  if (const auto e = frameOptionsFrom(frameArgs, frames)) return usageError(e->message);
  frames.overlay = !noOverlay;  // on by default for a scene: it is a debugging view
  if (trace.empty() != csvPath.empty()) return usageError("--trace and --csv go together");
  const RunInput inputs[] = {{"the scene", scenePath}};
  if (const auto e = checkFrameOptions(frames, inputs)) return refuse("ricochet sim", *e);
  // --out and --csv: neither the scene nor each other (nor a sheet or video), and each a file
  // that can be made, all before the run rather than after it.
  const RunOutput outputs[] = {
      {"--out", outPath}, {"--csv", csvPath}, {"--sheet", frames.sheet}, {"--video", frames.video}};
  std::optional<RunFileError> outputError = outputOverwritesAnother(outputs, inputs);
  for (std::size_t i = 0; i < 2 && !outputError; ++i)
    outputError = outputFileUnwritable(outputs[i]);
  if (outputError) return refuse("ricochet sim", *outputError);
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
    scene.world.enableProfile = profile;
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
    double stepMs = 0;  // timed here: the world's own phase times are on only with --profile
    for (long k = 1; k <= steps; ++k) {
      const auto begin = std::chrono::steady_clock::now();
      built.world->step(scene.dt);
      stepMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
                    .count();
      if (const auto& bad = built.world->quarantineEvents(); !bad.empty()) {
        std::fprintf(stderr, "ricochet sim: %s\n", quarantineMessage(scene, built, bad, k).c_str());
        return 1;
      }
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
                state.hash.c_str(), stepMs * perStep);
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
