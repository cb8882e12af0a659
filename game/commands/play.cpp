// `ricochet play LEVEL.tmj [--bots K] [--seed S] [--ticks N] [--weapons FILE] [--json]
//                         [--record FILE] [--input FILE|-]
//                         [--frames DIR --every K --size WxH --overlay --sheet FILE --video FILE]`
// A headless match on a level, the players on autopilot: prints one summary line (ticks, kills,
// shots, explosions, pickups taken, crashes, exits, suicides, each team's score, the final hash,
// ticks per second of wall time). What a recording will replay, and what the determinism tests
// compare across builds. --record writes the match as it plays (game/session/recording.h),
// --input takes the players' controls from a script; with --frames the match is rendered
// (game/view/match_frames.h); progress goes to stderr on long runs.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/commands/progress.h"
#include "game/level/level_error.h"
#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/session/input_script.h"
#include "game/session/recording.h"
#include "game/view/match_frames.h"
#include "game/weapons/weapon_table.h"

namespace game {

int runPlay(std::span<const std::string_view> args) {
  CLI::App app{
      "Plays a headless match on a Tiled level: bots against the players, the players on\n"
      "autopilot. Prints one summary line on stdout.\n"
      "Exit codes: 0 done, 1 bad level, 2 bad command line.",
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
  int lanes = 8;
  app.add_option("--lanes", lanes,
                 "the contact solver's batch width, 4 or 8 (the widest the processor has); the "
                 "match is the same at either")
      ->check(CLI::IsMember({4, 8}));
  bool profile = false;
  app.add_flag("--profile", profile,
               "a second line: the tick's phases in microseconds per tick and their shares "
               "(perception, decisions, movement, weapons, physics, rules)");
  std::string recordPath, inputPath;
  app.add_option("--input", inputPath,
                 "the players' controls from a script (FILE, or - for standard input; the format "
                 "is in game/session/input_script.h) instead of the autopilot");
  int keyframeEvery = 300;
  app.add_option("--record", recordPath,
                 "record the match into FILE (written as it plays: a killed run leaves a file "
                 "that replays up to its last second)");
  app.add_option("--keyframe-every", keyframeEvery,
                 "with --record: ticks between keyframes (default 300, 5 s)")
      ->check(CLI::Range(1, 1 << 20));
  FrameArgs frameArgs;
  addFrameOptions(app, frameArgs, "tick");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet play", args)) return *exit;
  FrameOptions frameOptions;
  std::vector<RunInput> runInputs = {{"the level", levelPath}, {"the weapon table", weaponsPath}};
  if (!inputPath.empty() && inputPath != "-") runInputs.push_back({"the input script", inputPath});
  auto frameError = frameOptionsFrom(frameArgs, frameOptions);
  if (!frameError) frameError = checkFrameOptions(frameOptions, runInputs);
  // The recording: not an input, nor the sheet or the video.
  const RunOutput outputs[] = {
      {"--record", recordPath}, {"--sheet", frameOptions.sheet}, {"--video", frameOptions.video}};
  if (!frameError) frameError = outputOverwritesAnother(outputs, runInputs);
  if (frameError) return refuse("ricochet play", *frameError);

  try {
    MatchConfig config;
    config.bots = bots;
    config.players = players;
    config.seed = seed;
    config.profile = profile;
    config.solverLanes = lanes;
    config.weapons = loadWeaponTable(weaponsPath);
    Level level = loadLevel(levelPath);
    // The level's tilesets are inputs too, known once it is read: before anything is written.
    const std::vector<RunInput> levelFiles = levelInputs(level);
    std::optional<RunFileError> outputError = checkFrameOptions(frameOptions, levelFiles);
    if (!outputError) outputError = outputOverwritesAnother(outputs, levelFiles);
    if (outputError) return refuse("ricochet play", *outputError);
    Match match(std::move(level), config);
    std::ifstream scriptFile;
    std::optional<InputScript> script;
    if (!inputPath.empty()) {
      std::istream* in = &std::cin;
      if (inputPath != "-") {
        scriptFile.open(inputPath);
        if (!scriptFile) {
          std::fprintf(stderr, "ricochet play: %s: cannot open the input script\n",
                       inputPath.c_str());
          return kExitBadInput;
        }
        in = &scriptFile;
      }
      script.emplace(*in, inputPath == "-" ? "standard input" : inputPath, players);
    }
    // The frames first: a frames directory that cannot be made refuses the run before the
    // recorder empties a file given to --record.
    MatchFrames frames(frameOptions, "ricochet play", match.state(), static_cast<long>(ticks),
                       levelPath);
    std::optional<Recorder> recorder;
    if (!recordPath.empty()) {
      RecordingHeader header = headerFor(match, levelPath, recordPath);
      header.keyframeEvery = keyframeEvery;
      recorder.emplace(recordPath, header);
    }
    Progress progress("ricochet play", "tick", ticks);
    const auto start = std::chrono::steady_clock::now();
    std::size_t shots = 0, explosions = 0, crashes = 0;
    frames.update(match.state());
    for (long long t = 0; t < ticks; ++t) {
      if (script) {
        match.tick(script->inputsFor(t));
      } else {
        match.tick();
      }
      if (recorder) recorder->afterTick(match);
      frames.update(match.state());
      // Trigger pulls: a shotgun's pellets count once.
      for (const Shot& shot : match.state().shots)
        shots += shot.pellet == 0;
      explosions += match.state().explosions.size();
      crashes += match.state().crashes.size();
      progress.update(t + 1, frameOptions.enabled() ? frames.framesAdded() : -1);
    }
    if (recorder) recorder->finish(match);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    frames.finish();  // the last frames, the sheet and the video: after the clock stops
    int kills = 0, deaths = 0, exits = 0, suicides = 0, pickups = 0;
    for (const Actor& a : match.state().actors) {
      kills += a.kills;
      deaths += a.deaths;
      exits += a.exits;
      suicides += a.suicides;
    }
    for (const PickupState& p : match.state().pickups)
      pickups += p.timesTaken;
    // Each team's points: "0:12,1:95" on the line, objects in JSON.
    std::string scores, teams;
    for (const TeamScore& t : match.state().teams) {
      scores +=
          (scores.empty() ? "" : ",") + std::to_string(t.team) + ":" + std::to_string(t.score);
      teams += std::string(teams.empty() ? "" : ", ") + "{\"team\": " + std::to_string(t.team) +
               ", \"score\": " + std::to_string(t.score) +
               ", \"kills\": " + std::to_string(t.kills) +
               ", \"deaths\": " + std::to_string(t.deaths) +
               ", \"suicides\": " + std::to_string(t.suicides) +
               ", \"exits\": " + std::to_string(t.exits) + "}";
    }
    const double rate = seconds > 0.0 ? static_cast<double>(ticks) / seconds : 0.0;
    const auto hash = static_cast<unsigned long long>(match.hash());
    if (json) {
      std::printf(
          "{\"ticks\": %lld, \"actors\": %zu, \"kills\": %d, \"deaths\": %d, \"shots\": %zu, "
          "\"explosions\": %zu, \"pickups\": %d, \"crashes\": %zu, \"exits\": %d, "
          "\"suicides\": %d, \"teams\": [%s], \"hash\": \"%016llx\", \"ticks_per_second\": %.0f}\n",
          ticks, match.state().actors.size(), kills, deaths, shots, explosions, pickups, crashes,
          exits, suicides, teams.c_str(), hash, rate);
    } else {
      std::printf(
          "ticks %lld actors %zu kills %d deaths %d shots %zu explosions %zu pickups %d crashes "
          "%zu exits %d suicides %d score %s hash %016llx ticks_per_second %.0f\n",
          ticks, match.state().actors.size(), kills, deaths, shots, explosions, pickups, crashes,
          exits, suicides, scores.empty() ? "-" : scores.c_str(), hash, rate);
    }
    if (profile) {
      const MatchProfile& p = match.state().profile;
      const double total = p.total(),
                   perTick = 1e6 / static_cast<double>(std::max<std::int64_t>(1, p.ticks));
      auto phase = [&](const char* name, double spent) {
        std::printf(" %s %.2f (%.0f%%)", name, spent * perTick,
                    total > 0.0 ? 100.0 * spent / total : 0.0);
      };
      std::printf("profile us_per_tick");
      phase("perception", p.perception);
      phase("decisions", p.decisions);
      phase("movement", p.movement);
      phase("weapons", p.weapons);
      phase("physics", p.physics);
      phase("rules", p.rules);
      std::printf(" total %.2f\n", total * perTick);
    }
    return 0;
  } catch (const FrameOutputError& e) {
    std::fprintf(stderr, "ricochet play: %s\n", e.what());
    return kExitBadInput;
  } catch (const InputScriptError& e) {
    std::fprintf(stderr, "ricochet play: %s\n", e.what());
    return kExitBadInput;
  } catch (const RecordingError& e) {
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
