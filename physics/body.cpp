// Bodies and their shapes: creation and destruction, mass, state, forces and impulses.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {
namespace {

// Half the thinnest width of a shape: it cannot pass through anything while it moves less than
// this per step. (The polygon's value is its inscribed radius about the centroid, a lower
// bound.)
float thickness(const Shape& s) {
  switch (s.type) {
    case ShapeType::circle:
      return s.circle.radius;
    case ShapeType::box:
      return std::min(s.box.halfExtents.x, s.box.halfExtents.y);
    case ShapeType::capsule:
      return s.capsule.radius;
    case ShapeType::polygon: {
      float r = std::numeric_limits<float>::max();
      for (int i = 0; i < s.polygon.count; ++i)
        r = std::min(r, dot(s.polygon.normals[i], s.polygon.vertices[i] - s.polygon.centroid));
      return r + s.polygon.radius;
    }
    case ShapeType::segment:
    case ShapeType::chainSegment:
      return 0.0f;
  }
  return 0.0f;
}

// A body's extents for continuous collision, widened by one of its shapes: the thinnest shape's
// half-thickness (a lower bound) and the farthest reach from the body origin.
void widenExtents(float& minExtent, float& maxExtent, const Shape& s, const BoundingCircle& bound) {
  minExtent = std::min(minExtent, thickness(s));
  maxExtent = std::max(maxExtent, length(bound.center) + bound.radius);
}

// A circle about the body's centre of mass: a body of nothing else is round (Body::round).
bool centredCircle(const Shape& s, Vec2 localCenter) {
  return s.type == ShapeType::circle && s.circle.center == localCenter;
}

}  // namespace

// ------------------------------------------------------------------------------------ ForceStage

int ForceStage::slot(BodyId id) const {
  return world_.body(id).slot;
}
Vec2 ForceStage::center(BodyId id) const {
  const int s = slot(id);
  if (s < 0) return world_.center(world_.body(id));
  return {static_cast<float>(q_[3 * static_cast<std::size_t>(s)]),
          static_cast<float>(q_[3 * static_cast<std::size_t>(s) + 1])};
}
float ForceStage::angle(BodyId id) const {
  const int s = slot(id);
  return s < 0 ? world_.body(id).angle
               : static_cast<float>(q_[3 * static_cast<std::size_t>(s) + 2]);
}
Vec2 ForceStage::velocity(BodyId id) const {
  const int s = slot(id);
  if (s < 0) return {};
  return {v_[3 * static_cast<std::size_t>(s)], v_[3 * static_cast<std::size_t>(s) + 1]};
}
float ForceStage::angularVelocity(BodyId id) const {
  const int s = slot(id);
  return s < 0 ? 0.0f : v_[3 * static_cast<std::size_t>(s) + 2];
}
void ForceStage::addForce(BodyId id, Vec2 force) {
  const WorldState::Body& b = world_.body(id);
  if (b.type != BodyType::dynamicBody) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  a_[i] += b.invMass * force.x;
  a_[i + 1] += b.invMass * force.y;
}
void ForceStage::addTorque(BodyId id, float torque) {
  const WorldState::Body& b = world_.body(id);
  if (b.type != BodyType::dynamicBody) return;
  a_[3 * static_cast<std::size_t>(b.slot) + 2] += b.invInertia * torque;
}
void ForceStage::addForceAt(BodyId id, Vec2 force, Vec2 worldPoint) {
  addForce(id, force);
  addTorque(id, cross(worldPoint - center(id), force));
}

std::size_t WorldState::checked(BodyId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= bodies_.size() ||
      !bodies_[static_cast<std::size_t>(id.index)].alive ||
      bodies_[static_cast<std::size_t>(id.index)].generation != id.generation)
    throw std::invalid_argument("world: body " + std::to_string(id.index) + " (generation " +
                                std::to_string(id.generation) + ") does not exist");
  return static_cast<std::size_t>(id.index);
}

bool World::isValid(BodyId id) const {
  const auto& bodies = s_->bodies_;
  return id.index >= 0 && static_cast<std::size_t>(id.index) < bodies.size() &&
         bodies[static_cast<std::size_t>(id.index)].alive &&
         bodies[static_cast<std::size_t>(id.index)].generation == id.generation;
}

BodyId World::createBody(const BodyDef& def) {
  return s_->createBody(def);
}
void World::destroyBody(BodyId id) {
  s_->destroyBody(id);
}
ShapeId World::createShape(BodyId body, const Shape& shape, const ShapeDef& def) {
  return s_->createShape(body, shape, def);
}

Vec2 WorldState::velocityOf(const Body& b) const {
  if (b.slot < 0) return {};
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  return {v_[i], v_[i + 1]};
}

Vec2 WorldState::center(const Body& b) const {
  if (b.slot < 0) return apply(b.xf, b.localCenter);
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  return {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])};
}

Sweep WorldState::stepSweep(const Body& b) const {
  const auto s = static_cast<std::size_t>(b.slot);
  const std::size_t i = 3 * s;
  return {b.localCenter,
          {static_cast<float>(startCenter_[2 * s]), static_cast<float>(startCenter_[2 * s + 1])},
          {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])},
          static_cast<float>(startAngle_[s]),
          static_cast<float>(q_[i + 2])};
}

double WorldState::preciseOrigin(const Body& b, int axis) const {
  if (b.slot < 0) return axis == 0 ? b.xf.p.x : b.xf.p.y;
  const Vec2 turned = rotate(b.xf.q, b.localCenter);
  return q_[3 * static_cast<std::size_t>(b.slot) + static_cast<std::size_t>(axis)] -
         static_cast<double>(axis == 0 ? turned.x : turned.y);
}

std::array<double, 2> WorldState::preciseOrigin(const Body& b) const {
  return {preciseOrigin(b, 0), preciseOrigin(b, 1)};
}

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
  if (def.type != BodyType::staticBody) {
    b.slot = static_cast<std::int32_t>(slotBody_.size());
    slotBody_.push_back(index);
    q_.insert(q_.end(), {def.position.x, def.position.y, def.angle});
    const float w = def.fixedRotation ? 0.0f : def.angularVelocity;
    v_.insert(v_.end(), {def.linearVelocity.x, def.linearVelocity.y, w});
    // Into the awake slots, before the sleeping ones.
    swapSlots(b.slot, awakeCount_);
    ++awakeCount_;
  }
  updateMass(b);
  if (b.slot >= 0) pendingRefit_.push_back(index);
  ++bodyCount_;
  return {index, generation};
}

void WorldState::destroyBody(BodyId id) {
  const std::size_t index = checked(id);
  Body& b = bodies_[index];
  wakeBody(b);
  // Its contacts (back to front: removal swaps the last contact in); what it touched wakes.
  for (std::size_t c = contacts_.size(); c-- > 0;) {
    const Contact& k = contacts_[c];
    const std::int32_t bodyA = shapes_[static_cast<std::size_t>(k.shapeA)].body;
    const std::int32_t bodyB = shapes_[static_cast<std::size_t>(k.shapeB)].body;
    if (bodyA != id.index && bodyB != id.index) continue;
    if (k.touching) wakeBody(bodies_[static_cast<std::size_t>(bodyA == id.index ? bodyB : bodyA)]);
    destroyContact(c);
  }
  for (std::size_t k = sensorPairs_.size(); k-- > 0;) {
    const SensorPair& sp = sensorPairs_[k];
    if (shapes_[static_cast<std::size_t>(sp.sensor)].body == id.index ||
        shapes_[static_cast<std::size_t>(sp.visitor)].body == id.index)
      destroySensorPair(k);
  }
  for (std::int32_t s : b.shapes) {
    ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    broadphase_.destroyProxy(r.proxy);
    r.alive = false;
  }
  if (b.slot >= 0) {
    // To the end of the awake slots, then to the very end, then gone.
    swapSlots(b.slot, awakeCount_ - 1);
    swapSlots(b.slot, static_cast<std::int32_t>(slotBody_.size()) - 1);
    --awakeCount_;
    slotBody_.pop_back();
    q_.resize(q_.size() - 3);
    v_.resize(v_.size() - 3);
  }
  b.alive = false;
  b.shapes.clear();
  freeBodies_.push_back(id.index);
  --bodyCount_;
}

void WorldState::swapSlots(std::int32_t a, std::int32_t b) {
  if (a == b) return;
  const auto ia = 3 * static_cast<std::size_t>(a), ib = 3 * static_cast<std::size_t>(b);
  for (std::size_t k = 0; k < 3; ++k) {
    std::swap(q_[ia + k], q_[ib + k]);
    std::swap(v_[ia + k], v_[ib + k]);
  }
  std::swap(slotBody_[static_cast<std::size_t>(a)], slotBody_[static_cast<std::size_t>(b)]);
  bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(a)])].slot = a;
  bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(b)])].slot = b;
}

ShapeId WorldState::createShape(BodyId bodyId, const Shape& shape, const ShapeDef& def) {
  const std::size_t bi = checked(bodyId);
  try {
    validate(shape);
  } catch (const InvalidShape& e) {
    throw InvalidDefinition(std::string("shape: ") + e.what());
  }
  requireNonNegative("shape", "density", def.density);
  requireNonNegative("shape", "friction", def.friction);
  requireNonNegative("shape", "restitution", def.restitution);
  if (!shape.isSolid() && bodies_[bi].type == BodyType::dynamicBody)
    failDefinition("shape", "type",
                   std::string("is a ") + shapeTypeName(shape.type) +
                       ", which has no area: only static and kinematic bodies may carry it");
  const auto index = static_cast<std::int32_t>(shapes_.size());
  ShapeRecord r;
  r.shape = shape;
  r.body = bodyId.index;
  r.generation = 1;
  r.alive = true;
  r.isSensor = def.isSensor;
  r.density = def.density;
  r.friction = def.friction;
  r.restitution = def.restitution;
  r.userData = def.userData;
  r.bound = computeBoundingCircle(shape);
  Body& b = bodies_[bi];
  ProxyDef proxy;
  proxy.aabb = computeAABB(shape, b.xf);
  proxy.filter = def.filter;
  proxy.isStatic = b.type == BodyType::staticBody;
  proxy.userData = static_cast<std::uint64_t>(index);
  r.proxy = broadphase_.createProxy(proxy);
  shapes_.push_back(r);
  b.shapes.push_back(index);
  if (b.type == BodyType::dynamicBody) {
    updateMass(b);
  } else {
    // No mass to combine: the new shape only widens the extents, which updateMass would find by
    // walking every shape of the body again (a level's walls as 20,000 tiles on one static body
    // took 2 s to create, quadratically).
    if (b.shapes.size() == 1) {
      b.minExtent = std::numeric_limits<float>::max();
      b.maxExtent = 0.0f;
      b.round = true;
    }
    widenExtents(b.minExtent, b.maxExtent, shape, r.bound);
    b.round = b.round && centredCircle(shape, b.localCenter);
  }
  if (b.slot >= 0) pendingRefit_.push_back(bodyId.index);
  return {index, 1};
}

bool WorldState::isRound(const Body& b) const {
  if (b.shapes.empty()) return false;
  for (std::int32_t s : b.shapes) {
    if (!centredCircle(shapes_[static_cast<std::size_t>(s)].shape, b.localCenter)) return false;
  }
  return true;
}

void WorldState::updateMass(Body& b) {
  b.mass = b.invMass = b.inertia = b.invInertia = 0.0f;
  b.minExtent = std::numeric_limits<float>::max();
  b.maxExtent = 0.0f;
  for (std::int32_t s : b.shapes) {
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    widenExtents(b.minExtent, b.maxExtent, r.shape, r.bound);
  }
  if (b.type != BodyType::dynamicBody) {
    b.localCenter = {};
    b.round = isRound(b);
    return;
  }
  std::vector<MassData> parts;
  for (std::int32_t s : b.shapes) {
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    if (r.shape.isSolid() && r.density > 0.0f) parts.push_back(computeMass(r.shape, r.density));
  }
  const MassData m = combineMass(parts);
  const std::array<double, 2> origin = preciseOrigin(b);
  const Vec2 oldLocalCenter = b.localCenter;
  if (m.mass > 0.0f) {
    b.mass = m.mass;
    b.localCenter = m.center;
    b.inertia = m.inertia;
  } else {
    // A dynamic body needs mass: 1 kg at the origin, as Box2D does.
    b.mass = 1.0f;
    b.localCenter = {};
  }
  b.invMass = 1.0f / b.mass;
  b.invInertia = (b.fixedRotation || b.inertia <= 0.0f) ? 0.0f : 1.0f / b.inertia;
  b.round = isRound(b);
  // The centre of mass moved: keep the origin where it is and the motion of every point.
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  const Vec2 turned = rotate(b.xf.q, b.localCenter);
  const float w = v_[i + 2];
  const Vec2 shift = cross(w, rotate(b.xf.q, b.localCenter - oldLocalCenter));
  q_[i] = origin[0] + turned.x;
  q_[i + 1] = origin[1] + turned.y;
  v_[i] += shift.x;
  v_[i + 1] += shift.y;
}

// ------------------------------------------------------------------------------ accessors

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

void World::setLinearVelocity(BodyId id, Vec2 v) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  s.wakeBody(b);
  requireFinite("setLinearVelocity", "velocity", v);
  if (b.slot < 0) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  s.v_[i] = v.x;
  s.v_[i + 1] = v.y;
  s.pendingRefit_.push_back(id.index);
}
void World::setAngularVelocity(BodyId id, float w) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  s.wakeBody(b);
  requireFinite("setAngularVelocity", "angular velocity", w);
  if (b.slot < 0 || b.fixedRotation) return;
  s.v_[3 * static_cast<std::size_t>(b.slot) + 2] = w;
}
void World::setTransform(BodyId id, Vec2 position, float angle) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  s.wakeBody(b);
  requireFinite("setTransform", "position", position);
  requireFinite("setTransform", "angle", angle);
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

void World::applyForce(BodyId id, Vec2 force, Vec2 worldPoint) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("applyForce", "force", force);
  requireFinite("applyForce", "point", worldPoint);
  s.wakeBody(b);
  if (b.type != BodyType::dynamicBody) return;
  b.force += force;
  b.torque += cross(worldPoint - s.center(b), force);
}
void World::applyForceToCenter(BodyId id, Vec2 force) {
  WorldState::Body& b = s_->body(id);
  requireFinite("applyForceToCenter", "force", force);
  s_->wakeBody(b);
  if (b.type == BodyType::dynamicBody) b.force += force;
}
void World::applyTorque(BodyId id, float torque) {
  WorldState::Body& b = s_->body(id);
  requireFinite("applyTorque", "torque", torque);
  s_->wakeBody(b);
  if (b.type == BodyType::dynamicBody) b.torque += torque;
}
void World::applyLinearImpulse(BodyId id, Vec2 impulse, Vec2 worldPoint) {
  WorldState& s = *s_;
  WorldState::Body& b = s.body(id);
  requireFinite("applyLinearImpulse", "impulse", impulse);
  requireFinite("applyLinearImpulse", "point", worldPoint);
  s.wakeBody(b);
  if (b.type != BodyType::dynamicBody) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  s.v_[i] += b.invMass * impulse.x;
  s.v_[i + 1] += b.invMass * impulse.y;
  s.v_[i + 2] += b.invInertia * cross(worldPoint - s.center(b), impulse);
}
void World::applyAngularImpulse(BodyId id, float impulse) {
  WorldState::Body& b = s_->body(id);
  requireFinite("applyAngularImpulse", "impulse", impulse);
  s_->wakeBody(b);
  if (b.type == BodyType::dynamicBody)
    s_->v_[3 * static_cast<std::size_t>(b.slot) + 2] += b.invInertia * impulse;
}

std::vector<BodyId> World::bodies() const {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < s_->bodies_.size(); ++i)
    if (s_->bodies_[i].alive) out.push_back(s_->bodyId(static_cast<std::int32_t>(i)));
  return out;
}

std::vector<ShapeId> World::shapesOf(BodyId id) const {
  std::vector<ShapeId> out;
  for (std::int32_t shape : s_->body(id).shapes)
    out.push_back(s_->shapeId(shape));
  return out;
}

const Shape& World::shape(ShapeId id) const {
  return s_->shapeRecord(id).shape;
}

bool World::isSensor(ShapeId id) const {
  return s_->shapeRecord(id).isSensor;
}

void WorldState::refitBody(Body& b, Vec2 displacement) {
  if (b.round && b.slot >= 0) {
    // Circles about the centre of mass: their box is the centre (kept in double) plus and minus
    // the radius, with no rotation and no dispatch on the shape type (computeAABB was 6% of a
    // 5000-circle arena step).
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
  for (std::int32_t s : b.shapes) {
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    broadphase_.moveProxy(r.proxy, computeAABB(r.shape, b.xf), displacement);
  }
}

const WorldState::ShapeRecord& WorldState::shapeRecord(ShapeId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= shapes_.size() ||
      !shapes_[static_cast<std::size_t>(id.index)].alive ||
      shapes_[static_cast<std::size_t>(id.index)].generation != id.generation)
    throw std::invalid_argument("world: shape " + std::to_string(id.index) + " does not exist");
  return shapes_[static_cast<std::size_t>(id.index)];
}

BodyId World::bodyOf(ShapeId shape) const {
  return s_->bodyId(s_->shapeRecord(shape).body);
}

}  // namespace rc
