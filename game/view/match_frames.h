// The frames of a match run (ricochet play, and replay to come): a MatchView fed every tick and
// a FrameOutput that renders and writes the due ones. Built with or without the renderer (without
// it, checkFrameOptions refuses --frames, so there is never anything to draw).
#pragma once

#include <memory>
#include <string>

#include "game/match/match.h"
#include "game/view/frame_output.h"

namespace game {

class MatchFrames {
 public:
  // Makes the output (FrameOutputError when it cannot be written) and, with frames asked for, the
  // view of `s` as it starts; `ticks` is the run's length; `caption` goes in the HUD.
  MatchFrames(const FrameOptions& options, const std::string& command, const MatchState& s,
              long ticks, const std::string& caption);
  ~MatchFrames();
  MatchFrames(const MatchFrames&) = delete;
  MatchFrames& operator=(const MatchFrames&) = delete;

  // Before the first tick and after every tick: the view keeps what it needs for its trails and
  // the frame is drawn if s.tick is due.
  void update(const MatchState& s);
  long long framesAdded() const;
  // FrameOutput::finish.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace game
