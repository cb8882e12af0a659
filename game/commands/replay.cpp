// `ricochet replay FILE [--verify] [--synctest] [--from T] [--to T] [--level FILE] [--json]
//                  [--frames DIR --every K --size WxH --overlay --sheet FILE --video FILE]`
// re-simulates a recorded session headless and prints one summary line; `--verify` checks every
// recorded hash and names what diverged first. `ricochet replay --batch DIR_OR_LIST --shard i/n
// --jobs J` verifies many sessions, one JSON line each (game/session/batch.h).
#include <sys/resource.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/commands/progress.h"
#include "game/session/batch.h"
#include "game/session/recording.h"
#include "game/session/replay.h"
#include "game/view/match_frames.h"

namespace game {
namespace {

int exitCodeOf(Verdict v) {
  switch (v) {
    case Verdict::ok:
      return kExitOk;
    case Verdict::damaged:
      return kExitDamaged;
    case Verdict::diverged:
    case Verdict::desynced:
      return kExitDiverged;
  }
  return kExitBadInput;
}

}  // namespace

int runReplay(std::span<const std::string_view> args) {
  CLI::App app{
      "Plays a recorded session back headless: the match made again from its header and\n"
      "stepped with its inputs. Prints one summary line on stdout.\n"
      "Exit codes: 0 played (and verified) to the end, 1 a file that cannot be replayed,\n"
      "2 bad command line, 3 diverged (--verify) or desynced (--synctest), 4 a damaged file\n"
      "that played (and verified) up to its last good chunk.",
      "ricochet replay"};
  std::string path, levelPath, fromText, toText, batch, shardText = "0/1";
  bool verify = false, synctest = false, json = false;
  int jobs = 1;
  app.add_option("recording", path, "the recording (.rec)");
  app.add_flag("--verify", verify,
               "check every recorded hash; stop at the first that differs and name what diverged");
  app.add_flag("--synctest", synctest,
               "every tick: save, tick, restore, tick again and compare (finds state that "
               "snapshots miss)");
  app.add_option("--from", fromText, "start at tick T (or Ts seconds), seeking through keyframes");
  app.add_option("--to", toText, "stop at tick T (or Ts seconds)");
  app.add_option("--level", levelPath, "the level's file, if not where the recording says");
  app.add_flag("--json", json, "the summary as a JSON object");
  app.add_option("--batch", batch,
                 "verify every recording in a folder (*.rec, by name) or listed in a file (one "
                 "path a line): one JSON line each");
  app.add_option("--shard", shardText, "with --batch: this machine's share i/n (default 0/1)");
  app.add_option("--jobs", jobs, "with --batch: sessions replayed at once (default 1)")
      ->check(CLI::Range(1, 256));
  FrameArgs frameArgs;
  addFrameOptions(app, frameArgs, "tick");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet replay", args)) return *exit;
  FrameOptions frameOptions;
  {
    std::vector<RunInput> inputs = {{"the recording", path}};
    if (!levelPath.empty()) inputs.push_back({"the level", levelPath});
    auto frameError = frameOptionsFrom(frameArgs, frameOptions);
    if (!frameError) frameError = checkFrameOptions(frameOptions, inputs);
    if (!frameError && frameOptions.enabled() && !batch.empty())
      frameError = FrameOptionError{kExitUsage, "--frames is for one recording, not --batch"};
    if (frameError) return refuse("ricochet replay", *frameError);
  }

  auto usage = [](const std::string& what) {
    std::fprintf(stderr, "ricochet replay: %s (try ricochet replay --help)\n", what.c_str());
    return kExitUsage;
  };
  if (!batch.empty()) {
    if (!path.empty()) return usage("--batch takes no recording of its own");
    const std::optional<Shard> shard = parseShard(shardText);
    if (!shard) return usage("--shard must be i/n with 0 <= i < n, got '" + shardText + "'");
    BatchOptions options;
    options.shard = *shard;
    options.jobs = jobs;
    options.synctest = synctest;
    try {
      return runBatch(batch, options, stdout);
    } catch (const RecordingError& e) {
      std::fprintf(stderr, "ricochet replay: %s\n", e.what());
      return kExitBadInput;
    }
  }
  if (path.empty()) return usage("a recording is required (or --batch)");
  ReplayOptions options;
  options.verify = verify;
  options.synctest = synctest;
  options.level = levelPath;
  if (!fromText.empty() && !(options.from = parseTick(fromText)))
    return usage("--from must be a tick or seconds (90s), got '" + fromText + "'");
  if (!toText.empty() && !(options.to = parseTick(toText)))
    return usage("--to must be a tick or seconds (90s), got '" + toText + "'");
  if (options.from && options.to && *options.from > *options.to)
    return usage("--from is after --to");

  try {
    const Recording recording = loadRecording(path);
    ReplaySetup setup(recording, options.level);
    if (frameOptions.enabled()) {
      // The level and its tilesets, known once the recording says where it is: before any frame.
      std::vector<RunInput> inputs = levelInputs(setup.level());
      inputs.push_back({"the recording", path});
      if (const auto e = checkFrameOptions(frameOptions, inputs))
        return refuse("ricochet replay", *e);
    }
    // Frames from the first tick played on (the view made from the match as it is there).
    std::unique_ptr<MatchFrames> frames;
    if (frameOptions.enabled()) {
      const std::int64_t last = std::min(options.to.value_or(recording.ticks), recording.ticks);
      const std::int64_t first = std::min(options.from.value_or(0), last);
      options.onTick = [&, last, first](const Match& m) {
        if (!frames)
          frames = std::make_unique<MatchFrames>(frameOptions, "ricochet replay", m.state(),
                                                 static_cast<long>(last - first), path);
        frames->update(m.state());
      };
    }
    const std::int64_t last = std::min(options.to.value_or(recording.ticks), recording.ticks);
    Progress progress("ricochet replay", "tick", last);
    options.onProgress = [&](std::int64_t tick, std::int64_t) {
      progress.update(tick, frames ? frames->framesAdded() : -1);
    };
    const auto start = std::chrono::steady_clock::now();
    const ReplayReport report = replayRecording(setup, recording, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (frames) frames->finish();
    const std::int64_t played = report.end - report.start;
    const double rate = seconds > 0.0 ? static_cast<double>(played) / seconds : 0.0;
    if (json) {
      // The peak resident set, for the benchmarks' memory figure (a long replay's stays flat).
      rusage resources{};
      getrusage(RUSAGE_SELF, &resources);
      std::string line = replayJson(path, report, seconds);
      line.insert(line.size() - 1,
                  ", \"ticks_per_second\": " + std::to_string(static_cast<long long>(rate)) +
                      ", \"peak_rss_kib\": " + std::to_string(resources.ru_maxrss));
      std::printf("%s\n", line.c_str());
    } else {
      std::printf("replay %s ticks %lld-%lld hash %016" PRIx64
                  " verdict %s hashes %d "
                  "keyframes %d ticks_per_second %.0f\n",
                  path.c_str(), static_cast<long long>(report.start),
                  static_cast<long long>(report.end), report.finalHash, verdictName(report.verdict),
                  report.hashesChecked, report.keyframesChecked, rate);
    }
    if (report.verdict != Verdict::ok)
      std::fprintf(stderr, "ricochet replay: %s: %s: %s\n", path.c_str(),
                   verdictName(report.verdict), report.message.c_str());
    return exitCodeOf(report.verdict);
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "ricochet replay: %s\n", e.what());
    return kExitBadInput;
  } catch (const FrameOutputError& e) {
    std::fprintf(stderr, "ricochet replay: %s\n", e.what());
    return kExitBadInput;
  }
}

}  // namespace game
