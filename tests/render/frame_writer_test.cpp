// FrameWriter: numbered frames written on a worker thread, bounded queue, errors surfaced.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "render/frame_writer.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace frame_writer_test {

using render::FrameWriter;
using render::FrameWriterOptions;
using render::Image;

Image solid(int w, int h, render::Color c) {
  Image image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x)
      image.setPixel(x, y, c);
  }
  return image;
}

TEST(FrameWriter, WritesEveryFrameUnderItsNumber) {
  render_test::ScratchDir dir;
  FrameWriterOptions options;
  options.directory = dir.path() / "frames";  // created by the writer
  options.queueCapacity = 2;
  FrameWriter writer(options);
  for (int i = 0; i < 10; ++i) {
    std::filesystem::path path = writer.submit(i, solid(16, 9, {std::uint8_t(i * 20), 0, 0, 255}));
    EXPECT_EQ(path, options.directory / render::frameFileName(i));
  }
  writer.finish();
  EXPECT_EQ(writer.stats().framesWritten, 10);
  for (int i = 0; i < 10; ++i) {
    Image back = render::readPng(options.directory / render::frameFileName(i));
    EXPECT_EQ(back.pixel(3, 3), (render::Color{std::uint8_t(i * 20), 0, 0, 255}));
  }
  int files = 0;
  for ([[maybe_unused]] const auto& entry :
       std::filesystem::directory_iterator(options.directory)) {
    ++files;
  }
  EXPECT_EQ(files, 10);  // no temporaries left behind
  EXPECT_THROW(writer.submit(10, solid(2, 2, render::colors::kRed)), std::logic_error);
}

TEST(FrameWriter, DestructorWritesWhatIsQueued) {
  render_test::ScratchDir dir;
  {
    FrameWriter writer({dir.path(), "shot_", 8, {}});
    for (int i = 0; i < 5; ++i)
      writer.submit(i, solid(8, 8, render::colors::kBlue));
  }
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(std::filesystem::exists(dir.path() / render::frameFileName(i, "shot_")));
  }
}

TEST(FrameWriter, DirectoryThatCannotBeMadeIsNamed) {
  render_test::ScratchDir dir;
  std::filesystem::path file = dir.path() / "file";
  std::ofstream(file) << "x";
  std::filesystem::path target = file / "frames";
  try {
    FrameWriter writer({target, "frame_", 4, {}});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(
                  "render: cannot use '" + target.string() + "' as the frame directory: ", 0),
              0u)
        << e.what();
  }
}

TEST(FrameWriter, FailedWriteSurfacesOnTheCallersThread) {
  render_test::ScratchDir dir;
  std::filesystem::path frames = dir.path() / "frames";
  FrameWriter writer({frames, "frame_", 4, {}});
  writer.submit(0, solid(8, 8, render::colors::kRed));
  writer.flush();
  // The directory goes away under the writer (a full or unmounted disk behaves the same).
  std::filesystem::remove_all(frames);
  writer.submit(1, solid(8, 8, render::colors::kRed));
  std::string expected = "render: cannot write '" + (frames / "frame_000001.png").string() +
                         "': No such file or directory";
  try {
    writer.finish();
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(e.what(), expected);
  }
  EXPECT_EQ(writer.stats().framesWritten, 1);
}

}  // namespace frame_writer_test
