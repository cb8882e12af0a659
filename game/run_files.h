// The files a run reads and writes, checked before it starts: an output never overwrites an
// input of the run (the scene, the level and its tilesets, the recording) or another output, and
// an output file can be made where it is named. Shared by every command that writes (sim, play,
// replay, render, frames of a run: game/view/frame_output) and by the tests' box2d_sim, so
// header-only and the standard library only.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <system_error>

namespace game {

// A file the run reads ("the level", its path): no output may overwrite it.
struct RunInput {
  std::string what;
  std::string path;
};

// A file the run writes and the option that named it ("--out", its path).
struct RunOutput {
  std::string option;
  std::string path;
};

// A line for the user and the exit code it calls for (2: the command line, 1: an output that
// cannot be written).
struct RunFileError {
  int exitCode = 2;
  std::string message;
};

// Whether two paths name one file, whether or not it exists yet: the same inode through links
// and relative paths alike, else the same path once made absolute and its links resolved.
inline bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a, ec), ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && ca == cb;
}

// An output that names an input of the run ("--out 'scene.json' is the scene, an input of this
// run") or another output ("--out and --csv name the same file 'x'"): a command-line error.
// Empty paths are outputs not asked for.
inline std::optional<RunFileError> outputOverwritesAnother(std::span<const RunOutput> outputs,
                                                           std::span<const RunInput> inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const RunOutput& out = outputs[i];
    if (out.path.empty()) continue;
    for (const RunInput& input : inputs)
      if (!input.path.empty() && sameFile(out.path, input.path))
        return RunFileError{
            2, out.option + " '" + out.path + "' is " + input.what + ", an input of this run"};
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
      if (!outputs[j].path.empty() && sameFile(out.path, outputs[j].path))
        return RunFileError{
            2, out.option + " and " + outputs[j].option + " name the same file '" + out.path + "'"};
  }
  return std::nullopt;
}

// An output file that cannot be made where it is named: a directory ("--out: 'x' is a
// directory") or in a directory that does not exist. Found before the run, not after it.
inline std::optional<RunFileError> outputFileUnwritable(const RunOutput& out) {
  namespace fs = std::filesystem;
  if (out.path.empty()) return std::nullopt;
  std::error_code ec;
  if (fs::is_directory(out.path, ec))
    return RunFileError{1, out.option + ": '" + out.path + "' is a directory"};
  const fs::path parent = fs::path(out.path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    return RunFileError{1, out.option + ": cannot write '" + out.path + "': no directory '" +
                               parent.string() + "'"};
  return std::nullopt;
}

}  // namespace game
