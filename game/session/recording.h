// A recorded session: what its chunks hold (game/session/FORMAT.md), written as a match is
// played (Recorder) and read back whole, every payload checked (loadRecording).
//
// A recording holds the inputs, not the states: the header says how to make the match again
// (level, weapons, seed, players, bots), the input chunks give the players' input records tick
// by tick, and state hashes and keyframes let a replay check itself and seek.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "game/match/input.h"
#include "game/match/match.h"
#include "game/session/recording_file.h"

namespace game {

// Bumped when a change to the engine or the game moves the hashes of recorded matches on
// purpose (and the bundled sessions are recorded again): a replay of an older recording is
// refused with a clear message instead of failing at its first hash.
inline constexpr std::uint32_t kSimulationVersion = 10;

// The program's version, written into every recording (informative: kSimulationVersion decides).
inline constexpr const char* kProgramVersion = "ricochet 0.1.0";

// Limits on what a header may claim, so a hostile one cannot ask for a giant allocation.
inline constexpr int kMaxRecordedPlayers = 16;
inline constexpr int kMaxRecordedBots = 256;
inline constexpr std::size_t kMaxHeaderText = 1u << 20;  // a weapon table, a path

struct RecordingHeader {
  std::string program = kProgramVersion;
  std::uint32_t simulation = kSimulationVersion;
  // The level's path relative to the recording's folder (absolute if it has no relative path),
  // and the hash of its content (Match::levelHash): a replay finds the level there and refuses
  // one whose content differs.
  std::string level;
  std::uint64_t levelHash = 0;
  // The weapon table's text and where it came from: a recording carries its weapons, so editing
  // assets/weapons.json does not change what an old recording replays.
  std::string weaponsSource;
  std::string weaponsText;
  std::uint64_t seed = 1;
  int players = 1;  // input records per tick
  int bots = 0;     // bots fielded
  int actors = 0;   // players + bots: checked against the match made again
  int ticksPerSecond = kTicksPerSecond;
  int hashEvery = 60;       // ticks between state hashes
  int keyframeEvery = 300;  // ticks between keyframes
  int inputsPerChunk = 60;  // ticks of inputs in one INPT chunk (its loss if killed)
  // The world's settings, for `info` (the level's content hash already covers them).
  int substeps = 0;
  std::string integrator;
};

struct RecordedHash {
  std::int64_t tick = 0;  // the match's tick after the ticks played (1 after the first)
  std::uint64_t hash = 0;
};

struct Keyframe {
  std::int64_t tick = 0;
  std::uint64_t hash = 0;              // Match::hash() of the state it holds
  std::vector<std::uint8_t> snapshot;  // saveMatch(), zlib-compressed
  std::uint32_t snapshotBytes = 0;     // uncompressed
};

struct Recording {
  std::string path;
  std::uint64_t bytes = 0;
  std::size_t chunks = 0;  // whole, checked chunks read
  RecordingHeader header;
  std::int64_t ticks = 0;            // ticks whose inputs the file holds
  std::vector<PlayerInput> inputs;   // ticks * players records, tick after tick
  std::vector<RecordedHash> hashes;  // in tick order
  std::vector<Keyframe> keyframes;   // in tick order
  bool finished = false;             // an END chunk closed it
  std::optional<std::uint64_t> finalHash;
  // Where reading stopped before the end of the file, and why (a truncated or corrupt chunk, or
  // one whose payload makes no sense): everything before it is usable.
  std::optional<std::string> damage;

  std::span<const PlayerInput> inputsAt(std::int64_t tick) const;
  const Keyframe* keyframeAtOrBefore(std::int64_t tick) const;
};

// Reads and checks a whole recording. RecordingError (one line naming the file) when it cannot
// be used at all: missing, a directory, not a recording, another format or simulation version,
// a header that is damaged or claims what no recording holds. A file damaged further on is
// returned with `damage` set, up to its last good chunk.
Recording loadRecording(const std::string& path);
Recording parseRecording(std::span<const std::uint8_t> bytes, const std::string& name);

// The keyframe's match snapshot, uncompressed (RecordingError if it does not inflate to its size).
std::vector<std::uint8_t> keyframeSnapshot(const Keyframe& keyframe, const std::string& name);

// Writes a recording as a match is played: the header at once, then after every tick the
// players' inputs (an INPT chunk every inputsPerChunk ticks), a HASH every hashEvery ticks and a
// KEYF every keyframeEvery ticks, each flushed as it is written; finish() writes what is left
// and the END chunk. A recorder killed at any moment leaves a file that plays up to its last
// whole chunk.
class Recorder {
 public:
  Recorder(const std::string& path, const RecordingHeader& header);
  // After Match::tick(): the players' inputs of the tick just played, and the hash and keyframe
  // when one is due.
  void afterTick(const Match& match);
  void finish(const Match& match);
  const std::string& path() const { return writer_.path(); }

 private:
  void writeInputs();
  RecordingWriter writer_;
  RecordingHeader header_;
  std::int64_t firstBuffered_ = 0;  // the tick of the first buffered record
  std::int64_t buffered_ = 0;       // ticks buffered
  std::vector<std::uint8_t> inputs_;
};

// The header of a match about to be recorded: its level (path relative to the recording's
// folder), configuration, weapons and world settings.
RecordingHeader headerFor(const Match& match, const std::string& levelPath,
                          const std::string& recordingPath);

}  // namespace game
