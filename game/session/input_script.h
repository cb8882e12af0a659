// Scripted input: the players' controls read from text instead of chosen by the autopilot, for
// recording a match played by a script, a test, or a live source on a pipe (`play --input -`).
//
// One line per change, each player's controls holding until its next line:
//
//   # tick player move_x move_y aim_degrees buttons weapon
//   0     0      1      0      90          -       0
//   120   0      0.5    -0.5   180         ft      0
//
// move_x, move_y in [-1, 1] (a longer move is shortened to 1), aim in degrees counter-clockwise
// from +x, buttons a word of f (fire), t (throw), r (reload) or "-" for none, weapon an index in
// the weapon table. Ticks never go down. A player with no line yet stands still. Lines are read
// only as far as the tick being played needs (to play tick t the reader must see a line after t,
// or the end), so a script on a pipe paces the match.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "game/match/input.h"

namespace game {

class InputScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputScript {
 public:
  // `in` must outlive the script; `name` names it in errors; `players` is how many it drives.
  InputScript(std::istream& in, std::string name, int players);
  // The players' inputs for `tick` (called with 0, 1, 2, ...). InputScriptError names the line
  // that is wrong ("script.txt:12: aim is not a number: 'x'").
  const std::vector<PlayerInput>& inputsFor(std::int64_t tick);

 private:
  struct Line {
    std::int64_t tick = 0;
    int player = 0;
    PlayerInput input;
  };
  bool readLine();  // the next line into pending_, false at the end
  std::istream& in_;
  std::string name_;
  std::int64_t lineNumber_ = 0;
  std::int64_t lastTick_ = 0;
  std::optional<Line> pending_;
  bool ended_ = false;
  std::vector<PlayerInput> current_;
};

}  // namespace game
