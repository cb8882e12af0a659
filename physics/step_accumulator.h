// Ricochet physics: a world run at a fixed step from wall-clock time.
#pragma once

namespace rc {

class World;

// "Fix your timestep": the elapsed time of each frame is banked and spent in whole steps of
// exactly dt, so the simulation (and its hashes) depend only on how many steps were taken, never
// on the frame rate. At most maxSteps are taken per call, so a frame that took too long cannot
// make the next one take longer still; the time over that is dropped (and counted). alpha() is
// the banked part of a step, for drawing bodies between their last two states.
class StepAccumulator {
 public:
  // dt finite and positive, maxSteps at least 1; otherwise InvalidDefinition.
  explicit StepAccumulator(float dt = 1.0f / 60.0f, int maxSteps = 8);
  // Banks elapsed seconds (finite, not negative) and steps the world for every whole step in
  // the bank, up to maxSteps. Returns the number of steps taken.
  int advance(World& world, double elapsedSeconds);
  float dt() const { return dt_; }
  double alpha() const { return banked_ / dt_; }      // in [0, 1) after advance()
  double droppedSeconds() const { return dropped_; }  // discarded by the step cap, in total
  long long steps() const { return steps_; }          // taken, in total

 private:
  float dt_;
  int maxSteps_;
  double banked_ = 0.0, dropped_ = 0.0;
  long long steps_ = 0;
};

}  // namespace rc
