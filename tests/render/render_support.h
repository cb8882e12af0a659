// Helpers shared by the renderer tests: one Renderer for the whole run (its context, shaders and
// font atlas take a moment to make), a scratch directory per test, and colour comparisons.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "render/image.h"
#include "render/renderer.h"

namespace render_test {

inline render::Renderer& sharedRenderer() {
  static render::Renderer renderer(render::RendererOptions{RICOCHET_TEST_FONT});
  return renderer;
}

// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string("ricochet_render_") + (info ? info->test_suite_name() : "x") +
                       "_" + (info ? info->name() : "y") + "_" + std::to_string(::getpid());
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A 32x32 sprite in four 16x16 quadrants: red top-left, green top-right, blue bottom-left, white
// bottom-right; orientation and tint are read off it.
inline render::Image quadrantSprite() {
  render::Image image(32, 32);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      const bool right = x >= 16, bottom = y >= 16;
      render::Color c =
          !bottom ? (right ? render::Color{0, 255, 0, 255} : render::Color{255, 0, 0, 255})
                  : (right ? render::Color{255, 255, 255, 255} : render::Color{0, 0, 255, 255});
      image.setPixel(x, y, c);
    }
  }
  return image;
}

// A 32x32 crate: a transparent 1-pixel margin, a dark frame, planks, a diagonal brace from the
// bottom-left to the top-right and a red mark in the top-left corner inside the frame.
inline render::Image crateSprite() {
  render::Image image(32, 32);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      render::Color c{0, 0, 0, 0};
      if (x >= 1 && x <= 30 && y >= 1 && y <= 30) {
        const bool frame = x <= 3 || x >= 28 || y <= 3 || y >= 28;
        const bool brace = std::abs((x + y) - 31) <= 1;
        const bool seam = y % 8 == 0;
        const bool mark = x >= 5 && x <= 9 && y >= 5 && y <= 9;
        c = frame   ? render::Color{100, 60, 25, 255}
            : mark  ? render::Color{230, 40, 40, 255}
            : brace ? render::Color{125, 78, 36, 255}
            : seam  ? render::Color{160, 105, 50, 255}
                    : render::Color{205, 145, 75, 255};
      }
      image.setPixel(x, y, c);
    }
  }
  return image;
}

// Largest difference of one channel.
inline int channelDistance(render::Color a, render::Color b) {
  int d = std::abs(a.r - b.r);
  d = std::max(d, std::abs(a.g - b.g));
  d = std::max(d, std::abs(a.b - b.b));
  return std::max(d, std::abs(a.a - b.a));
}

inline std::string describe(render::Color c) {
  return "(" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) +
         ", " + std::to_string(c.a) + ")";
}

// EXPECT_PIXEL(image, x, y, colour, tolerance): every channel within tolerance.
#define EXPECT_PIXEL(image, x, y, color, tolerance)                                        \
  EXPECT_LE(::render_test::channelDistance((image).pixel((x), (y)), (color)), (tolerance)) \
      << "pixel (" << (x) << ", " << (y) << ") is "                                        \
      << ::render_test::describe((image).pixel((x), (y))) << ", expected "                 \
      << ::render_test::describe(color)

}  // namespace render_test
