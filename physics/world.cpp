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
double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

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

WorldState::WorldState(const WorldDef& def) : def_(def), broadphase_(def.bounds) {
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
  const auto start = Clock::now();
  auto t = start;
  s.events_.begin.clear();
  s.events_.end.clear();
  s.events_.hit.clear();
  s.sensorEvents_.begin.clear();
  s.sensorEvents_.end.clear();
  // Bodies new or changed since the last step: proxies stretched along this step's motion.
  std::sort(s.pendingRefit_.begin(), s.pendingRefit_.end());
  s.pendingRefit_.erase(std::unique(s.pendingRefit_.begin(), s.pendingRefit_.end()),
                        s.pendingRefit_.end());
  for (std::int32_t index : s.pendingRefit_) {
    WorldState::Body& b = s.bodies_[static_cast<std::size_t>(index)];
    if (b.alive && b.slot >= 0) s.refitBody(b, dt * s.velocityOf(b));
  }
  s.pendingRefit_.clear();

  s.updatePairs();
  profile.updatePairs = millisecondsSince(t);
  t = Clock::now();
  s.narrowphase(dt);
  profile.narrowphase = millisecondsSince(t);
  t = Clock::now();
  s.solve(dt);
  profile.solve = millisecondsSince(t);
  t = Clock::now();
  if (s.def_.continuous) s.continuous();
  profile.continuous = millisecondsSince(t);
  t = Clock::now();
  s.refit(dt);
  profile.refit = millisecondsSince(t);
  t = Clock::now();
  s.updateSensors();
  profile.sensors = millisecondsSince(t);
  t = Clock::now();
  s.updateSleep(dt);
  profile.sleep = millisecondsSince(t);
  profile.total = millisecondsSince(start);
  s.time_ += dt;
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
    refitBody(b, dt * Vec2{v_[i], v_[i + 1]});  // where it goes next step
  }
}

// ------------------------------------------------------------------------- the whole state

std::uint64_t World::stateHash() const {
  const WorldState& s = *s_;
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto mixBits = [&](std::uint64_t bits, int bytes) {
    for (int k = 0; k < bytes; ++k) {
      h ^= (bits >> (8 * k)) & 0xFFu;
      h *= 0x100000001b3ull;
    }
  };
  auto mix = [&](float f) { mixBits(std::bit_cast<std::uint32_t>(f), 4); };
  for (std::size_t i = 0; i < s.bodies_.size(); ++i) {
    const WorldState::Body& b = s.bodies_[i];
    if (!b.alive) continue;
    if (b.slot < 0) {
      mix(b.xf.p.x);
      mix(b.xf.p.y);
      mix(b.angle);
      continue;
    }
    // The state as the world keeps it: double centre and angle, float velocities.
    const auto k = 3 * static_cast<std::size_t>(b.slot);
    for (std::size_t j = 0; j < 3; ++j)
      mixBits(std::bit_cast<std::uint64_t>(s.q_[k + j]), 8);
    for (std::size_t j = 0; j < 3; ++j)
      mix(s.v_[k + j]);
  }
  return h;
}

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
int World::bodyCount() const {
  return s_->bodyCount_;
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
void World::addForceField(ForceField field) {
  s_->fields_.push_back(std::move(field));
}
const Quadtree& World::broadphase() const {
  return s_->broadphase_;
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
