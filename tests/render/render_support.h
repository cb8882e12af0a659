// Helpers shared by the renderer tests: one Renderer for the whole run (its context, shaders and
// font atlas take a moment to make), a scratch directory per test, and colour comparisons.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

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
