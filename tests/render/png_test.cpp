// PNG output: round trip through a file, atomic writes, names, and a clear error for a
// directory that cannot be written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include "render/png.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace png_test {

using render::Image;

Image testPattern(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.setPixel(x, y,
                     {static_cast<std::uint8_t>(x * 7), static_cast<std::uint8_t>(y * 13),
                      static_cast<std::uint8_t>((x * y) & 255),
                      static_cast<std::uint8_t>(x < w / 2 ? 255 : 128)});
    }
  }
  return image;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Png, RoundTripKeepsEveryByte) {
  render_test::ScratchDir dir;
  const Image image = testPattern(37, 23);  // odd sizes: no row padding anywhere
  for (int level : {1, 6, 9}) {
    std::filesystem::path path = dir.path() / ("pattern" + std::to_string(level) + ".png");
    render::writePng(path, image, {level});
    Image back = render::readPng(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_TRUE(back == image) << "level " << level;
  }
}

TEST(Png, WritesLeaveNoTemporaryFiles) {
  render_test::ScratchDir dir;
  render::writePng(dir.path() / "a.png", testPattern(8, 8));
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.png");
  }
  EXPECT_EQ(files, 1);
}

TEST(Png, FrameNamesHaveSixDigits) {
  EXPECT_EQ(render::frameFileName(0), "frame_000000.png");
  EXPECT_EQ(render::frameFileName(123), "frame_000123.png");
  EXPECT_EQ(render::frameFileName(1234567), "frame_1234567.png");
  EXPECT_EQ(render::frameFileName(5, "shot_"), "shot_000005.png");
}

TEST(Png, UnwritableDirectoryGivesOneLineNamingThePath) {
  render_test::ScratchDir dir;
  // A regular file where a directory should be: fails for root too.
  std::filesystem::path notADir = dir.path() / "file";
  std::ofstream(notADir) << "x";
  std::filesystem::path target = notADir / "frame_000001.png";
  EXPECT_EQ(errorOf([&] { render::writePng(target, testPattern(4, 4)); }),
            "render: cannot write '" + target.string() + "': Not a directory");
  std::filesystem::path missing = dir.path() / "no" / "such" / "frame_000002.png";
  EXPECT_EQ(errorOf([&] { render::writePng(missing, testPattern(4, 4)); }),
            "render: cannot write '" + missing.string() + "': No such file or directory");
}

TEST(Png, ReadOnlyDirectoryIsReported) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes through directory permissions";
  render_test::ScratchDir dir;
  std::filesystem::permissions(
      dir.path(), std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  std::filesystem::path target = dir.path() / "frame_000001.png";
  EXPECT_EQ(errorOf([&] { render::writePng(target, testPattern(4, 4)); }),
            "render: cannot write '" + target.string() + "': Permission denied");
}

TEST(Png, ReadingAMissingOrBrokenFileNamesIt) {
  render_test::ScratchDir dir;
  std::filesystem::path broken = dir.path() / "broken.png";
  std::ofstream(broken) << "not a png";
  EXPECT_EQ(errorOf([&] {
              render::readPng(broken);
            }).rfind("render: cannot read PNG '" + broken.string() + "': ", 0),
            0u);
  EXPECT_EQ(errorOf([&] {
              render::readPng(dir.path() / "none.png");
            }).rfind("render: cannot read PNG '", 0),
            0u);
}

TEST(Png, EncodingRejectsAnInconsistentImage) {
  Image bad(4, 4);
  bad.rgba.pop_back();
  EXPECT_THROW(render::encodePng(bad), std::runtime_error);
  EXPECT_THROW(render::encodePng(testPattern(2, 2), {0}), std::invalid_argument);
}

}  // namespace png_test
