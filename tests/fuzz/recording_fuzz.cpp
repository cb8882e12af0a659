// libFuzzer target: the recording reader on arbitrary bytes, and every keyframe it accepts
// restored into a match and played a few ticks, under ASan+UBSan. Nothing may crash, hang or
// allocate beyond the input's size; a bad file is a RecordingError or a damage note. Built with
// the `fuzz` preset (clang), where FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION turns the chunks'
// CRC checks off so that mutated payloads reach their parsers. tests/README.md says how to run it.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "game/level/level_loader.h"
#include "game/match/match.h"
#include "game/match/match_snapshot.h"
#include "game/session/recording.h"

namespace {

// The match keyframes are restored into: the arena, one player and one bot, as the seed corpus
// (tests/fuzz/corpus/recording) was recorded.
// Made once: a restore replaces everything a previous input left in it, or leaves it be.
game::Match& scratchMatch() {
  static game::Match match = [] {
    game::MatchConfig config;
    config.bots = 1;
    return game::Match(
        game::loadLevel(std::string(RICOCHET_SOURCE_DIR) + "/assets/levels/arena.tmj"), config);
  }();
  return match;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const game::Recording r = game::parseRecording(std::span(data, size), "fuzz");
    int restored = 0;
    for (const game::Keyframe& k : r.keyframes) {
      if (restored++ == 2) break;
      try {
        game::Match& match = scratchMatch();
        game::restoreMatch(match.state(), game::keyframeSnapshot(k, "fuzz"));
        for (std::int64_t t = k.tick; t < k.tick + 3; ++t)
          match.tick(r.inputsAt(t));
      } catch (const game::RecordingError&) {
      } catch (const game::MatchSnapshotError&) {
      }
    }
  } catch (const game::RecordingError&) {
  }
  return 0;
}
