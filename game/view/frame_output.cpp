#include "game/view/frame_output.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#ifdef RICOCHET_HAS_RENDER
#include "render/contact_sheet.h"
#include "render/frame_writer.h"
#include "render/png.h"
#include "render/renderer.h"
#endif

namespace fs = std::filesystem;

namespace game {
namespace {

std::optional<FrameOptionError> usage(std::string message) {
  return FrameOptionError{2, std::move(message)};
}

}  // namespace

std::optional<std::string> parseEvery(std::string_view text, long& every) {
  long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 1)
    return "--every must be a whole number >= 1, got '" + std::string(text) + "'";
  every = value;
  return std::nullopt;
}

std::optional<std::string> parseSize(std::string_view v, int& width, int& height) {
  const std::size_t x = v.find('x');
  int w = 0, h = 0;
  bool ok = x != std::string_view::npos;
  if (ok) {
    const auto [e1, c1] = std::from_chars(v.data(), v.data() + x, w);
    const auto [e2, c2] = std::from_chars(v.data() + x + 1, v.data() + v.size(), h);
    ok = c1 == std::errc() && e1 == v.data() + x && c2 == std::errc() &&
         e2 == v.data() + v.size() && w >= 16 && h >= 16 && w <= 8192 && h <= 8192;
  }
  if (!ok) return "--size must be WxH with 16 to 8192 pixels each, got '" + std::string(v) + "'";
  width = w;
  height = h;
  return std::nullopt;
}

void addFrameOptions(CLI::App& app, FrameArgs& args, const std::string& unit) {
  app.add_option(
         "--frames", args.frames,
         "render frame_000000.png, ... into DIR (" + unit + " 0 and every K-th " + unit + ")")
      ->option_text("DIR");
  app.add_option("--every", args.every, "with --frames: every K-th " + unit + " (default 1)")
      ->option_text("K");
  app.add_option("--size", args.size, "with --frames: frame size in pixels (default 640x360)")
      ->option_text("WxH");
  app.add_flag("--overlay", args.overlay, "with --frames: draw what the bots perceive");
  app.add_option("--sheet", args.sheet,
                 "with --frames: also a contact sheet of up to 24 of the frames")
      ->option_text("FILE");
  app.add_option("--video", args.video,
                 "with --frames: also an MP4 (or a GIF, by the name) of the frames, if ffmpeg "
                 "is installed")
      ->option_text("FILE");
}

std::optional<FrameOptionError> frameOptionsFrom(const FrameArgs& args, FrameOptions& out) {
  out.directory = args.frames;
  out.sheet = args.sheet;
  out.video = args.video;
  out.overlay = args.overlay;
  if (auto e = parseEvery(args.every, out.every)) return usage(*e);
  if (auto e = parseSize(args.size, out.width, out.height)) return usage(*e);
  return std::nullopt;
}

std::optional<FrameOptionError> checkFrameOptions(const FrameOptions& options,
                                                  std::span<const RunInput> inputs) {
  if (!options.enabled() && !options.sheet.empty()) return usage("--sheet needs --frames");
  if (!options.enabled() && !options.video.empty()) return usage("--video needs --frames");
  if (!options.enabled()) return std::nullopt;
#ifndef RICOCHET_HAS_RENDER
  return usage("--frames: this ricochet was built without the renderer (-DRICOCHET_RENDER=OFF)");
#endif
  const std::pair<const char*, const std::string*> outputs[] = {
      {"--frames", &options.directory}, {"--sheet", &options.sheet}, {"--video", &options.video}};
  for (const auto& [option, path] : outputs) {
    if (path->empty()) continue;
    for (const RunInput& input : inputs)
      if (!input.path.empty() && sameFile(*path, input.path))
        return usage(std::string(option) + " '" + *path + "' is " + input.what +
                     ", an input of this run");
  }
  if (!options.sheet.empty() && options.sheet == options.video)
    return usage("--sheet and --video name the same file '" + options.sheet + "'");
  // A sheet or video named like a frame in the frames' directory would be overwritten by it.
  for (const auto& [option, path] : std::span(outputs).subspan(1)) {
    const fs::path p(*path);
    const std::string name = p.filename().string();
    if (!path->empty() && name.rfind("frame_", 0) == 0 && p.extension() == ".png" &&
        sameFile(p.parent_path().empty() ? fs::path(".") : p.parent_path(), options.directory))
      return usage(std::string(option) + " '" + *path + "' is the name of a frame of the run");
  }
  return std::nullopt;
}

#ifdef RICOCHET_HAS_RENDER

namespace {

// The frames as a video through ffmpeg, if it is installed (never required): run without a
// shell, so no path is ever interpreted, and without stdin, so it never waits on a terminal.
// Returns what happened, for the log.
std::string encodeVideo(const std::string& dir, double fps, const std::string& out) {
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  const std::string pattern = dir + "/frame_%06d.png";
  const bool gif = out.size() >= 4 && out.compare(out.size() - 4, 4, ".gif") == 0;
  std::vector<std::string> args = {"ffmpeg",     "-nostdin", "-y", "-loglevel", "error",
                                   "-framerate", rate,       "-i", pattern};
  if (gif) {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse"});
  } else {
    // yuv420p needs even sizes; pad by a pixel when a frame's side is odd.
    args.insert(args.end(),
                {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p", "-c:v", "libx264"});
  }
  args.push_back(out);
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, "ffmpeg", nullptr, nullptr, argv.data(), environ) != 0)
    return "--video: ffmpeg is not installed (Debian package ffmpeg); the frames are in " + dir;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "--video: ffmpeg failed to write " + out + "; the frames are in " + dir;
  return "video in " + out;
}

// The directory a file will be written in must exist, or be the frames' own (found now, not after
// a long run).
void checkParent(const char* option, const std::string& file, const fs::path& frames) {
  if (file.empty()) return;
  std::error_code ec;
  if (fs::is_directory(file, ec))
    throw FrameOutputError(std::string(option) + ": '" + file + "' is a directory");
  const fs::path parent = fs::path(file).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec) && !sameFile(parent, frames))
    throw FrameOutputError(std::string(option) + ": cannot write '" + file + "': no directory '" +
                           parent.string() + "'");
}

}  // namespace

struct FrameOutput::Impl {
  FrameOptions options;
  std::string command;
  double stepSeconds = 0.0;
  long sheetEvery = 1;
  long long added = 0;
  bool finished = false;
  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<render::FrameWriter> writer;
  std::vector<render::Image> sheet;
};

FrameOutput::FrameOutput(const FrameOptions& options, std::string command, long steps,
                         double stepSeconds) {
  if (!options.enabled()) return;
  const fs::path dir(options.directory);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw FrameOutputError("--frames: '" + options.directory + "' is a file, not a directory");
  checkParent("--sheet", options.sheet, dir);
  checkParent("--video", options.video, dir);
  fs::create_directories(dir, ec);
  if (ec)
    throw FrameOutputError("--frames: cannot create directory '" + options.directory +
                           "': " + ec.message());
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw FrameOutputError("--frames: cannot write in '" + options.directory +
                           "': " + std::strerror(errno));
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->command = std::move(command);
  impl->stepSeconds = stepSeconds;
  // Up to 24 frames on the sheet, evenly spaced over the run.
  impl->sheetEvery = std::max(1L, (steps / options.every + 1 + 23) / 24);
  impl->renderer = std::make_unique<render::Renderer>();
  render::FrameWriterOptions writerOptions;
  writerOptions.directory = dir;
  impl->writer = std::make_unique<render::FrameWriter>(writerOptions);
  impl_ = std::move(impl);
}

FrameOutput::~FrameOutput() = default;

bool FrameOutput::due(long step) const {
  return impl_ && !impl_->finished && step % impl_->options.every == 0;
}

void FrameOutput::add(long step, const render::Frame& frame, const render::Camera& camera) {
  if (!impl_ || impl_->finished) return;
  Impl& m = *impl_;
  render::Image image = m.renderer->render(frame, camera);
  const long index = step / m.options.every;
  if (!m.options.sheet.empty() && index % m.sheetEvery == 0) m.sheet.push_back(image);
  try {
    m.writer->submit(index, std::move(image));
  } catch (const std::exception& e) {
    throw FrameOutputError(e.what());
  }
  ++m.added;
}

long long FrameOutput::framesAdded() const {
  return impl_ ? impl_->added : 0;
}

void FrameOutput::finish() {
  if (!impl_ || impl_->finished) return;
  Impl& m = *impl_;
  m.finished = true;
  try {
    m.writer->finish();
    if (!m.options.sheet.empty() && !m.sheet.empty())
      render::writePng(m.options.sheet, render::contactSheet(m.sheet));
  } catch (const std::exception& e) {
    throw FrameOutputError(e.what());
  }
  std::fprintf(stderr, "%s: %lld frames in %s\n", m.command.c_str(),
               static_cast<long long>(m.writer->stats().framesWritten),
               m.options.directory.c_str());
  if (!m.options.video.empty()) {
    const double fps = 1.0 / (m.stepSeconds * static_cast<double>(m.options.every));
    const std::string result = encodeVideo(m.options.directory, fps, m.options.video);
    std::fprintf(stderr, "%s: %s\n", m.command.c_str(), result.c_str());
  }
}

#else  // without the renderer: checkFrameOptions refuses --frames, so nothing is ever made

struct FrameOutput::Impl {};

FrameOutput::FrameOutput(const FrameOptions& options, std::string, long, double) {
  if (options.enabled())
    throw FrameOutputError(
        "--frames: this ricochet was built without the renderer (-DRICOCHET_RENDER=OFF)");
}
FrameOutput::~FrameOutput() = default;
bool FrameOutput::due(long) const {
  return false;
}
void FrameOutput::add(long, const render::Frame&, const render::Camera&) {}
long long FrameOutput::framesAdded() const {
  return 0;
}
void FrameOutput::finish() {}

#endif

}  // namespace game
