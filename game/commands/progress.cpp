#include "game/commands/progress.h"

#include <cstdio>
#include <utility>

namespace game {

Progress::Progress(std::string command, std::string unit, long long total, double firstAfterSeconds,
                   double everySeconds)
    : command_(std::move(command)),
      unit_(std::move(unit)),
      total_(total),
      every_(everySeconds),
      start_(Clock::now()),
      next_(start_ + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(firstAfterSeconds))) {}

void Progress::update(long long done, long long frames) {
  const Clock::time_point now = Clock::now();
  if (now < next_ || done >= total_) return;
  next_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(every_));
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double left = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  char extra[48] = "";
  if (frames >= 0) std::snprintf(extra, sizeof extra, ", %lld frames", frames);
  std::fprintf(stderr, "%s: %s %lld of %lld (%.0f%%), %.0f %ss/s, about %.0f s left%s\n",
               command_.c_str(), unit_.c_str(), done, total_,
               total_ > 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 0.0,
               rate, unit_.c_str(), left, extra);
}

}  // namespace game
