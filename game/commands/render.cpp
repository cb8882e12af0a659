// `ricochet render FILE --tick T -o out.png [--size WxH] [--overlay] [--level FILE]`: one tick of
// a recorded session as a picture. The replay seeks through keyframes to a little before T (so
// the shots and blasts of the last ticks show, as in a run's frames), plays to T and draws it.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/session/batch.h"
#include "game/session/recording.h"
#include "game/session/replay.h"
#include "game/view/frame_output.h"

#ifdef RICOCHET_HAS_RENDER
#include "game/view/match_view.h"
#include "render/png.h"
#include "render/renderer.h"
#endif

namespace game {

int runRender(std::span<const std::string_view> args) {
  CLI::App app{
      "Renders one tick of a recorded session as a PNG.\n"
      "Exit codes: 0 written, 1 a recording that cannot be replayed or an output that cannot\n"
      "be written, 2 bad command line.",
      "ricochet render"};
  std::string path, tickText, out, sizeText = "640x360", levelPath;
  bool overlay = false, json = false;
  app.add_option("recording", path, "the recording (.rec)")->required();
  app.add_option("--tick", tickText, "the tick to draw: T ticks (or Ts seconds) in")->required();
  app.add_option("-o,--out", out, "the PNG to write")->required();
  app.add_option("--size", sizeText, "the picture's size in pixels (default 640x360)");
  app.add_flag("--overlay", overlay, "with what the bots perceive");
  app.add_option("--level", levelPath, "the level's file, if not where the recording says");
  app.add_flag("--json", json, "a JSON summary on stdout (the tick, its hash, the file written)");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet render", args)) return *exit;
  auto usage = [](const std::string& what) {
    std::fprintf(stderr, "ricochet render: %s (try ricochet render --help)\n", what.c_str());
    return kExitUsage;
  };
  const std::optional<std::int64_t> tick = parseTick(tickText);
  if (!tick) return usage("--tick must be a tick or seconds (90s), got '" + tickText + "'");
  int width = 0, height = 0;
  if (const std::optional<std::string> bad = parseSize(sizeText, width, height)) return usage(*bad);
  const RunOutput outputs[] = {{"-o", out}};
  const RunInput givenInputs[] = {{"the recording", path}, {"the level", levelPath}};
  if (auto e = outputOverwritesAnother(outputs, givenInputs);
      e || (e = outputFileUnwritable(outputs[0])))
    return refuse("ricochet render", *e);
#ifndef RICOCHET_HAS_RENDER
  (void)overlay;
  return usage("this ricochet was built without the renderer (-DRICOCHET_RENDER=OFF)");
#else
  try {
    const Recording recording = loadRecording(path);
    if (*tick > recording.ticks) {
      std::fprintf(stderr, "ricochet render: %s: tick %lld is past its end (tick %lld)\n",
                   path.c_str(), static_cast<long long>(*tick),
                   static_cast<long long>(recording.ticks));
      return kExitBadInput;
    }
    // The level and its tilesets, known once the recording says where it is.
    ReplaySetup setup(recording, levelPath);
    if (const auto e = outputOverwritesAnother(outputs, levelInputs(setup.level())))
      return refuse("ricochet render", *e);
    ReplayOptions options;
    options.from = std::max<std::int64_t>(0, *tick - MatchView::kBlastTicks);
    options.to = *tick;
    std::unique_ptr<MatchView> view;
    std::unique_ptr<render::Renderer> renderer;
    options.onTick = [&](const Match& m) {
      if (!view) view = std::make_unique<MatchView>(m.state(), width, height);
      view->observe(m.state());
      if (m.state().tick != *tick) return;
      MatchViewOptions viewOptions;
      viewOptions.overlay = overlay;
      viewOptions.caption = path;
      renderer = std::make_unique<render::Renderer>();
      render::writePng(out, renderer->render(view->draw(m.state(), viewOptions), view->camera()));
    };
    const ReplayReport report = replayRecording(setup, recording, options);
    if (!renderer) {
      std::fprintf(stderr, "ricochet render: %s: the replay stopped at tick %lld (%s)\n",
                   path.c_str(), static_cast<long long>(report.end), report.message.c_str());
      return kExitBadInput;
    }
    std::fprintf(stderr, "ricochet render: tick %lld of %s in %s\n", static_cast<long long>(*tick),
                 path.c_str(), out.c_str());
    if (json)
      std::printf("{\"file\": %s, \"tick\": %lld, \"hash\": \"%016llx\", \"out\": %s}\n",
                  jsonString(path).c_str(), static_cast<long long>(*tick),
                  static_cast<unsigned long long>(report.finalHash), jsonString(out).c_str());
    return kExitOk;
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "ricochet render: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ricochet render: %s: %s\n", out.c_str(), e.what());
    return kExitBadInput;
  }
#endif
}

}  // namespace game
