// Renderer benchmark (run by hand, not a test): frames per second end to end (draw, read back,
// encode, write) for a scene of N moving shapes with the debug overlay and a HUD, split into
// its parts. Also leaves the frames on disk for a look.
//
//   render_bench [--width 640] [--height 360] [--shapes 2000] [--frames 60] [--level 1]
//                [--out /tmp/ricochet_render_bench]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "render/contact_sheet.h"
#include "render/context.h"
#include "render/frame_writer.h"
#include "render/png.h"
#include "render/renderer.h"

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// A deterministic arena: walls, then shapes of every kind drifting around, each with an AABB
// and a velocity arrow in the overlay.
render::Frame scene(int shapes, int frameIndex, float halfWidth, float halfHeight) {
  using render::Style;
  render::Frame frame;
  frame.background = render::Color{24, 26, 32, 255};
  const float t = static_cast<float>(frameIndex) / 60.0f;
  const rc::Vec2 walls[] = {{-halfWidth, -halfHeight},
                            {halfWidth, -halfHeight},
                            {halfWidth, halfHeight},
                            {-halfWidth, halfHeight}};
  frame.world.polyline(walls, 3.0f, render::Color{200, 200, 210, 255}, true);
  std::uint32_t seed = 12345;
  auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / 16777216.0f;
  };
  for (int i = 0; i < shapes; ++i) {
    float x0 = (next() * 2.0f - 1.0f) * (halfWidth - 1.0f);
    float y0 = (next() * 2.0f - 1.0f) * (halfHeight - 1.0f);
    float phase = next() * 6.2831853f;
    rc::Vec2 v{std::cos(phase), std::sin(phase)};
    rc::Vec2 p{x0 + 0.5f * std::sin(t + phase), y0 + 0.5f * std::cos(1.3f * t + phase)};
    float size = 0.15f + 0.35f * next();
    render::Color c{static_cast<std::uint8_t>(80 + 175 * next()),
                    static_cast<std::uint8_t>(80 + 175 * next()),
                    static_cast<std::uint8_t>(80 + 175 * next()), 255};
    switch (i % 4) {
      case 0:
        frame.world.circle(p, size, Style::both(c, render::colors::kWhite, 1.0f));
        break;
      case 1:
        frame.world.capsule(p, p + size * v, 0.5f * size, Style::filled(c));
        break;
      case 2: {
        rc::Vec2 u{-v.y, v.x};
        const rc::Vec2 box[] = {p - size * v - size * u, p + size * v - size * u,
                                p + size * v + size * u, p - size * v + size * u};
        frame.world.polygon(box, Style::both(c, render::colors::kBlack, 1.0f));
        break;
      }
      default: {
        const rc::Vec2 tri[] = {p, p + size * v, p + size * rc::Vec2{-v.y, v.x}};
        frame.world.polygon(tri, Style::filled(c), 0.03f);
        break;
      }
    }
    if (i % 8 == 0) {
      frame.overlay.rect({p - rc::Vec2{size, size}, p + rc::Vec2{size, size}},
                         Style::outlined(render::Color{60, 220, 90, 160}, 1.0f));
      frame.overlay.arrow(p, p + 1.5f * v, 1.0f, render::colors::kYellow, 6.0f);
    }
  }
  frame.overlay.text({-halfWidth + 1.0f, -halfHeight + 1.0f}, "overlay: AABBs, velocities", 12.0f,
                     render::Color{60, 220, 90, 255}, render::HAlign::kLeft,
                     render::VAlign::kBottom);
  char hud[96];
  std::snprintf(hud, sizeof hud, "tick %d\nshapes %d", frameIndex, shapes);
  frame.hud.text({8.0f, 8.0f}, hud, 16.0f, render::colors::kWhite);
  frame.hud.rect({{8.0f, 50.0f}, {108.0f, 58.0f}}, Style::outlined(render::colors::kWhite, 1.0f));
  frame.hud.rect({{9.0f, 51.0f}, {9.0f + 98.0f * (0.5f + 0.5f * std::sin(t)), 57.0f}},
                 Style::filled(render::colors::kRed));
  return frame;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 640, height = 360, shapes = 2000, frames = 60, level = 1;
  std::string out = "/tmp/ricochet_render_bench";
  for (int i = 1; i < argc; ++i) {
    auto value = [&](const char* name) -> const char* {
      if (std::strcmp(argv[i], name) != 0) return nullptr;
      if (i + 1 >= argc) {
        std::fprintf(stderr, "render_bench: %s needs a value\n", name);
        std::exit(2);
      }
      return argv[++i];
    };
    if (const char* v = value("--width"))
      width = std::atoi(v);
    else if (const char* v2 = value("--height"))
      height = std::atoi(v2);
    else if (const char* v3 = value("--shapes"))
      shapes = std::atoi(v3);
    else if (const char* v4 = value("--frames"))
      frames = std::atoi(v4);
    else if (const char* v5 = value("--level"))
      level = std::atoi(v5);
    else if (const char* v6 = value("--out"))
      out = v6;
    else {
      std::fprintf(stderr,
                   "usage: render_bench [--width W] [--height H] [--shapes N] [--frames F] "
                   "[--level 1-9] [--out DIR]\n");
      return 2;
    }
  }
  try {
    auto start = Clock::now();
    render::Renderer renderer;
    std::printf("setup %.3f s (%s, %s)\n", since(start), renderer.context().version().c_str(),
                renderer.context().rendererName().c_str());
    const float halfWidth = 32.0f, halfHeight = 18.0f;
    render::Camera camera = render::Camera::fit(
        {{-halfWidth, -halfHeight}, {halfWidth, halfHeight}}, width, height, 4.0f);

    // Parts, one after another on this thread.
    double build = 0, draw = 0, readback = 0, encode = 0;
    long long bytes = 0;
    render::Image image;
    for (int f = 0; f < frames; ++f) {
      auto t0 = Clock::now();
      render::Frame frame = scene(shapes, f, halfWidth, halfHeight);
      build += since(t0);
      renderer.render(frame, camera, image);
      draw += renderer.lastTiming().drawSeconds;
      readback += renderer.lastTiming().readbackSeconds;
      auto t1 = Clock::now();
      bytes += static_cast<long long>(render::encodePng(image, {level}).size());
      encode += since(t1);
    }
    const double n = frames;
    std::printf("%dx%d, %d shapes, %d frames, zlib level %d, per frame:\n", width, height, shapes,
                frames, level);
    std::printf("  build draw list %7.2f ms\n", 1e3 * build / n);
    std::printf("  draw            %7.2f ms\n", 1e3 * draw / n);
    std::printf("  readback        %7.2f ms\n", 1e3 * readback / n);
    std::printf("  encode PNG      %7.2f ms (%.0f KiB)\n", 1e3 * encode / n,
                static_cast<double>(bytes) / n / 1024.0);

    // End to end with the writer thread: draw the next frame while the last one is encoded.
    render::FrameWriter writer({out, "frame_", 4, {level}});
    std::vector<render::Image> sheet;  // every 10th frame
    start = Clock::now();
    for (int f = 0; f < frames; ++f) {
      render::Frame frame = scene(shapes, f, halfWidth, halfHeight);
      render::Image frameImage;
      renderer.render(frame, camera, frameImage);
      if (f % 10 == 0) sheet.push_back(frameImage);
      writer.submit(f, std::move(frameImage));
    }
    writer.finish();
    double total = since(start);
    render::writePng(std::filesystem::path(out) / "contact_sheet.png", render::contactSheet(sheet));
    std::printf(
        "end to end with the writer thread: %.1f frames/s (%.2f ms per frame), "
        "frames in %s\n",
        n / total, 1e3 * total / n, out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
