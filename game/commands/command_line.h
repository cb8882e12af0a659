// What every command parsed with CLI11 shares: its arguments handed over, `--help` printed on
// stdout with exit 0, and a bad command line as one line on stderr with exit 2.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "game/match/input.h"

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

// Whether two paths name one file (the same inode, through links and relative paths alike): an
// output that is an input of the run is refused, never overwritten.
inline bool sameFile(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  return fs::absolute(a, ec).lexically_normal() == fs::absolute(b, ec).lexically_normal();
}

}  // namespace game
