// The world: construction, the step as its list of phases, and what reads the whole state.
#include "physics/world.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "physics/world_state.h"

namespace rc {
namespace {

using Clock = std::chrono::steady_clock;

// The phases' clock (WorldDef::enableProfile): each lap() is the time since the last one, in
// milliseconds; off, nothing is read.
class PhaseClock {
 public:
  explicit PhaseClock(bool on) : on_(on) {
    if (on_) start_ = last_ = Clock::now();
  }
  void lap(double& into) {
    if (!on_) return;
    const auto now = Clock::now();
    into = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
  }
  void total(double& into) const {
    if (on_) into = std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  bool on_;
  Clock::time_point start_, last_;
};

}  // namespace

std::string formatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void failDefinition(const char* what, const char* field, const std::string& why) {
  throw InvalidDefinition(std::string(what) + ": " + field + " " + why);
}
void requireFinite(const char* what, const char* field, float v) {
  if (!std::isfinite(v)) failDefinition(what, field, "is not finite (" + formatNumber(v) + ")");
}
void requireFinite(const char* what, const char* field, Vec2 v) {
  if (!isFinite(v))
    failDefinition(what, field,
                   "is not finite (" + formatNumber(v.x) + ", " + formatNumber(v.y) + ")");
}
void requireNonNegative(const char* what, const char* field, float v) {
  requireFinite(what, field, v);
  if (v < 0.0f) failDefinition(what, field, "is " + formatNumber(v) + " (must be >= 0)");
}

WorldState::WorldState(const WorldDef& def, int broadphaseDepth)
    : def_(def), broadphase_(def.bounds, broadphaseDepth) {
  profile_.lanes = def.maxSolverLanes >= 8 ? ContactSolver::widestLanes() : 4;
}

World::World(const WorldDef& def) {
  requireFinite("world", "gravity", def.gravity);
  if (def.substeps < 1 || def.substeps > 64)
    failDefinition("world", "substeps",
                   "is " + std::to_string(def.substeps) + " (must be 1 to 64)");
  requireNonNegative("world", "restitutionThreshold", def.restitutionThreshold);
  requireNonNegative("world", "contactHertz", def.contactHertz);
  requireNonNegative("world", "contactDampingRatio", def.contactDampingRatio);
  requireNonNegative("world", "maxPushoutSpeed", def.maxPushoutSpeed);
  requireNonNegative("world", "contactRecycleDistance", def.contactRecycleDistance);
  requireNonNegative("world", "quarantineSpeed", def.quarantineSpeed);
  if (def.stackSolveDepth < 0 || def.stackSolveDepth > kMaxStackSolveDepth)
    failDefinition("world", "stackSolveDepth",
                   "is " + std::to_string(def.stackSolveDepth) + " (must be 0 to " +
                       std::to_string(kMaxStackSolveDepth) + ")");
  if (def.maxSolverLanes != 4 && def.maxSolverLanes != 8)
    failDefinition("world", "maxSolverLanes",
                   "is " + std::to_string(def.maxSolverLanes) + " (must be 4 or 8)");
  s_ = std::make_unique<WorldState>(def);
}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

// ------------------------------------------------------------------------------------ step

void World::step(float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt))
    throw std::invalid_argument("world: step dt must be finite and > 0, got " + formatNumber(dt));
  WorldState& s = *s_;
  Profile& profile = s.profile_;
  PhaseClock clock(s.def_.enableProfile);
  s.beginEvents();
  s.stepping_ = true;
  // (Reset however the step ends: a force field may throw.)
  struct Stepping {
    bool& flag;
    ~Stepping() { flag = false; }
  } stepping{s.stepping_};
  // A velocity the game gave (an impulse on top of a fast body) may already be unusable.
  if (s.velocitiesSet_) s.quarantineUnusable(QuarantineCause::motion, false);
  s.velocitiesSet_ = false;
  // Bodies new or changed since the last step: proxies stretched along this step's motion.
  std::sort(s.pendingRefit_.begin(), s.pendingRefit_.end());
  s.pendingRefit_.erase(std::unique(s.pendingRefit_.begin(), s.pendingRefit_.end()),
                        s.pendingRefit_.end());
  for (std::int32_t index : s.pendingRefit_) {
    WorldState::Body& b = s.bodies_[static_cast<std::size_t>(index)];
    if (b.alive && b.slot >= 0)
      s.refitBody(b, dt * s.velocityOf(b),
                  b.round ? 0.0f : dt * s.v_[3 * static_cast<std::size_t>(b.slot) + 2]);
  }
  s.pendingRefit_.clear();

  s.updatePairs();
  clock.lap(profile.updatePairs);
  s.narrowphase(dt);
  clock.lap(profile.narrowphase);
  s.solve(dt);
  clock.lap(profile.solve);
  if (s.def_.continuous) s.continuous();
  // What the contacts made of the bodies: one pass, and nothing more unless one is unusable.
  if (s.awakeCount_ > 0) s.quarantineUnusable(QuarantineCause::contact, true);
  clock.lap(profile.continuous);
  s.refit(dt);
  clock.lap(profile.refit);
  s.updateSensors();
  clock.lap(profile.sensors);
  s.updateSleep(dt);
  clock.lap(profile.sleep);
  s.stepping_ = false;
  s.time_ += dt;
  s.endStep();
  clock.total(profile.total);
  if (s.staleFieldId_) {
    const BodyId stale = *s.staleFieldId_;
    s.staleFieldId_.reset();
    throw std::invalid_argument("world: a force field named body " + std::to_string(stale.index) +
                                " (generation " + std::to_string(stale.generation) +
                                "), which does not exist; the step was completed without it");
  }
}

// The published events start as what happened between the steps (ends made by destroying or
// disabling), then take the step's own.
void WorldState::beginEvents() {
  events_.begin.clear();
  events_.hit.clear();
  events_.end.swap(pendingEvents_.end);
  pendingEvents_.end.clear();
  sensorEvents_.begin.clear();
  sensorEvents_.end.swap(pendingSensorEvents_.end);
  pendingSensorEvents_.end.clear();
  quarantineEvents_.clear();
}

// What the step found to act on once it is whole: bodies to quarantine, sleeping bodies a force
// field pushed.
void WorldState::endStep() {
  for (const Quarantined& bad : quarantine_) {
    Body& b = bodies_[static_cast<std::size_t>(bad.body)];
    if (!b.alive || !b.enabled) continue;  // named twice
    quarantineEvents_.push_back({bodyId(bad.body), b.userData, bad.cause});
    if (b.slot >= 0) {
      // Where it began the step, at rest.
      const auto i = 3 * static_cast<std::size_t>(b.slot);
      for (std::size_t k = 0; k < 3; ++k) {
        q_[i + k] = bad.start[k];
        v_[i + k] = 0.0f;
      }
      b.angle = static_cast<float>(bad.start[2]);
      b.xf.q = Rot::fromAngle(b.angle);
      const std::array<double, 2> origin = preciseOrigin(b);
      b.xf.p = {static_cast<float>(origin[0]), static_cast<float>(origin[1])};
    }
    disable(b);
  }
  quarantine_.clear();
  for (std::int32_t index : fieldWakes_) {
    Body& b = bodies_[static_cast<std::size_t>(index)];
    if (b.alive && b.enabled) wakeBody(b);
  }
  fieldWakes_.clear();
}

// Transforms, AABBs and proxies from the new positions, each fat AABB stretched along the
// body's next step; forces are used up.
void WorldState::refit(float dt) {
  reserveTurns(static_cast<std::size_t>(awakeCount_));
  for (std::size_t s = 0; s < static_cast<std::size_t>(awakeCount_); ++s) {
    Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const auto angle = static_cast<float>(q_[3 * s + 2]);
    if (angle != b.angle) {  // no trigonometry for bodies that did not turn
      b.angle = angle;
      turnAngles_.push_back(angle);
      turnOwners_.push_back(slotBody_[s]);
    }
  }
  applyTurns([&](std::int32_t body, Rot q) { bodies_[static_cast<std::size_t>(body)].xf.q = q; });
  for (std::size_t s = 0; s < static_cast<std::size_t>(awakeCount_); ++s) {
    Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const std::array<double, 2> origin = preciseOrigin(b);
    b.xf.p = {static_cast<float>(origin[0]), static_cast<float>(origin[1])};
    b.force = {};
    b.torque = 0.0f;
    refitBody(b, dt * Vec2{v_[i], v_[i + 1]}, dt * v_[i + 2]);  // where it goes next step
  }
}

// ------------------------------------------------------------------------- the whole state

double World::energy() const {
  const WorldState& s = *s_;
  double e = 0;
  for (const WorldState::Body& b : s.bodies_) {
    if (!b.alive || b.type != BodyType::dynamicBody) continue;
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const double vx = s.v_[i], vy = s.v_[i + 1], w = s.v_[i + 2];
    e += 0.5 * b.mass * (vx * vx + vy * vy) + 0.5 * b.inertia * w * w;
    e -= b.mass * b.gravityScale *
         (static_cast<double>(s.def_.gravity.x) * s.q_[i] +
          static_cast<double>(s.def_.gravity.y) * s.q_[i + 1]);
  }
  return e;
}

int World::awakeBodyCount() const {
  return s_->awakeCount_;
}
int World::contactCount() const {
  return static_cast<int>(s_->contacts_.size());
}
const ContactEvents& World::contactEvents() const {
  return s_->events_;
}
const SensorEvents& World::sensorEvents() const {
  return s_->sensorEvents_;
}
const std::vector<QuarantineEvent>& World::quarantineEvents() const {
  return s_->quarantineEvents_;
}

const char* quarantineCauseName(QuarantineCause cause) {
  switch (cause) {
    case QuarantineCause::forceField:
      return "force field";
    case QuarantineCause::motion:
      return "motion";
    case QuarantineCause::contact:
      return "contact";
  }
  return "unknown";
}
void World::addForceField(ForceField field) {
  s_->fields_.push_back(std::move(field));
}
const Quadtree& World::broadphase() const {
  return s_->broadphase_;
}
void World::setStepping(int substeps, Integrator integrator) {
  if (substeps < 1 || substeps > 64)
    failDefinition("world", "substeps", "is " + std::to_string(substeps) + " (must be 1 to 64)");
  if (std::find(std::begin(kIntegrators), std::end(kIntegrators), integrator) ==
      std::end(kIntegrators))
    failDefinition("world", "integrator", "is not one of the four");
  WorldState& s = *s_;
  const float scale = static_cast<float>(s.def_.substeps) / static_cast<float>(substeps);
  for (WorldState::Contact& c : s.contacts_)
    for (int k = 0; k < 2; ++k) {
      c.normalImpulse[k] *= scale;
      c.tangentImpulse[k] *= scale;
    }
  s.lanesCurrent_ = false;  // the lanes hold the impulses before the scaling
  s.def_.substeps = substeps;
  s.def_.integrator = integrator;
}

const WorldDef& World::def() const {
  return s_->def_;
}
const Profile& World::profile() const {
  return s_->profile_;
}
double World::time() const {
  return s_->time_;
}

}  // namespace rc
