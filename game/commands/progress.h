// Progress of a long run on stderr: nothing for a run that ends within a few seconds, then a
// line every few seconds of wall time ("ricochet play: tick 12000 of 108000 (11%), 4512 ticks/s,
// about 21 s left, 400 frames"). On stderr, so that a summary or JSON on stdout stays clean.
#pragma once

#include <chrono>
#include <string>

namespace game {

class Progress {
 public:
  // `unit` names what is counted ("tick"); `total` is how many the run has.
  Progress(std::string command, std::string unit, long long total, double firstAfterSeconds = 3.0,
           double everySeconds = 5.0);

  // `done` of the total so far; `frames` written so far, shown when not negative.
  void update(long long done, long long frames = -1);

 private:
  using Clock = std::chrono::steady_clock;
  std::string command_, unit_;
  long long total_;
  double every_;
  Clock::time_point start_, next_;
};

}  // namespace game
