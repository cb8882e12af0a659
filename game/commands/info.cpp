// `ricochet info FILE [--json]`: what a recording holds and whether it is whole, without playing
// it: its header, duration, players, chunks, hashes, keyframes, and where it is damaged.
#include <cinttypes>
#include <cstdio>
#include <string>

#include "game/cli.h"
#include "game/commands/command_line.h"
#include "game/quote.h"
#include "game/session/batch.h"
#include "game/session/recording.h"
#include "game/weapons/weapon_table.h"

namespace game {

int runInfo(std::span<const std::string_view> args) {
  CLI::App app{
      "Says what a recorded session holds and whether it is whole, without playing it.\n"
      "Exit codes: 0 a whole recording, 4 a damaged one (it plays up to its last good chunk),\n"
      "1 not a recording that can be read, 2 bad command line.",
      "ricochet info"};
  std::string path;
  bool json = false;
  app.add_option("recording", path, "the recording (.rec)")->required();
  app.add_flag("--json", json, "as a JSON object");
  if (const std::optional<int> exit = parseCommandLine(app, "ricochet info", args)) return *exit;

  Recording r;
  try {
    r = loadRecording(path);
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "ricochet info: %s\n", e.what());
    return kExitBadInput;
  }
  const RecordingHeader& h = r.header;
  const bool whole = !r.damage && r.finished;
  const std::string integrity =
      whole ? "whole"
            : (r.damage ? "damaged: " + *r.damage
                        : std::string("unfinished: it ends without its END chunk")) +
                  "; it plays to tick " + std::to_string(r.ticks);
  const double seconds = static_cast<double>(r.ticks) / h.ticksPerSecond;
  char finalHash[17] = "";
  if (r.finalHash) std::snprintf(finalHash, sizeof finalHash, "%016" PRIx64, *r.finalHash);
  if (json) {
    std::printf("{\"file\": %s, \"bytes\": %" PRIu64
                ", \"chunks\": %zu, \"program\": %s, "
                "\"simulation\": %u, \"level\": %s, \"level_hash\": \"%016" PRIx64
                "\", "
                "\"weapons\": %s, \"seed\": %" PRIu64
                ", \"players\": %d, \"bots\": %d, "
                "\"ticks\": %lld, \"seconds\": %.3f, \"hashes\": %zu, \"keyframes\": %zu, "
                "\"finished\": %s, \"final_hash\": %s, \"whole\": %s, \"integrity\": %s}\n",
                jsonString(path).c_str(), r.bytes, r.chunks, jsonString(h.program).c_str(),
                h.simulation, jsonString(h.level).c_str(), h.levelHash,
                jsonString(h.weaponsSource).c_str(), h.seed, h.players, h.bots,
                static_cast<long long>(r.ticks), seconds, r.hashes.size(), r.keyframes.size(),
                r.finished ? "true" : "false",
                r.finalHash ? ("\"" + std::string(finalHash) + "\"").c_str() : "null",
                whole ? "true" : "false", jsonString(integrity).c_str());
  } else {
    std::printf("recording %s: %" PRIu64 " bytes, %zu chunks\n", path.c_str(), r.bytes, r.chunks);
    // The header's texts quoted and cut (game/quote.h): a forged header's level may be a
    // megabyte of anything, newlines and terminal escapes included.
    std::printf("recorded by %s (simulation %u)\n", quoteName(h.program).c_str(), h.simulation);
    std::printf("level %s (content hash %016" PRIx64 ")\n", quoteName(h.level).c_str(),
                h.levelHash);
    std::printf("weapons from %s, seed %" PRIu64 ", %d players, %d bots\n",
                quoteName(h.weaponsSource).c_str(), h.seed, h.players, h.bots);
    std::printf("world %d substeps, %s\n", h.substeps, quoteName(h.integrator).c_str());
    std::printf(
        "ticks %lld (%.1f s at %d per second), %zu hashes (every %d), %zu keyframes "
        "(every %d)\n",
        static_cast<long long>(r.ticks), seconds, h.ticksPerSecond, r.hashes.size(), h.hashEvery,
        r.keyframes.size(), h.keyframeEvery);
    std::printf("integrity %s%s%s\n", integrity.c_str(), r.finalHash ? ", final hash " : "",
                finalHash);
  }
  return whole ? kExitOk : kExitDamaged;
}

}  // namespace game
