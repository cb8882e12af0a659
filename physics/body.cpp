// Bodies: creation and destruction (generational slots), their simulated slots, enabling and
// disabling, state, setters, forces and impulses; what a force field sees (ForceStage).
#include <algorithm>
#include <cmath>
#include <string>

#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

// ------------------------------------------------------------------------------ ForceStage

// The stage's slot of an awake body, or -1 (static, asleep or disabled: seen as the world keeps
// it). A stale id is remembered (step() reports it once the step is done) and reads as -2.
int ForceStage::slot(BodyId id) const {
  const WorldState::Body* b = world_.find(id);
  if (b == nullptr) {
    if (!world_.staleFieldId_) world_.staleFieldId_ = id;
    return -2;
  }
  return world_.awake(*b) ? b->slot : -1;
}
Vec2 ForceStage::center(BodyId id) const {
  const int s = slot(id);
  if (s == -2) return {};
  if (s < 0) return world_.center(world_.bodies_[static_cast<std::size_t>(id.index)]);
  return {static_cast<float>(q_[3 * static_cast<std::size_t>(s)]),
          static_cast<float>(q_[3 * static_cast<std::size_t>(s) + 1])};
}
float ForceStage::angle(BodyId id) const {
  const int s = slot(id);
  if (s == -2) return 0.0f;
  return s < 0 ? world_.bodies_[static_cast<std::size_t>(id.index)].angle
               : static_cast<float>(q_[3 * static_cast<std::size_t>(s) + 2]);
}
Vec2 ForceStage::velocity(BodyId id) const {
  const int s = slot(id);
  if (s < 0) return {};  // static, asleep (at rest) or stale
  return {v_[3 * static_cast<std::size_t>(s)], v_[3 * static_cast<std::size_t>(s) + 1]};
}
float ForceStage::angularVelocity(BodyId id) const {
  const int s = slot(id);
  return s < 0 ? 0.0f : v_[3 * static_cast<std::size_t>(s) + 2];
}
void ForceStage::addForce(BodyId id, Vec2 force) {
  const int s = slot(id);
  if (s == -2) return;
  const WorldState::Body& b = world_.bodies_[static_cast<std::size_t>(id.index)];
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  if (!isFinite(force)) {
    world_.requestQuarantine(id.index, QuarantineCause::forceField);
    return;
  }
  if (s < 0) {
    // Asleep: it cannot join a step under way; it wakes after it, and the field acts from the
    // next step on.
    if (force != Vec2{}) world_.fieldWakes_.push_back(id.index);
    return;
  }
  const auto i = 3 * static_cast<std::size_t>(s);
  a_[i] += b.invMass * force.x;
  a_[i + 1] += b.invMass * force.y;
}
void ForceStage::addTorque(BodyId id, float torque) {
  const int s = slot(id);
  if (s == -2) return;
  const WorldState::Body& b = world_.bodies_[static_cast<std::size_t>(id.index)];
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  if (!std::isfinite(torque)) {
    world_.requestQuarantine(id.index, QuarantineCause::forceField);
    return;
  }
  if (s < 0) {
    if (torque != 0.0f) world_.fieldWakes_.push_back(id.index);
    return;
  }
  a_[3 * static_cast<std::size_t>(s) + 2] += b.invInertia * torque;
}
void ForceStage::addForceAt(BodyId id, Vec2 force, Vec2 worldPoint) {
  addForce(id, force);
  addTorque(id, cross(worldPoint - center(id), force));
}

// ------------------------------------------------------------------------------ lookups

const WorldState::Body* WorldState::find(BodyId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= bodies_.size()) return nullptr;
  const Body& b = bodies_[static_cast<std::size_t>(id.index)];
  return b.alive && b.generation == id.generation ? &b : nullptr;
}

std::size_t WorldState::checked(BodyId id) const {
  if (find(id) == nullptr)
    throw std::invalid_argument("world: body " + std::to_string(id.index) + " (generation " +
                                std::to_string(id.generation) + ") does not exist");
  return static_cast<std::size_t>(id.index);
}

bool World::isValid(BodyId id) const {
  return s_->find(id) != nullptr;
}

// ------------------------------------------------------------------- creation, destruction

BodyId WorldState::createBody(const BodyDef& def) {
  requireFinite("body", "position", def.position);
  requireFinite("body", "angle", def.angle);
  requireFinite("body", "linearVelocity", def.linearVelocity);
  requireFinite("body", "angularVelocity", def.angularVelocity);
  requireNonNegative("body", "linearDamping", def.linearDamping);
  requireNonNegative("body", "angularDamping", def.angularDamping);
  requireFinite("body", "gravityScale", def.gravityScale);
  if (def.type != BodyType::staticBody && def.type != BodyType::kinematicBody &&
      def.type != BodyType::dynamicBody)
    failDefinition("body", "type", "is not static, kinematic or dynamic");

  std::int32_t index;
  if (!freeBodies_.empty()) {
    index = freeBodies_.back();
    freeBodies_.pop_back();
  } else {
    index = static_cast<std::int32_t>(bodies_.size());
    bodies_.emplace_back();
  }
  Body& b = bodies_[static_cast<std::size_t>(index)];
  const std::uint32_t generation = b.generation + 1;
  b = Body{};
  b.generation = generation;
  b.alive = true;
  b.type = def.type;
  b.xf = {def.position, Rot::fromAngle(def.angle)};
  b.angle = def.angle;
  b.linearDamping = def.linearDamping;
  b.angularDamping = def.angularDamping;
  b.gravityScale = def.gravityScale;
  b.fixedRotation = def.fixedRotation;
  b.bullet = def.bullet;
  b.allowSleep = def.allowSleep;
  b.userData = def.userData;
  if (def.type != BodyType::staticBody)
    takeSlot(index, def.linearVelocity, def.fixedRotation ? 0.0f : def.angularVelocity);
  updateMass(b);
  if (b.slot >= 0) pendingRefit_.push_back(index);
  ++bodyCount_;
  return {index, generation};
}

void WorldState::destroyBody(BodyId id) {
  const std::size_t index = checked(id);
  Body& b = bodies_[index];
  wakeBody(b);
  removeProxies(b);
  for (std::int32_t s : b.shapes) {
    shapes_[static_cast<std::size_t>(s)].alive = false;
    freeShapes_.push_back(s);
    --shapeCount_;
  }
  if (b.slot >= 0) releaseSlot(b);
  b.alive = false;
  b.shapes.clear();
  freeBodies_.push_back(id.index);
  --bodyCount_;
}

// A new slot at the end, then swapped into the awake slots, before the sleeping ones.
void WorldState::takeSlot(std::int32_t index, Vec2 velocity, float angularVelocity) {
  velocitiesSet_ = true;
  Body& b = bodies_[static_cast<std::size_t>(index)];
  b.slot = static_cast<std::int32_t>(slotBody_.size());
  slotBody_.push_back(index);
  const Vec2 c = apply(b.xf, b.localCenter);
  q_.insert(q_.end(), {c.x, c.y, b.angle});
  v_.insert(v_.end(), {velocity.x, velocity.y, angularVelocity});
  stillFrom_.insert(stillFrom_.end(), {0.0, 0.0});
  swapSlots(b.slot, awakeCount_);
  ++awakeCount_;
}

// Out of the awake slots if it is in them, then to the very end, then gone. The body keeps
// its transform (xf), rounded to float.
void WorldState::releaseSlot(Body& b) {
  const std::array<double, 2> origin = preciseOrigin(b);
  b.xf.p = {static_cast<float>(origin[0]), static_cast<float>(origin[1])};
  if (awake(b)) {
    swapSlots(b.slot, awakeCount_ - 1);
    --awakeCount_;
  }
  swapSlots(b.slot, static_cast<std::int32_t>(slotBody_.size()) - 1);
  slotBody_.pop_back();
  q_.resize(q_.size() - 3);
  v_.resize(v_.size() - 3);
  stillFrom_.resize(stillFrom_.size() - 2);
  b.slot = -1;
}

void WorldState::swapSlots(std::int32_t a, std::int32_t b) {
  ++awakeEpoch_;  // every change of the awake set swaps slots (awakeContacts_)
  if (a == b) return;
  const auto ia = 3 * static_cast<std::size_t>(a), ib = 3 * static_cast<std::size_t>(b);
  for (std::size_t k = 0; k < 3; ++k) {
    std::swap(q_[ia + k], q_[ib + k]);
    std::swap(v_[ia + k], v_[ib + k]);
  }
  for (std::size_t k = 0; k < 2; ++k)
    std::swap(stillFrom_[2 * static_cast<std::size_t>(a) + k],
              stillFrom_[2 * static_cast<std::size_t>(b) + k]);
  std::swap(slotBody_[static_cast<std::size_t>(a)], slotBody_[static_cast<std::size_t>(b)]);
  bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(a)])].slot = a;
  bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(b)])].slot = b;
}

// A disabled body keeps its slot, after the awake ones and in no island, so its state stays.
void WorldState::disable(Body& b) {
  if (!b.enabled) return;
  wakeBody(b);  // out of its island
  removeProxies(b);
  if (awake(b)) {
    swapSlots(b.slot, awakeCount_ - 1);
    --awakeCount_;
  }
  b.enabled = false;
}

void WorldState::enable(Body& b) {
  if (b.enabled) return;
  velocitiesSet_ = true;
  b.enabled = true;
  b.sleepTime = 0.0f;
  if (b.slot >= 0) {
    swapSlots(b.slot, awakeCount_);
    ++awakeCount_;
    pendingRefit_.push_back(static_cast<std::int32_t>(&b - bodies_.data()));
  }
  addProxies(b);
}

void WorldState::refitBody(Body& b, Vec2 displacement, float turn) {
  if (!b.enabled) return;  // no proxies
  if (b.round && b.slot >= 0) {
    // Circles about the centre of mass: their box is the centre (kept in double) plus and minus
    // the radius, with no rotation and no dispatch on the shape type.
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const Vec2 c{static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])};
    for (std::int32_t s : b.shapes) {
      const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
      const float radius = r.shape.circle.radius;
      broadphase_.moveProxy(r.proxy, {{c.x - radius, c.y - radius}, {c.x + radius, c.y + radius}},
                            displacement);
    }
    return;
  }
  // (maxExtent, the reach from the origin, plus the centre's distance from it bounds every
  // shape's reach: the common slow turner is told apart without a square root per shape.)
  const float turned = std::fabs(turn);
  const bool fastTurn =
      turned * (b.maxExtent + std::fabs(b.localCenter.x) + std::fabs(b.localCenter.y)) >
      kAabbMargin;
  for (std::int32_t s : b.shapes) {
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    const float reach = fastTurn ? r.reach : 0.0f;
    if (turned * reach > kAabbMargin) {
      // A fast turner (a swinging door): its next step's box is the disc every point of the
      // shape stays in as the body turns about its centre of mass, so the pairs it will meet
      // exist before it sweeps through them.
      const Vec2 c = center(b);
      broadphase_.moveProxy(r.proxy, {{c.x - reach, c.y - reach}, {c.x + reach, c.y + reach}},
                            displacement);
    } else {
      // (Tested inline first: a resting shape's fat box stays, and the call is skipped.)
      const AABB box = computeAABB(r.shape, b.xf);
      if (!broadphase_.fits(r.proxy, box, displacement))
        broadphase_.moveProxy(r.proxy, box, displacement);
    }
  }
}

BodyId World::createBody(const BodyDef& def) {
  return s_->createBody(def);
}
void World::destroyBody(BodyId id) {
  s_->destroyBody(id);
}

std::vector<BodyId> World::bodies() const {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < s_->bodies_.size(); ++i)
    if (s_->bodies_[i].alive) out.push_back(s_->bodyId(static_cast<std::int32_t>(i)));
  return out;
}

int World::bodyCount() const {
  return s_->bodyCount_;
}

// ------------------------------------------------------------------------------ state

Vec2 World::position(BodyId id) const {
  return s_->body(id).xf.p;
}
std::array<double, 2> World::precisePosition(BodyId id) const {
  return s_->preciseOrigin(s_->body(id));
}
float World::angle(BodyId id) const {
  return s_->body(id).angle;
}
Transform World::transform(BodyId id) const {
  return s_->body(id).xf;
}
Vec2 World::worldCenter(BodyId id) const {
  return s_->center(s_->body(id));
}
Vec2 World::linearVelocity(BodyId id) const {
  return s_->velocityOf(s_->body(id));
}
float World::angularVelocity(BodyId id) const {
  const WorldState::Body& b = s_->body(id);
  return b.slot < 0 ? 0.0f : s_->v_[3 * static_cast<std::size_t>(b.slot) + 2];
}
float World::mass(BodyId id) const {
  return s_->body(id).mass;
}
float World::rotationalInertia(BodyId id) const {
  return s_->body(id).inertia;
}
BodyType World::type(BodyId id) const {
  return s_->body(id).type;
}
std::uint64_t World::userData(BodyId id) const {
  return s_->body(id).userData;
}
float World::gravityScale(BodyId id) const {
  return s_->body(id).gravityScale;
}
bool World::isBullet(BodyId id) const {
  return s_->body(id).bullet;
}
bool World::isEnabled(BodyId id) const {
  return s_->body(id).enabled;
}

// ------------------------------------------------------------------------------ setters

void World::setLinearVelocity(BodyId id, Vec2 v) {
  s_->velocitiesSet_ = true;
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("setLinearVelocity", "velocity", v);
  s.wakeBody(b);
  if (b.slot < 0) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  s.v_[i] = v.x;
  s.v_[i + 1] = v.y;
  s.pendingRefit_.push_back(id.index);
}
void World::setAngularVelocity(BodyId id, float w) {
  s_->velocitiesSet_ = true;
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("setAngularVelocity", "angular velocity", w);
  s.wakeBody(b);
  if (b.slot < 0 || b.fixedRotation) return;
  s.v_[3 * static_cast<std::size_t>(b.slot) + 2] = w;
}
void World::setTransform(BodyId id, Vec2 position, float angle) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("setTransform", "position", position);
  requireFinite("setTransform", "angle", angle);
  s.wakeBody(b);
  b.xf = {position, Rot::fromAngle(angle)};
  b.angle = angle;
  if (b.slot >= 0) {
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const Vec2 c = apply(b.xf, b.localCenter);
    s.q_[i] = c.x;
    s.q_[i + 1] = c.y;
    s.q_[i + 2] = angle;
  }
  s.refitBody(b, {});
  if (b.slot >= 0) s.pendingRefit_.push_back(id.index);
}

void World::setTargetTransform(BodyId id, Vec2 position, float angle, float dt) {
  s_->velocitiesSet_ = true;
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("setTargetTransform", "position", position);
  requireFinite("setTargetTransform", "angle", angle);
  if (!(dt > 0.0f) || !std::isfinite(dt))
    failDefinition("setTargetTransform", "dt", "is " + formatNumber(dt) + " (must be > 0)");
  if (b.type != BodyType::kinematicBody)
    failDefinition("setTargetTransform", "body", "is not kinematic");
  // The centre's motion in double (the body may be far from the origin), the angle's too.
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  const Vec2 centre = apply(Transform{position, Rot::fromAngle(angle)}, b.localCenter);
  const double inv = 1.0 / static_cast<double>(dt);
  const Vec2 v{static_cast<float>((centre.x - s.q_[i]) * inv),
               static_cast<float>((centre.y - s.q_[i + 1]) * inv)};
  const auto w = static_cast<float>((static_cast<double>(angle) - s.q_[i + 2]) * inv);
  s.wakeBody(b);
  s.v_[i] = v.x;
  s.v_[i + 1] = v.y;
  s.v_[i + 2] = b.fixedRotation ? 0.0f : w;
  s.pendingRefit_.push_back(id.index);
}

void World::setType(BodyId id, BodyType type) {
  s_->velocitiesSet_ = true;
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  if (type != BodyType::staticBody && type != BodyType::kinematicBody &&
      type != BodyType::dynamicBody)
    failDefinition("setType", "type", "is not static, kinematic or dynamic");
  if (b.type == type) return;
  if (type == BodyType::dynamicBody)
    for (std::int32_t shape : b.shapes)
      if (!s.shapes_[static_cast<std::size_t>(shape)].shape.isSolid())
        failDefinition("setType", "type",
                       "is dynamic, but the body carries a shape without area (a segment or "
                       "chain link)");
  // Pairs depend on the type (static bodies pair with no static body, and live in their own
  // tree): its proxies are taken out and put back, and pairs found anew.
  s.wakeBody(b);
  const bool enabled = b.enabled;
  if (enabled) s.removeProxies(b);
  const Vec2 v = s.velocityOf(b);
  const float w = b.slot < 0 ? 0.0f : s.v_[3 * static_cast<std::size_t>(b.slot) + 2];
  if (type == BodyType::staticBody && b.slot >= 0) {
    s.releaseSlot(b);
  } else if (b.slot < 0 && type != BodyType::staticBody) {
    s.takeSlot(id.index, {}, 0.0f);
    if (!enabled) {
      s.swapSlots(b.slot, s.awakeCount_ - 1);
      --s.awakeCount_;
    }
  }
  b.type = type;
  s.updateMass(b);
  if (b.slot >= 0 && type == BodyType::dynamicBody) {
    // A kinematic body turning dynamic keeps its motion.
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    s.v_[i] = v.x;
    s.v_[i + 1] = v.y;
    s.v_[i + 2] = b.fixedRotation ? 0.0f : w;
  }
  b.force = {};
  b.torque = 0.0f;
  if (enabled) s.addProxies(b);
  if (b.slot >= 0) s.pendingRefit_.push_back(id.index);
}

void World::setGravityScale(BodyId id, float scale) {
  WorldState::Body& b = s_->body(id);
  requireFinite("setGravityScale", "scale", scale);
  s_->wakeBody(b);
  b.gravityScale = scale;
}
void World::setBullet(BodyId id, bool bullet) {
  s_->body(id).bullet = bullet;
}
void World::setUserData(BodyId id, std::uint64_t userData) {
  s_->body(id).userData = userData;
}
void World::setEnabled(BodyId id, bool enabled) {
  WorldState::Body& b = s_->body(id);
  if (enabled) {
    s_->enable(b);
  } else {
    s_->disable(b);
  }
}

// ------------------------------------------------------------------------ forces, impulses

void World::applyForce(BodyId id, Vec2 force, Vec2 worldPoint) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("applyForce", "force", force);
  requireFinite("applyForce", "point", worldPoint);
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  s.wakeBody(b);
  b.force += force;
  b.torque += cross(worldPoint - s.center(b), force);
}
void World::applyForceToCenter(BodyId id, Vec2 force) {
  WorldState::Body& b = s_->body(id);
  requireFinite("applyForceToCenter", "force", force);
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  s_->wakeBody(b);
  b.force += force;
}
void World::applyTorque(BodyId id, float torque) {
  WorldState::Body& b = s_->body(id);
  requireFinite("applyTorque", "torque", torque);
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  s_->wakeBody(b);
  b.torque += torque;
}
void World::applyLinearImpulse(BodyId id, Vec2 impulse, Vec2 worldPoint) {
  s_->velocitiesSet_ = true;
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("applyLinearImpulse", "impulse", impulse);
  requireFinite("applyLinearImpulse", "point", worldPoint);
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  s.wakeBody(b);
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  s.v_[i] += b.invMass * impulse.x;
  s.v_[i + 1] += b.invMass * impulse.y;
  s.v_[i + 2] += b.invInertia * cross(worldPoint - s.center(b), impulse);
  // A new velocity, as from setLinearVelocity: its proxies are stretched along the next step's
  // motion before pairs are found, or a fast body launched this way meets no moving body then.
  s.pendingRefit_.push_back(id.index);
}
void World::applyAngularImpulse(BodyId id, float impulse) {
  s_->velocitiesSet_ = true;
  WorldState::Body& b = s_->body(id);
  requireFinite("applyAngularImpulse", "impulse", impulse);
  if (b.type != BodyType::dynamicBody || !b.enabled) return;
  s_->wakeBody(b);
  s_->v_[3 * static_cast<std::size_t>(b.slot) + 2] += b.invInertia * impulse;
}

}  // namespace rc
