// Frames of a run (game/view/frame_output): the options' values and messages, the checks made
// before a run (outputs that would overwrite an input or a frame, a frames directory that is a
// file, a sheet in a missing directory), and the files a run leaves: step 0 and every K-th step,
// and the sheet.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "game/view/frame_output.h"
#include "render/camera.h"
#include "render/draw_list.h"
#include "render/png.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace frame_output_test {

namespace fs = std::filesystem;
using game::FrameOptions;
using game::FrameOutput;
using game::FrameOutputError;
using game::RunInput;
using render_test::ScratchDir;

TEST(FrameOptions, SizeAndEveryParseOrSayWhatIsWrong) {
  int w = 0, h = 0;
  EXPECT_FALSE(game::parseSize("1280x720", w, h));
  EXPECT_EQ(w, 1280);
  EXPECT_EQ(h, 720);
  for (const char* bad : {"15x100", "100x8193", "640", "640x", "x360", "640x360x2", "-640x360"}) {
    const auto e = game::parseSize(bad, w, h);
    ASSERT_TRUE(e) << bad;
    EXPECT_EQ(*e, std::string("--size must be WxH with 16 to 8192 pixels each, got '") + bad + "'");
  }
  long every = 0;
  EXPECT_FALSE(game::parseEvery("30", every));
  EXPECT_EQ(every, 30);
  EXPECT_EQ(*game::parseEvery("0", every), "--every must be a whole number >= 1, got '0'");
  EXPECT_TRUE(game::parseEvery("2.5", every));
}

TEST(FrameOptions, ChecksBeforeTheRun) {
  ScratchDir dir;
  const std::string level = (dir.path() / "level.tmj").string();
  std::ofstream(level) << "{}";
  const RunInput inputs[] = {{"the level", level}};
  FrameOptions o;
  EXPECT_FALSE(game::checkFrameOptions(o, inputs));
  o.sheet = (dir.path() / "sheet.png").string();
  auto e = game::checkFrameOptions(o, inputs);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->exitCode, 2);
  EXPECT_EQ(e->message, "--sheet needs --frames");
  o.sheet.clear();
  o.video = "run.mp4";
  EXPECT_EQ(game::checkFrameOptions(o, inputs)->message, "--video needs --frames");
  // An output that is an input of the run, however it is spelled.
  o.video.clear();
  o.directory = (dir.path() / "frames").string();
  o.sheet = (dir.path() / "." / "level.tmj").string();
  e = game::checkFrameOptions(o, inputs);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->exitCode, 2);
  EXPECT_EQ(e->message, "--sheet '" + o.sheet + "' is the level, an input of this run");
  o.sheet = (dir.path() / "frames" / "frame_000002.png").string();
  EXPECT_EQ(game::checkFrameOptions(o, inputs)->message,
            "--sheet '" + o.sheet + "' is the name of a frame of the run");
  o.sheet = o.video = (dir.path() / "out.gif").string();
  EXPECT_EQ(game::checkFrameOptions(o, inputs)->message,
            "--sheet and --video name the same file '" + o.sheet + "'");
  o.video.clear();
  EXPECT_FALSE(game::checkFrameOptions(o, inputs));
}

TEST(FrameOutput, MakesNothingWithoutFrames) {
  FrameOutput output(FrameOptions{}, "test", 100, 1.0 / 60.0);
  EXPECT_FALSE(output.enabled());
  EXPECT_FALSE(output.due(0));
  output.finish();
  EXPECT_EQ(output.framesAdded(), 0);
}

TEST(FrameOutput, RefusesAFileForADirectoryAndAMissingDirectoryForTheSheet) {
  ScratchDir dir;
  FrameOptions o;
  o.directory = (dir.path() / "file").string();
  std::ofstream(o.directory) << "x";
  try {
    FrameOutput output(o, "test", 10, 1.0);
    FAIL() << "a file taken for the frames' directory";
  } catch (const FrameOutputError& e) {
    EXPECT_EQ(std::string(e.what()), "--frames: '" + o.directory + "' is a file, not a directory");
  }
  o.directory = (dir.path() / "frames").string();
  o.sheet = (dir.path() / "missing" / "sheet.png").string();
  try {
    FrameOutput output(o, "test", 10, 1.0);
    FAIL() << "a sheet in a missing directory";
  } catch (const FrameOutputError& e) {
    EXPECT_EQ(std::string(e.what()), "--sheet: cannot write '" + o.sheet + "': no directory '" +
                                         (dir.path() / "missing").string() + "'");
  }
}

TEST(FrameOutput, WritesStepZeroAndEveryKthStepAndTheSheet) {
  ScratchDir dir;
  FrameOptions o;
  o.directory = (dir.path() / "frames" / "nested").string();  // made, parents too
  o.every = 4;
  o.width = 64;
  o.height = 48;
  o.sheet = (dir.path() / "frames" / "nested" / "sheet.png").string();
  FrameOutput output(o, "test", 10, 1.0 / 60.0);
  const render::Camera camera = render::Camera::fit({{-1, -1}, {1, 1}}, o.width, o.height);
  for (long step = 0; step <= 10; ++step) {
    if (!output.due(step)) continue;
    render::Frame frame;
    frame.world.circle({0, 0}, 0.5f, render::Style::filled(render::colors::kRed));
    output.add(step, frame, camera);
  }
  output.finish();
  EXPECT_EQ(output.framesAdded(), 3);  // steps 0, 4 and 8
  for (int i = 0; i < 3; ++i) {
    const render::Image image = render::readPng(fs::path(o.directory) / render::frameFileName(i));
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 48);
  }
  EXPECT_FALSE(fs::exists(fs::path(o.directory) / render::frameFileName(3)));
  EXPECT_TRUE(fs::exists(o.sheet));
  EXPECT_FALSE(output.due(12)) << "finished";
}

}  // namespace frame_output_test
