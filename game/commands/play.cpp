// `ricochet play LEVEL.tmj [--bots K] [--seed S] [--ticks N] [--weapons FILE] [--json]
//                         [--frames DIR --every K --size WxH --overlay --sheet FILE --video FILE]`
// A headless match on a level, the players on autopilot: prints one summary line (ticks, kills,
// shots, explosions, the final hash, ticks per second of wall time). What a recording will replay,
// and what the determinism tests compare across builds. With --frames, the match is rendered
// (game/view/match_frames.h); progress goes to stderr on long runs.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/commands/progress.h"
#include "game/level/level_error.h"
#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/view/match_frames.h"
#include "game/weapons/weapon_table.h"

namespace game {

int runPlay(std::span<const std::string_view> args) {
  CLI::App app{
      "Plays a headless match on a Tiled level: bots against the players, the players on\n"
      "autopilot. Prints one summary line on stdout; --frames renders the match.\n"
      "Exit codes: 0 done, 1 bad level or weapon table or unwritable output, 2 bad command line.",
      "ricochet play"};
  std::string levelPath;
  int bots = -1, players = 1;
  std::uint64_t seed = 1;
  long long ticks = 60 * kTicksPerSecond;
  bool json = false;
  std::string weaponsPath = bundledWeaponTablePath();
  app.add_option("level", levelPath, "the level (.tmj)")->required();
  app.add_option("--bots", bots, "bots to field (default: one per bot spawn)")
      ->check(CLI::Range(0, 256));
  app.add_option("--players", players, "players, on autopilot (default 1)")
      ->check(CLI::Range(0, 16));
  app.add_option("--seed", seed, "the match's randomness (default 1)");
  app.add_option("--ticks", ticks, "ticks to play at 60 per second (default 3600: a minute)")
      ->check(CLI::Range(0LL, 1LL << 31));
  app.add_option("--weapons", weaponsPath, "the weapon table (default: the bundled one)");
  app.add_flag("--json", json, "the summary as a JSON object");
  FrameArgs frameArgs;
  addFrameOptions(app, frameArgs, "tick");
  std::vector<std::string> argv{"ricochet play"};
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
      return 0;
    }
    std::fprintf(stderr, "ricochet play: %s (try ricochet play --help)\n", e.what());
    return 2;
  }
  FrameOptions frameOptions;
  const RunInput inputs[] = {{"the level", levelPath}, {"the weapon table", weaponsPath}};
  auto frameError = frameOptionsFrom(frameArgs, frameOptions);
  if (!frameError) frameError = checkFrameOptions(frameOptions, inputs);
  if (frameError) {
    std::fprintf(stderr, "ricochet play: %s%s\n", frameError->message.c_str(),
                 frameError->exitCode == 2 ? " (try ricochet play --help)" : "");
    return frameError->exitCode;
  }

  try {
    MatchConfig config;
    config.bots = bots;
    config.players = players;
    config.seed = seed;
    config.weapons = loadWeaponTable(weaponsPath);
    Match match(loadLevel(levelPath), config);
    MatchFrames frames(frameOptions, "ricochet play", match.state(), static_cast<long>(ticks),
                       levelPath);
    Progress progress("ricochet play", "tick", ticks);
    const auto start = std::chrono::steady_clock::now();
    std::size_t shots = 0, explosions = 0;
    frames.update(match.state());
    for (long long t = 0; t < ticks; ++t) {
      match.tick();
      frames.update(match.state());
      // Trigger pulls: a shotgun's pellets count once.
      for (const Shot& shot : match.state().shots)
        shots += shot.pellet == 0;
      explosions += match.state().explosions.size();
      progress.update(t + 1, frameOptions.enabled() ? frames.framesAdded() : -1);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    frames.finish();  // the last frames, the sheet and the video: after the clock stops
    int kills = 0, deaths = 0;
    for (const Actor& a : match.state().actors) {
      kills += a.kills;
      deaths += a.deaths;
    }
    const double rate = seconds > 0.0 ? static_cast<double>(ticks) / seconds : 0.0;
    const auto hash = static_cast<unsigned long long>(match.hash());
    if (json) {
      std::printf(
          "{\"ticks\": %lld, \"actors\": %zu, \"kills\": %d, \"deaths\": %d, \"shots\": %zu, "
          "\"explosions\": %zu, \"hash\": \"%016llx\", \"ticks_per_second\": %.0f}\n",
          ticks, match.state().actors.size(), kills, deaths, shots, explosions, hash, rate);
    } else {
      std::printf(
          "ticks %lld actors %zu kills %d deaths %d shots %zu explosions %zu hash %016llx "
          "ticks_per_second %.0f\n",
          ticks, match.state().actors.size(), kills, deaths, shots, explosions, hash, rate);
    }
    return 0;
  } catch (const FrameOutputError& e) {
    std::fprintf(stderr, "ricochet play: %s\n", e.what());
    return 1;
  } catch (const WeaponTableError& e) {
    std::fprintf(stderr, "ricochet play: %s\n", e.what());
    return 1;
  } catch (const LevelError& e) {
    std::fprintf(stderr, "ricochet play: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ricochet play: %s: %s\n", levelPath.c_str(), e.what());
    return 1;
  }
}

}  // namespace game
