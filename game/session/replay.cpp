#include "game/session/replay.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <filesystem>

#include "game/level/level_error.h"
#include "game/level/level_loader.h"
#include "game/quote.h"
#include "game/weapons/weapon_table.h"

namespace game {
namespace {

std::string hex(std::uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, v);
  return text;
}

std::string describe(const std::vector<MatchDifference>& differences) {
  if (differences.empty()) return "nothing differs";
  const MatchDifference& d = differences.front();
  std::string out = d.what + ": recorded " + d.recorded + ", replayed " + d.replayed;
  if (differences.size() > 1)
    out += " (and " + std::to_string(differences.size() - 1) +
           (differences.size() >= 16 ? "+" : "") + " more)";
  return out;
}

}  // namespace

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::ok:
      return "ok";
    case Verdict::damaged:
      return "damaged";
    case Verdict::diverged:
      return "diverged";
    case Verdict::desynced:
      return "desynced";
  }
  return "?";
}

ReplaySetup::ReplaySetup(const Recording& recording, const std::string& levelOverride,
                         std::function<void(MatchState&)> testHook) {
  namespace fs = std::filesystem;
  const RecordingHeader& h = recording.header;
  if (!levelOverride.empty()) {
    levelPath_ = levelOverride;
  } else {
    const fs::path recorded(h.level);
    levelPath_ =
        (recorded.is_absolute() ? recorded : fs::path(recording.path).parent_path() / recorded)
            .lexically_normal()
            .string();
    std::error_code ec;
    // The header's path is quoted and cut (a forged one may be a megabyte of anything); where
    // it was looked for is said when that shows nothing more of it.
    if (!fs::exists(levelPath_, ec))
      throw RecordingError(recording.path + ": its level " + quoteName(h.level) + " is not " +
                           (isPlainText(h.level) ? "at " + levelPath_ : "where it says") +
                           " (give it with --level)");
  }
  try {
    level_ = loadLevel(levelPath_);
  } catch (const LevelError& e) {
    throw RecordingError(recording.path + ": its level: " + e.what());
  }
  try {
    config_.weapons = parseWeaponTable(h.weaponsText, recording.path + " (its weapon table, from " +
                                                          quoteName(h.weaponsSource) + ")");
  } catch (const WeaponTableError& e) {
    throw RecordingError(e.what());
  }
  config_.players = h.players;
  config_.bots = h.bots;
  config_.seed = h.seed;
  config_.testHook = std::move(testHook);
  first_ = makeMatch();
  const MatchState& s = first_->state();
  if (s.levelHash != h.levelHash)
    throw RecordingError(recording.path + ": the level at " + levelPath_ +
                         " is not the one recorded (content hash " + hex(s.levelHash) +
                         ", recorded " + hex(h.levelHash) + ")");
  if (static_cast<int>(s.actors.size()) != h.actors)
    throw RecordingError(recording.path + ": the match made again has " +
                         std::to_string(s.actors.size()) + " actors, the recording " +
                         std::to_string(h.actors));
}

std::unique_ptr<Match> ReplaySetup::makeMatch() {
  // The match the constructor made to check the level, handed out once: a replay makes one match
  // and needs it at once, and a match takes a few milliseconds to build.
  if (first_) return std::move(first_);
  try {
    return std::make_unique<Match>(level_, config_);
  } catch (const std::exception& e) {
    throw RecordingError(levelPath_ + ": " + e.what());
  }
}

ReplayReport replayRecording(const Recording& rec, const ReplayOptions& options) {
  ReplaySetup setup(rec, options.level, options.testHook);
  return replayRecording(setup, rec, options);
}

ReplayReport replayRecording(ReplaySetup& setup, const Recording& rec,
                             const ReplayOptions& options) {
  std::unique_ptr<Match> match = setup.makeMatch();
  ReplayReport report;
  const std::int64_t last = std::clamp<std::int64_t>(options.to.value_or(rec.ticks), 0, rec.ticks);
  const std::int64_t from = std::clamp<std::int64_t>(options.from.value_or(0), 0, last);

  // Seek: the latest keyframe at or before `from`, checked against the hash it was saved with.
  if (from > 0) {
    if (const Keyframe* k = rec.keyframeAtOrBefore(from)) {
      try {
        restoreMatch(match->state(), keyframeSnapshot(*k, rec.path));
      } catch (const MatchSnapshotError& e) {
        throw RecordingError(rec.path + ": the keyframe of tick " + std::to_string(k->tick) + ": " +
                             e.what());
      }
      if (match->hash() != k->hash)
        throw RecordingError(rec.path + ": the keyframe of tick " + std::to_string(k->tick) +
                             " does not restore to the state it was saved from");
    }
  }
  report.start = match->state().tick;

  auto nextHash =
      std::upper_bound(rec.hashes.begin(), rec.hashes.end(), report.start,
                       [](std::int64_t t, const RecordedHash& h) { return t < h.tick; });
  auto nextKeyframe =
      std::upper_bound(rec.keyframes.begin(), rec.keyframes.end(), report.start,
                       [](std::int64_t t, const Keyframe& k) { return t < k.tick; });
  std::int64_t lastGood = report.start;  // the last tick whose hash was seen equal

  // A hash differs at `tick`: name the window, then what differs at the first keyframe at or
  // after it (the recording's state there against ours, played on to it).
  auto diverged = [&](std::int64_t tick, std::uint64_t ours, std::uint64_t theirs) {
    report.verdict = Verdict::diverged;
    report.message = "tick " + std::to_string(tick) + ": hash " + hex(ours) + ", recorded " +
                     hex(theirs) + " (it diverged in ticks " + std::to_string(lastGood + 1) +
                     " to " + std::to_string(tick) + ")";
    const auto k = std::lower_bound(rec.keyframes.begin(), rec.keyframes.end(), tick,
                                    [](const Keyframe& kf, std::int64_t t) { return kf.tick < t; });
    if (k == rec.keyframes.end()) {
      report.message += "; no keyframe after it names what differs";
      return;
    }
    while (match->state().tick < k->tick)
      match->tick(rec.inputsAt(match->state().tick));
    const std::unique_ptr<Match> recorded = setup.makeMatch();
    restoreMatch(recorded->state(), keyframeSnapshot(*k, rec.path));
    report.differences = compareMatches(recorded->state(), match->state());
    report.message += "; at the keyframe of tick " + std::to_string(k->tick) + ": " +
                      describe(report.differences);
  };

  if (options.onTick && from == match->state().tick) options.onTick(*match);
  while (match->state().tick < last) {
    const std::int64_t tick = match->state().tick;
    const std::span<const PlayerInput> inputs = rec.inputsAt(tick);
    if (options.synctest && tick >= from) {
      const MatchSnapshot before = saveMatch(match->state());
      match->tick(inputs);
      const MatchSnapshot first = saveMatch(match->state());
      restoreMatch(match->state(), before);
      match->tick(inputs);
      if (fnv1a(first) != match->hash()) {
        const std::unique_ptr<Match> firstRun = setup.makeMatch();
        restoreMatch(firstRun->state(), first);
        report.verdict = Verdict::desynced;
        report.differences = compareMatches(firstRun->state(), match->state());
        report.message = "tick " + std::to_string(tick + 1) +
                         ": played again from the state saved before it, it ends elsewhere: " +
                         describe(report.differences);
        // (compareMatches calls the first run "recorded": here it is the first of two runs.)
        break;
      }
    } else {
      match->tick(inputs);
    }
    const std::int64_t now = match->state().tick;
    if (options.verify) {
      while (nextHash != rec.hashes.end() && nextHash->tick < now)
        ++nextHash;
      if (nextHash != rec.hashes.end() && nextHash->tick == now) {
        const std::uint64_t ours = match->hash();
        ++report.hashesChecked;
        if (ours != nextHash->hash) {
          diverged(now, ours, nextHash->hash);
          break;
        }
        lastGood = now;
      }
      while (nextKeyframe != rec.keyframes.end() && nextKeyframe->tick < now)
        ++nextKeyframe;
      if (nextKeyframe != rec.keyframes.end() && nextKeyframe->tick == now) {
        const std::uint64_t ours = match->hash();
        ++report.keyframesChecked;
        if (ours != nextKeyframe->hash) {
          diverged(now, ours, nextKeyframe->hash);
          break;
        }
      }
    }
    if (now >= from && options.onTick) options.onTick(*match);
    if (options.onProgress && now % 600 == 0) options.onProgress(now, last);
  }
  report.end = match->state().tick;
  report.finalHash = match->hash();
  if (report.verdict != Verdict::ok) return report;
  if (options.verify && rec.finished && report.end == rec.ticks && rec.finalHash &&
      report.finalHash != *rec.finalHash) {
    diverged(report.end, report.finalHash, *rec.finalHash);
    return report;
  }
  if (rec.damage || !rec.finished) {
    report.verdict = Verdict::damaged;
    report.message = (rec.damage ? *rec.damage
                                 : "it ends without its END chunk (the recorder "
                                   "stopped before finishing)") +
                     "; the file plays to tick " + std::to_string(rec.ticks);
  }
  return report;
}

}  // namespace game
