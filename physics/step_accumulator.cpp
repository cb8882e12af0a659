#include "physics/step_accumulator.h"

#include <cmath>

#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

StepAccumulator::StepAccumulator(float dt, int maxSteps) : dt_(dt), maxSteps_(maxSteps) {
  if (!(std::isfinite(dt) && dt > 0.0f))
    throw InvalidDefinition("StepAccumulator: dt must be finite and positive, got " +
                            formatNumber(dt));
  if (maxSteps < 1)
    throw InvalidDefinition("StepAccumulator: maxSteps must be at least 1, got " +
                            std::to_string(maxSteps));
}

int StepAccumulator::advance(World& world, double elapsedSeconds) {
  if (!(std::isfinite(elapsedSeconds) && elapsedSeconds >= 0.0))
    throw InvalidDefinition("StepAccumulator: elapsed time must be finite and not negative, got " +
                            formatNumber(elapsedSeconds));
  banked_ += elapsedSeconds;
  int taken = 0;
  while (banked_ >= dt_ && taken < maxSteps_) {
    world.step(dt_);
    banked_ -= dt_;
    ++taken;
  }
  steps_ += taken;
  if (banked_ >= dt_) {
    // Over the cap: keep the part of a step already banked, drop the whole steps.
    const double keep = std::fmod(banked_, static_cast<double>(dt_));
    dropped_ += banked_ - keep;
    banked_ = keep;
  }
  return taken;
}

}  // namespace rc
