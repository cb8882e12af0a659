#include "game/session/batch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "game/input_file.h"

namespace game {
std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", static_cast<unsigned char>(c));
      out += esc;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::optional<Shard> parseShard(std::string_view text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return std::nullopt;
  auto number = [](std::string_view digits) -> std::optional<int> {
    if (digits.empty() || digits.size() > 7) return std::nullopt;
    int v = 0;
    for (const char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      v = v * 10 + (c - '0');
    }
    return v;
  };
  const std::optional<int> i = number(text.substr(0, slash)), n = number(text.substr(slash + 1));
  if (!i || !n || *n < 1 || *n > (1 << 20) || *i >= *n) return std::nullopt;
  return Shard{*i, *n};
}

std::vector<std::string> batchFiles(const std::string& folderOrList) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(folderOrList, ec);
  std::vector<std::string> files;
  if (ec || !fs::exists(status))
    throw RecordingError(folderOrList + ": no such folder or list of recordings");
  if (fs::is_directory(status)) {
    for (const fs::directory_entry& e : fs::directory_iterator(folderOrList, ec))
      if (e.path().extension() == ".rec") files.push_back(e.path().string());
    if (ec) throw RecordingError(folderOrList + ": cannot list the folder: " + ec.message());
    std::sort(files.begin(), files.end());
    return files;
  }
  std::ifstream in(folderOrList);
  if (!in) throw RecordingError(folderOrList + ": cannot open the list");
  const fs::path base = fs::path(folderOrList).parent_path();
  // Bounded, as the list may be a pipe (`--batch <(find ...)`) or a device: a path is at most
  // 4096 characters, a list at most 2^20 recordings.
  std::string line;
  bool tooLong = false;
  for (std::size_t number = 1; readBoundedLine(in, line, 4096, tooLong); ++number) {
    if (tooLong)
      throw RecordingError(folderOrList + ": line " + std::to_string(number) +
                           " is over 4096 characters: not a list of recordings");
    if (files.size() >= kMaxBatchRecordings)
      throw RecordingError(folderOrList + ": more than " + std::to_string(kMaxBatchRecordings) +
                           " recordings in the list");
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
      line.pop_back();
    if (line.empty() || line.front() == '#') continue;
    const fs::path p(line);
    files.push_back(p.is_absolute() ? line : (base / p).string());
  }
  return files;
}

std::vector<std::string> shardOf(const std::vector<std::string>& files, Shard shard) {
  std::vector<std::string> out;
  for (std::size_t k = static_cast<std::size_t>(shard.index); k < files.size();
       k += static_cast<std::size_t>(shard.count))
    out.push_back(files[k]);
  return out;
}

std::string replayJson(const std::string& file, const ReplayReport& report, double seconds) {
  char text[256];
  std::snprintf(text, sizeof text,
                ", \"from\": %lld, \"ticks\": %lld, \"hash\": \"%016" PRIx64
                "\", \"verdict\": \"%s\", \"hashes_checked\": %d, \"seconds\": %.3f",
                static_cast<long long>(report.start), static_cast<long long>(report.end),
                report.finalHash, verdictName(report.verdict), report.hashesChecked, seconds);
  return "{\"file\": " + jsonString(file) + text + ", \"message\": " + jsonString(report.message) +
         "}";
}

int runBatch(const std::string& folderOrList, const BatchOptions& options, std::FILE* out) {
  const std::vector<std::string> files = shardOf(batchFiles(folderOrList), options.shard);
  struct Result {
    std::string line;
    int rank = 0;  // 0 ok, 1 damaged, 2 error, 3 diverged
    bool done = false;
  };
  std::vector<Result> results(files.size());
  std::mutex mutex;
  std::condition_variable finished;
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < files.size(); k = next++) {
      Result r;
      const auto start = std::chrono::steady_clock::now();
      auto seconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      };
      try {
        const Recording recording = loadRecording(files[k]);
        ReplayOptions replay;
        replay.verify = true;
        replay.synctest = options.synctest;
        const ReplayReport report = replayRecording(recording, replay);
        r.line = replayJson(files[k], report, seconds());
        r.rank = report.verdict == Verdict::ok ? 0 : report.verdict == Verdict::damaged ? 1 : 3;
      } catch (const std::exception& e) {
        // A recording that cannot be replayed at all is one line too; the batch goes on.
        char text[64];
        std::snprintf(text, sizeof text, ", \"verdict\": \"error\", \"seconds\": %.3f", seconds());
        r.line = "{\"file\": " + jsonString(files[k]) + text +
                 ", \"message\": " + jsonString(e.what()) + "}";
        r.rank = 2;
      }
      const std::lock_guard lock(mutex);
      r.done = true;
      results[k] = std::move(r);
      finished.notify_all();
    }
  };
  std::vector<std::thread> threads;
  const auto jobs = static_cast<std::size_t>(std::max(1, options.jobs));
  for (std::size_t t = 1; t < std::min(jobs, files.size()); ++t)
    threads.emplace_back(work);
  // This thread works too, and writes each line as soon as every line before it is done.
  std::thread writer([&] {
    for (std::size_t k = 0; k < files.size(); ++k) {
      std::unique_lock lock(mutex);
      finished.wait(lock, [&] { return results[k].done; });
      std::fprintf(out, "%s\n", results[k].line.c_str());
      std::fflush(out);
    }
  });
  work();
  for (std::thread& t : threads)
    t.join();
  writer.join();
  int worst = 0;
  for (const Result& r : results)
    worst = std::max(worst, r.rank);
  static constexpr int kExit[] = {0, 4, 1, 3};
  return kExit[worst];
}

}  // namespace game
