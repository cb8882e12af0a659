// Playing a recording back: the match made again from its header, stepped with the recorded
// inputs, checked against the recorded hashes, seeking through keyframes, and the synctest.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "game/match/match.h"
#include "game/match/match_snapshot.h"
#include "game/session/recording.h"

namespace game {

// The recording's level (found at the header's path, relative to the recording's folder, or
// given), checked against the recorded content hash, and its configuration: everything needed
// to make its match again, as many times as a replay needs. RecordingError names the file and
// what is wrong (no level there, another level's content, a weapon table that does not read).
class ReplaySetup {
 public:
  // `testHook`: MatchConfig::testHook of the matches it makes (tests of the synctest only).
  ReplaySetup(const Recording& recording, const std::string& levelOverride = "",
              std::function<void(MatchState&)> testHook = {});
  std::unique_ptr<Match> makeMatch();
  const std::string& levelPath() const { return levelPath_; }
  // The level as read (Level::files: the map and its tilesets, which no output may overwrite).
  const Level& level() const { return level_; }
  // The recorded match's configuration (for making matches that differ from it on purpose).
  const MatchConfig& config() const { return config_; }

 private:
  std::string levelPath_;
  Level level_;
  MatchConfig config_;
  std::unique_ptr<Match> first_;
};

enum class Verdict : std::uint8_t {
  ok,        // played to its end; with verification, every hash equal
  damaged,   // the file is truncated or corrupt: played (and verified) up to its last good chunk
  diverged,  // a hash differs from the recording's
  desynced,  // synctest: a tick played again from its saved state gave another state
};
const char* verdictName(Verdict v);

struct ReplayOptions {
  bool verify = false;                   // check every recorded hash and keyframe on the way
  bool synctest = false;                 // save, tick, restore, tick again, compare, every tick
  std::optional<std::int64_t> from, to;  // the ticks to play (from: seek through keyframes)
  std::string level;                     // the level's file, if not where the header says
  // After every tick played from `from` on (and once at `from` itself, before any tick).
  std::function<void(const Match&)> onTick;
  // For tests of the synctest: state this keeps is hidden from snapshots (MatchConfig::testHook).
  std::function<void(MatchState&)> testHook;
  // Every so often: the tick reached and the last tick to play.
  std::function<void(std::int64_t tick, std::int64_t last)> onProgress;
};

struct ReplayReport {
  std::int64_t start = 0;  // the tick the replay began at (a keyframe's, or 0)
  std::int64_t end = 0;    // the tick it reached
  std::uint64_t finalHash = 0;
  int hashesChecked = 0, keyframesChecked = 0;
  Verdict verdict = Verdict::ok;
  std::string message;  // what diverged or what is damaged, in one line
  std::vector<MatchDifference> differences;
};

// Plays the recording as the options say. RecordingError when it cannot be played at all.
ReplayReport replayRecording(const Recording& recording, const ReplayOptions& options);
// The same with its setup made beforehand (a command checks its outputs against the level's
// files first); options.level and options.testHook are then the setup's business.
ReplayReport replayRecording(ReplaySetup& setup, const Recording& recording,
                             const ReplayOptions& options);

}  // namespace game
