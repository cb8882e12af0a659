// The shooter's frames benchmark (run by hand, not a test): a match played and rendered every
// tick, as `ricochet play --frames` does, in frames per second end to end (the tick, the view,
// drawing, reading back, encoding and writing on the writer thread), then the parts one after
// another: the tick, building the frame (MatchView::draw), drawing, reading back, encoding.
//
//   match_bench [--level assets/levels/arena.tmj] [--bots 16] [--ticks 600] [--width 640]
//               [--height 360] [--overlay] [--out /tmp/ricochet_match_bench]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/view/match_frames.h"
#include "game/view/match_view.h"
#include "render/png.h"
#include "render/renderer.h"

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string level = RICOCHET_SOURCE_DIR "/assets/levels/arena.tmj";
  std::string out = "/tmp/ricochet_match_bench";
  int bots = 16, ticks = 600, width = 640, height = 360;
  bool overlay = false;
  for (int i = 1; i < argc; ++i) {
    auto value = [&](const char* name) -> const char* {
      if (std::strcmp(argv[i], name) != 0) return nullptr;
      if (i + 1 >= argc) {
        std::fprintf(stderr, "match_bench: %s needs a value\n", name);
        std::exit(2);
      }
      return argv[++i];
    };
    if (std::strcmp(argv[i], "--overlay") == 0)
      overlay = true;
    else if (const char* v = value("--level"))
      level = v;
    else if (const char* v2 = value("--bots"))
      bots = std::atoi(v2);
    else if (const char* v3 = value("--ticks"))
      ticks = std::atoi(v3);
    else if (const char* v4 = value("--width"))
      width = std::atoi(v4);
    else if (const char* v5 = value("--height"))
      height = std::atoi(v5);
    else if (const char* v6 = value("--out"))
      out = v6;
    else {
      std::fprintf(stderr,
                   "usage: match_bench [--level FILE] [--bots K] [--ticks N] [--width W] "
                   "[--height H] [--overlay] [--out DIR]\n");
      return 2;
    }
  }
  try {
    game::MatchConfig config;
    config.bots = bots;
    const game::Level loaded = game::loadLevel(level);

    // End to end, as ricochet play --frames DIR --every 1 runs.
    game::FrameOptions options;
    options.directory = out;
    options.width = width;
    options.height = height;
    options.overlay = overlay;
    double endToEnd = 0.0;
    long long frames = 0;
    {
      game::Match match(loaded, config);
      game::MatchFrames output(options, "match_bench", match.state(), ticks, level);
      const auto start = Clock::now();
      output.update(match.state());
      for (int t = 0; t < ticks; ++t) {
        match.tick();
        output.update(match.state());
      }
      output.finish();
      endToEnd = since(start);
      frames = output.framesAdded();
    }

    // The parts, one after another on this thread, on the same match replayed.
    game::Match match(loaded, config);
    render::Renderer renderer;
    game::MatchView view(match.state(), width, height);
    game::MatchViewOptions viewOptions;
    viewOptions.overlay = overlay;
    double tick = 0, build = 0, draw = 0, readback = 0, encode = 0;
    long long shapes = 0;
    render::Image image;
    for (int t = 0; t <= ticks; ++t) {
      if (t > 0) {
        const auto t0 = Clock::now();
        match.tick();
        tick += since(t0);
      }
      view.observe(match.state());
      const auto t1 = Clock::now();
      const render::Frame frame = view.draw(match.state(), viewOptions);
      build += since(t1);
      shapes += static_cast<long long>(frame.world.shapes.size() +
                                       (overlay ? frame.overlay.shapes.size() : 0));
      renderer.render(frame, view.camera(), image);
      draw += renderer.lastTiming().drawSeconds;
      readback += renderer.lastTiming().readbackSeconds;
      const auto t2 = Clock::now();
      (void)render::encodePng(image);
      encode += since(t2);
    }
    const double n = ticks + 1.0;
    std::printf("%s, %d bots, %d ticks, %dx%d%s\n", level.c_str(), bots, ticks, width, height,
                overlay ? ", overlay" : "");
    std::printf(
        "end to end (tick, view, draw, readback, encode and write on the writer thread): "
        "%.1f frames/s (%lld frames in %.2f s, %s)\n",
        static_cast<double>(frames) / endToEnd, frames, endToEnd, out.c_str());
    std::printf("per frame, one after another (%.0f shapes on average):\n",
                static_cast<double>(shapes) / n);
    std::printf("  tick            %7.2f ms\n", 1e3 * tick / ticks);
    std::printf("  build frame     %7.2f ms\n", 1e3 * build / n);
    std::printf("  draw            %7.2f ms\n", 1e3 * draw / n);
    std::printf("  readback        %7.2f ms\n", 1e3 * readback / n);
    std::printf("  encode PNG      %7.2f ms\n", 1e3 * encode / n);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "match_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
