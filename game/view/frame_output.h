// Frames of a run, one piece for every command that renders one (sim, play, replay): the options
// and their checks, the renderer and the frame writer (made only when frames are asked for),
// step 0 and every K-th step after it, the contact sheet, the video through ffmpeg, and the
// closing line on stderr. What a frame shows is the command's (scene_view.h, match_view.h); this
// turns frames into files.
//
// Errors are one line each. Bad values and combinations are command-line errors (exit code 2):
// a size outside 16..8192, --sheet or --video without --frames, an output that names an input of
// the run (the level, the scene) or a frame's file. An output that cannot be written is exit
// code 1: a directory that cannot be made or is a file, a sheet or video in a missing directory.
// All of these are found before the run starts.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "game/run_files.h"

namespace CLI {
class App;
}
namespace render {
struct Frame;
struct Camera;
}  // namespace render

namespace game {

struct FrameOptions {
  std::string directory;          // --frames DIR; empty: no frames
  long every = 1;                 // --every K: step 0 and every K-th step
  int width = 640, height = 360;  // --size WxH
  bool overlay = false;           // the command's overlay (sim: on unless --no-overlay)
  std::string sheet;              // --sheet FILE: a contact sheet of up to 24 of the frames
  std::string video;              // --video FILE: an MP4, or a GIF by its name, through ffmpeg
  bool enabled() const { return !directory.empty(); }
};

// A line for the user and the exit code it calls for (2: the command line, 1: an output).
using FrameOptionError = RunFileError;

// --every K (a whole number >= 1) and --size WxH (16 to 8192 pixels each): nothing, or the
// error's text ("--size must be WxH with 16 to 8192 pixels each, got '10x10'").
std::optional<std::string> parseEvery(std::string_view text, long& every);
std::optional<std::string> parseSize(std::string_view text, int& width, int& height);

// Commands written with CLI11: --frames, --every, --size, --overlay, --sheet and --video added to
// `app` (their help counting in `unit`s: "tick", "step"); their texts wait in `args` until
// frameOptionsFrom reads and checks them.
struct FrameArgs {
  std::string frames, every = "1", size = "640x360", sheet, video;
  bool overlay = false;
};
void addFrameOptions(CLI::App& app, FrameArgs& args, const std::string& unit = "step");
std::optional<FrameOptionError> frameOptionsFrom(const FrameArgs& args, FrameOptions& out);

// Every check that writes nothing: --sheet and --video need --frames, the renderer was built,
// no output is an input of the run, the sheet or video is not also a frame's file or each other.
std::optional<FrameOptionError> checkFrameOptions(const FrameOptions& options,
                                                  std::span<const RunInput> inputs);

// An output that cannot be written (exit code 1), before or during the run.
class FrameOutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FrameOutput {
 public:
  // Without options.directory, nothing is made and every call does nothing. Otherwise checks that
  // the sheet's and the video's directories exist (or are the frames' own), makes the directory
  // (FrameOutputError for any of these when it cannot be, or it is a file), and makes the renderer
  // and the writer thread. `command`
  // starts the lines on stderr ("ricochet play"); `steps` is the run's length (the sheet picks
  // its frames evenly from it); `stepSeconds` the simulated time of a step (the video's rate).
  FrameOutput(const FrameOptions& options, std::string command, long steps, double stepSeconds);
  ~FrameOutput();
  FrameOutput(const FrameOutput&) = delete;
  FrameOutput& operator=(const FrameOutput&) = delete;

  bool enabled() const { return impl_ != nullptr; }
  // Whether step `step` is one to draw: step 0 and every K-th step.
  bool due(long step) const;
  // Renders frame `step` (a due one) as `camera` sees it and queues it for writing as
  // frame_<step / K>.png. A failed write (full disk) is thrown as FrameOutputError.
  void add(long step, const render::Frame& frame, const render::Camera& camera);
  // Frames handed to add() so far.
  long long framesAdded() const;
  // Waits for the writer, writes the sheet and the video, and prints "<command>: N frames in DIR"
  // (and the video's outcome) on stderr. Once; the destructor writes what is queued otherwise.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace game
