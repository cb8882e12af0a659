// What every command parsed with CLI11 shares: its arguments handed over, `--help` printed on
// stdout with exit 0, and a bad command line as one line on stderr with exit 2.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "game/level/level.h"
#include "game/match/input.h"
#include "game/run_files.h"

namespace game {

// Exit codes every command keeps.
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;  // a file that cannot be read or written
inline constexpr int kExitUsage = 2;     // a bad command line
inline constexpr int kExitDiverged = 3;  // a replay whose state left the recording's
inline constexpr int kExitDamaged = 4;   // a truncated or corrupt recording

// Parses; nothing when the command should go on, or the code to exit with.
inline std::optional<int> parseCommandLine(CLI::App& app, const char* command,
                                           std::span<const std::string_view> args) {
  std::vector<std::string> argv{command};
  for (std::string_view a : args)
    argv.emplace_back(a);
  std::vector<const char*> raw;
  for (const std::string& a : argv)
    raw.push_back(a.c_str());
  try {
    app.parse(static_cast<int>(raw.size()), raw.data());
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      std::fputs(app.help().c_str(), stdout);
      return kExitOk;
    }
    std::fprintf(stderr, "%s: %s (try %s --help)\n", command, e.what(), command);
    return kExitUsage;
  }
  return std::nullopt;
}

// A tick count, or seconds with an "s" ("90s", "1.5s"), at 60 ticks per second.
inline std::optional<std::int64_t> parseTick(const std::string& text) {
  try {
    std::size_t used = 0;
    if (!text.empty() && text.back() == 's') {
      const double seconds = std::stod(text.substr(0, text.size() - 1), &used);
      if (used + 1 != text.size() || !(seconds >= 0.0) || seconds > 1e9) return std::nullopt;
      return static_cast<std::int64_t>(seconds * kTicksPerSecond + 0.5);
    }
    const long long ticks = std::stoll(text, &used);
    if (used != text.size() || ticks < 0) return std::nullopt;
    return ticks;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// A level's files as inputs of the run (game/run_files.h): the map, then its external tilesets,
// which an output must not overwrite either.
inline std::vector<RunInput> levelInputs(const Level& level) {
  std::vector<RunInput> inputs;
  for (std::size_t i = 0; i < level.files.size(); ++i)
    inputs.push_back({i == 0 ? "the level" : "a tileset of the level", level.files[i]});
  return inputs;
}

// A refused input or output as the command's one line on stderr ("--help" hinted for a
// command-line error); returns the exit code.
inline int refuse(const char* command, const RunFileError& error) {
  std::fprintf(
      stderr, "%s: %s%s\n", command, error.message.c_str(),
      error.exitCode == kExitUsage ? (std::string(" (try ") + command + " --help)").c_str() : "");
  return error.exitCode;
}

}  // namespace game
