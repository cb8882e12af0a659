// Batch replay: many recordings verified, split across machines by shard and across cores by
// threads. A shard is a disjoint, deterministic part of the sorted list (every n-th file from
// the i-th), so n machines given 0/n ... n-1/n cover the list once between them, whatever runs
// them (GNU parallel, a Slurm job array, a Kubernetes Indexed Job). Each recording gets one JSON
// line (file, ticks, final hash, verdict, time), written in the list's order whatever the
// number of threads, so a shard's output is the same bytes run to run (but for the times).
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "game/session/replay.h"

namespace game {

struct Shard {
  int index = 0, count = 1;
};
// "i/n" with 0 <= i < n <= 2^20, or nothing.
std::optional<Shard> parseShard(std::string_view text);

// The recordings a batch names: a folder's *.rec files sorted by name, or a list file's lines
// (blank lines and lines starting with # skipped; relative paths are relative to the list's
// folder), in the list's order. RecordingError if it is neither.
std::vector<std::string> batchFiles(const std::string& folderOrList);
// The shard's share of the files: those at positions i, i + n, i + 2n, ...
std::vector<std::string> shardOf(const std::vector<std::string>& files, Shard shard);

// A list of recordings longer than this is refused (it may be a pipe or a device).
inline constexpr std::size_t kMaxBatchRecordings = std::size_t{1} << 20;

struct BatchOptions {
  Shard shard;
  int jobs = 1;
  bool synctest = false;
};

// A string as a JSON string literal, quotes included, control characters escaped (what every
// command's --json writes a file name or a message with).
std::string jsonString(const std::string& s);

// One recording's result as a JSON object on one line.
std::string replayJson(const std::string& file, const ReplayReport& report, double seconds);

// Verifies the shard's recordings, `jobs` at a time, writing a JSON line for each to `out`.
// Returns the exit code: 3 if any diverged or desynced, else 1 if any could not be replayed,
// else 4 if any is damaged, else 0.
int runBatch(const std::string& folderOrList, const BatchOptions& options, std::FILE* out);

}  // namespace game
