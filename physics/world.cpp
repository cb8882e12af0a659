#include "physics/world.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "physics/collide.h"
#include "physics/toi.h"

namespace rc {
namespace {

using Clock = std::chrono::steady_clock;
double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

[[noreturn]] void fail(const char* what, const char* field, const std::string& why) {
  throw InvalidDefinition(std::string(what) + ": " + field + " " + why);
}
void requireFinite(const char* what, const char* field, float v) {
  if (!std::isfinite(v)) fail(what, field, "is not finite (" + std::to_string(v) + ")");
}
void requireFinite(const char* what, const char* field, Vec2 v) {
  if (!isFinite(v))
    fail(what, field, "is not finite (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ")");
}
void requireNonNegative(const char* what, const char* field, float v) {
  requireFinite(what, field, v);
  if (v < 0.0f) fail(what, field, "is " + std::to_string(v) + " (must be >= 0)");
}

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

std::uint64_t pairKey(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// Friction and restitution of a pair, as Box2D mixes them: geometric mean, maximum.
float mixFriction(float a, float b) {
  return std::sqrt(a * b);
}
float mixRestitution(float a, float b) {
  return std::max(a, b);
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
  const World::Body& b = world_.body(id);
  if (b.type != BodyType::dynamicBody) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  a_[i] += b.invMass * force.x;
  a_[i + 1] += b.invMass * force.y;
}
void ForceStage::addTorque(BodyId id, float torque) {
  const World::Body& b = world_.body(id);
  if (b.type != BodyType::dynamicBody) return;
  a_[3 * static_cast<std::size_t>(b.slot) + 2] += b.invInertia * torque;
}
void ForceStage::addForceAt(BodyId id, Vec2 force, Vec2 worldPoint) {
  addForce(id, force);
  addTorque(id, cross(worldPoint - center(id), force));
}

// ----------------------------------------------------------------------------------- World

World::World(const WorldDef& def) : def_(def), broadphase_(def.bounds) {
  requireFinite("world", "gravity", def.gravity);
  if (def.substeps < 1 || def.substeps > 64)
    fail("world", "substeps", "is " + std::to_string(def.substeps) + " (must be 1 to 64)");
  requireNonNegative("world", "restitutionThreshold", def.restitutionThreshold);
  requireNonNegative("world", "contactHertz", def.contactHertz);
  requireNonNegative("world", "contactDampingRatio", def.contactDampingRatio);
  requireNonNegative("world", "maxPushoutSpeed", def.maxPushoutSpeed);
}

std::size_t World::checked(BodyId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= bodies_.size() ||
      !bodies_[static_cast<std::size_t>(id.index)].alive ||
      bodies_[static_cast<std::size_t>(id.index)].generation != id.generation)
    throw std::invalid_argument("world: body " + std::to_string(id.index) + " (generation " +
                                std::to_string(id.generation) + ") does not exist");
  return static_cast<std::size_t>(id.index);
}

bool World::isValid(BodyId id) const {
  return id.index >= 0 && static_cast<std::size_t>(id.index) < bodies_.size() &&
         bodies_[static_cast<std::size_t>(id.index)].alive &&
         bodies_[static_cast<std::size_t>(id.index)].generation == id.generation;
}

Vec2 World::velocityOf(const Body& b) const {
  if (b.slot < 0) return {};
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  return {v_[i], v_[i + 1]};
}

Vec2 World::center(const Body& b) const {
  if (b.slot < 0) return apply(b.xf, b.localCenter);
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  return {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])};
}

Sweep World::stepSweep(const Body& b) const {
  const auto s = static_cast<std::size_t>(b.slot);
  const std::size_t i = 3 * s;
  return {b.localCenter,
          {static_cast<float>(startCenter_[2 * s]), static_cast<float>(startCenter_[2 * s + 1])},
          {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])},
          static_cast<float>(startAngle_[s]),
          static_cast<float>(q_[i + 2])};
}

// Room for n queued turns before any is queued, so that an allocation failure cannot leave the
// angles and their owners of different lengths.
void World::reserveTurns(std::size_t n) {
  turnAngles_.reserve(n);
  turnOwners_.reserve(n);
  turnRotations_.reserve(n);
}

template <class Apply>
void World::applyTurns(Apply&& apply) {
  turnRotations_.resize(turnAngles_.size());
  sincos(turnAngles_, turnRotations_);
  for (std::size_t k = 0; k < turnAngles_.size(); ++k)
    apply(turnOwners_[k], Rot{turnRotations_[k].cosine, turnRotations_[k].sine});
  turnAngles_.clear();
  turnOwners_.clear();
}

double World::preciseOrigin(const Body& b, int axis) const {
  if (b.slot < 0) return axis == 0 ? b.xf.p.x : b.xf.p.y;
  const Vec2 turned = rotate(b.xf.q, b.localCenter);
  return q_[3 * static_cast<std::size_t>(b.slot) + static_cast<std::size_t>(axis)] -
         static_cast<double>(axis == 0 ? turned.x : turned.y);
}

std::array<double, 2> World::preciseOrigin(const Body& b) const {
  return {preciseOrigin(b, 0), preciseOrigin(b, 1)};
}

BodyId World::createBody(const BodyDef& def) {
  requireFinite("body", "position", def.position);
  requireFinite("body", "angle", def.angle);
  requireFinite("body", "linearVelocity", def.linearVelocity);
  requireFinite("body", "angularVelocity", def.angularVelocity);
  requireNonNegative("body", "linearDamping", def.linearDamping);
  requireNonNegative("body", "angularDamping", def.angularDamping);
  requireFinite("body", "gravityScale", def.gravityScale);
  if (def.type != BodyType::staticBody && def.type != BodyType::kinematicBody &&
      def.type != BodyType::dynamicBody)
    fail("body", "type", "is not static, kinematic or dynamic");

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

void World::destroyBody(BodyId id) {
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

void World::swapSlots(std::int32_t a, std::int32_t b) {
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

void World::wakeBody(Body& b) {
  b.sleepTime = 0.0f;
  if (b.island < 0) return;
  const std::int32_t island = b.island;
  for (std::int32_t index : islands_[static_cast<std::size_t>(island)]) {
    Body& m = bodies_[static_cast<std::size_t>(index)];
    m.island = -1;
    m.sleepTime = 0.0f;
    swapSlots(m.slot, awakeCount_);
    ++awakeCount_;
  }
  islands_[static_cast<std::size_t>(island)].clear();
  freeIslands_.push_back(island);
}

bool World::isAwake(BodyId id) const {
  return awake(body(id));
}

void World::wake(BodyId id) {
  wakeBody(body(id));
}

void World::updateSleep(float dt) {
  const auto n = static_cast<std::size_t>(awakeCount_);
  const float lin2 = def_.linearSleepTolerance * def_.linearSleepTolerance;
  const float ang2 = def_.angularSleepTolerance * def_.angularSleepTolerance;
  // Each awake body's still time; bodies that may not sleep count as never still.
  for (std::size_t s = 0; s < n; ++s) {
    Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const float v2 = v_[3 * s] * v_[3 * s] + v_[3 * s + 1] * v_[3 * s + 1];
    const float w2 = v_[3 * s + 2] * v_[3 * s + 2];
    const bool still = def_.enableSleep && b.allowSleep && v2 <= lin2 && w2 <= ang2;
    b.sleepTime = still ? b.sleepTime + dt : 0.0f;
  }
  if (!def_.enableSleep || n == 0) return;
  // Islands: awake dynamic bodies joined by touching contacts (union-find over slots).
  islandParent_.resize(n);
  for (std::size_t s = 0; s < n; ++s)
    islandParent_[s] = static_cast<std::int32_t>(s);
  auto root = [&](std::int32_t x) {
    while (islandParent_[static_cast<std::size_t>(x)] != x) {
      islandParent_[static_cast<std::size_t>(x)] =
          islandParent_[static_cast<std::size_t>(islandParent_[static_cast<std::size_t>(x)])];
      x = islandParent_[static_cast<std::size_t>(x)];
    }
    return x;
  };
  // An island touching something that moves and cannot join it (a moving kinematic body)
  // stays awake: its root gets a still time of 0 below.
  std::vector<float>& still = freeV_;  // reused scratch: the island's shortest still time
  still.assign(n, std::numeric_limits<float>::max());
  for (const Contact& c : contacts_) {
    if (!c.touching) continue;
    const Body& a =
        bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeA)].body)];
    const Body& b =
        bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeB)].body)];
    const bool da = a.type == BodyType::dynamicBody && awake(a);
    const bool db = b.type == BodyType::dynamicBody && awake(b);
    if (da && db) {
      islandParent_[static_cast<std::size_t>(root(a.slot))] = root(b.slot);
    } else if (da != db) {
      const Body& other = da ? b : a;
      if (other.type == BodyType::kinematicBody && awake(other)) {
        const auto k = 3 * static_cast<std::size_t>(other.slot);
        if (v_[k] != 0.0f || v_[k + 1] != 0.0f || v_[k + 2] != 0.0f)
          still[static_cast<std::size_t>((da ? a : b).slot)] = 0.0f;
      }
    }
  }
  for (std::size_t s = 0; s < n; ++s) {
    const float t = bodies_[static_cast<std::size_t>(slotBody_[s])].sleepTime;
    const auto r = static_cast<std::size_t>(root(static_cast<std::int32_t>(s)));
    still[r] = std::min({still[r], still[s], t});
  }
  // Islands still long enough go to sleep together, in slot order.
  std::vector<std::int32_t> sleepers;
  for (std::size_t s = 0; s < n; ++s)
    if (still[static_cast<std::size_t>(root(static_cast<std::int32_t>(s)))] >= def_.timeToSleep)
      sleepers.push_back(slotBody_[s]);
  if (sleepers.empty()) return;
  std::vector<std::int32_t> islandOfRoot(n, -1);
  for (std::int32_t index : sleepers) {
    Body& b = bodies_[static_cast<std::size_t>(index)];
    const auto r = static_cast<std::size_t>(root(b.slot));
    if (islandOfRoot[r] < 0) {
      if (freeIslands_.empty()) {
        islandOfRoot[r] = static_cast<std::int32_t>(islands_.size());
        islands_.emplace_back();
      } else {
        islandOfRoot[r] = freeIslands_.back();
        freeIslands_.pop_back();
      }
    }
    b.island = islandOfRoot[r];
    islands_[static_cast<std::size_t>(b.island)].push_back(index);
  }
  // Out of the awake slots (after the union-find is done with slot numbers), velocities zeroed.
  for (std::int32_t index : sleepers) {
    Body& b = bodies_[static_cast<std::size_t>(index)];
    swapSlots(b.slot, awakeCount_ - 1);
    --awakeCount_;
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    v_[i] = v_[i + 1] = v_[i + 2] = 0.0f;
  }
}

ShapeId World::createShape(BodyId bodyId, const Shape& shape, const ShapeDef& def) {
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
    fail("shape", "type",
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

bool World::isRound(const Body& b) const {
  if (b.shapes.empty()) return false;
  for (std::int32_t s : b.shapes) {
    if (!centredCircle(shapes_[static_cast<std::size_t>(s)].shape, b.localCenter)) return false;
  }
  return true;
}

void World::updateMass(Body& b) {
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
  return body(id).xf.p;
}
std::array<double, 2> World::precisePosition(BodyId id) const {
  return preciseOrigin(body(id));
}
float World::angle(BodyId id) const {
  return body(id).angle;
}
Transform World::transform(BodyId id) const {
  return body(id).xf;
}
Vec2 World::worldCenter(BodyId id) const {
  return center(body(id));
}
Vec2 World::linearVelocity(BodyId id) const {
  const Body& b = body(id);
  if (b.slot < 0) return {};
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  return {v_[i], v_[i + 1]};
}
float World::angularVelocity(BodyId id) const {
  const Body& b = body(id);
  return b.slot < 0 ? 0.0f : v_[3 * static_cast<std::size_t>(b.slot) + 2];
}
float World::mass(BodyId id) const {
  return body(id).mass;
}
float World::rotationalInertia(BodyId id) const {
  return body(id).inertia;
}
BodyType World::type(BodyId id) const {
  return body(id).type;
}
std::uint64_t World::userData(BodyId id) const {
  return body(id).userData;
}

void World::setLinearVelocity(BodyId id, Vec2 v) {
  Body& b = body(id);
  wakeBody(b);
  requireFinite("setLinearVelocity", "velocity", v);
  if (b.slot < 0) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  v_[i] = v.x;
  v_[i + 1] = v.y;
  pendingRefit_.push_back(id.index);
}
void World::setAngularVelocity(BodyId id, float w) {
  Body& b = body(id);
  wakeBody(b);
  requireFinite("setAngularVelocity", "angular velocity", w);
  if (b.slot < 0 || b.fixedRotation) return;
  v_[3 * static_cast<std::size_t>(b.slot) + 2] = w;
}
void World::setTransform(BodyId id, Vec2 position, float angle) {
  Body& b = body(id);
  wakeBody(b);
  requireFinite("setTransform", "position", position);
  requireFinite("setTransform", "angle", angle);
  b.xf = {position, Rot::fromAngle(angle)};
  b.angle = angle;
  if (b.slot >= 0) {
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const Vec2 c = apply(b.xf, b.localCenter);
    q_[i] = c.x;
    q_[i + 1] = c.y;
    q_[i + 2] = angle;
  }
  refitBody(b, {});
  if (b.slot >= 0) pendingRefit_.push_back(id.index);
}

void World::applyForce(BodyId id, Vec2 force, Vec2 worldPoint) {
  Body& b = body(id);
  requireFinite("applyForce", "force", force);
  requireFinite("applyForce", "point", worldPoint);
  wakeBody(b);
  if (b.type != BodyType::dynamicBody) return;
  b.force += force;
  b.torque += cross(worldPoint - center(b), force);
}
void World::applyForceToCenter(BodyId id, Vec2 force) {
  Body& b = body(id);
  requireFinite("applyForceToCenter", "force", force);
  wakeBody(b);
  if (b.type == BodyType::dynamicBody) b.force += force;
}
void World::applyTorque(BodyId id, float torque) {
  Body& b = body(id);
  requireFinite("applyTorque", "torque", torque);
  wakeBody(b);
  if (b.type == BodyType::dynamicBody) b.torque += torque;
}
void World::applyLinearImpulse(BodyId id, Vec2 impulse, Vec2 worldPoint) {
  Body& b = body(id);
  requireFinite("applyLinearImpulse", "impulse", impulse);
  requireFinite("applyLinearImpulse", "point", worldPoint);
  wakeBody(b);
  if (b.type != BodyType::dynamicBody) return;
  const auto i = 3 * static_cast<std::size_t>(b.slot);
  v_[i] += b.invMass * impulse.x;
  v_[i + 1] += b.invMass * impulse.y;
  v_[i + 2] += b.invInertia * cross(worldPoint - center(b), impulse);
}
void World::applyAngularImpulse(BodyId id, float impulse) {
  Body& b = body(id);
  requireFinite("applyAngularImpulse", "impulse", impulse);
  wakeBody(b);
  if (b.type == BodyType::dynamicBody)
    v_[3 * static_cast<std::size_t>(b.slot) + 2] += b.invInertia * impulse;
}

std::vector<BodyId> World::bodies() const {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (bodies_[i].alive) out.push_back({static_cast<std::int32_t>(i), bodies_[i].generation});
  return out;
}

std::vector<ShapeId> World::shapesOf(BodyId id) const {
  std::vector<ShapeId> out;
  for (std::int32_t s : body(id).shapes)
    out.push_back(shapeId(s));
  return out;
}

const Shape& World::shape(ShapeId id) const {
  return shapeRecord(id).shape;
}

bool World::isSensor(ShapeId id) const {
  return shapeRecord(id).isSensor;
}

std::vector<World::ContactPointView> World::contactPoints() const {
  std::vector<ContactPointView> out;
  for (const Contact& c : contacts_) {
    if (!c.touching) continue;
    for (int k = 0; k < c.manifold.pointCount; ++k)
      out.push_back({c.manifold.points[k].point, c.manifold.normal, c.manifold.points[k].separation,
                     c.normalImpulse[k]});
  }
  return out;
}

int World::touchingContactCount() const {
  int n = 0;
  for (const Contact& c : contacts_)
    n += c.touching;
  return n;
}

std::uint64_t World::stateHash() const {
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto mixBits = [&](std::uint64_t bits, int bytes) {
    for (int k = 0; k < bytes; ++k) {
      h ^= (bits >> (8 * k)) & 0xFFu;
      h *= 0x100000001b3ull;
    }
  };
  auto mix = [&](float f) { mixBits(std::bit_cast<std::uint32_t>(f), 4); };
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    if (!b.alive) continue;
    if (b.slot < 0) {
      mix(b.xf.p.x);
      mix(b.xf.p.y);
      mix(b.angle);
      continue;
    }
    // The state as the world keeps it: double centre and angle, float velocities.
    const auto s = 3 * static_cast<std::size_t>(b.slot);
    for (std::size_t k = 0; k < 3; ++k)
      mixBits(std::bit_cast<std::uint64_t>(q_[s + k]), 8);
    for (std::size_t k = 0; k < 3; ++k)
      mix(v_[s + k]);
  }
  return h;
}

double World::energy() const {
  double e = 0;
  for (const Body& b : bodies_) {
    if (!b.alive || b.type != BodyType::dynamicBody) continue;
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const double vx = v_[i], vy = v_[i + 1], w = v_[i + 2];
    e += 0.5 * b.mass * (vx * vx + vy * vy) + 0.5 * b.inertia * w * w;
    e -= b.mass * b.gravityScale *
         (static_cast<double>(def_.gravity.x) * q_[i] +
          static_cast<double>(def_.gravity.y) * q_[i + 1]);
  }
  return e;
}

// ------------------------------------------------------------------------------------ step

void World::step(float dt) {
  if (!(dt > 0.0f) || !std::isfinite(dt))
    throw std::invalid_argument("world: step dt must be finite and > 0, got " + std::to_string(dt));
  const auto start = Clock::now();
  auto t = start;
  events_.begin.clear();
  events_.end.clear();
  events_.hit.clear();
  sensorEvents_.begin.clear();
  sensorEvents_.end.clear();
  // Bodies new or changed since the last step: proxies stretched along this step's motion.
  std::sort(pendingRefit_.begin(), pendingRefit_.end());
  pendingRefit_.erase(std::unique(pendingRefit_.begin(), pendingRefit_.end()), pendingRefit_.end());
  for (std::int32_t index : pendingRefit_) {
    Body& b = bodies_[static_cast<std::size_t>(index)];
    if (b.alive && b.slot >= 0) refitBody(b, dt * velocityOf(b));
  }
  pendingRefit_.clear();
  updatePairs();
  profile_.updatePairs = millisecondsSince(t);
  t = Clock::now();
  narrowphase(dt);
  profile_.narrowphase = millisecondsSince(t);
  t = Clock::now();
  solve(dt);
  profile_.solve = millisecondsSince(t);
  t = Clock::now();
  if (def_.continuous) continuous();
  profile_.continuous = millisecondsSince(t);
  t = Clock::now();
  // Transforms, AABBs and proxies from the new positions; forces are used up.
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
  profile_.refit = millisecondsSince(t);
  t = Clock::now();
  updateSensors();
  profile_.sensors = millisecondsSince(t);
  t = Clock::now();
  updateSleep(dt);
  profile_.sleep = millisecondsSince(t);
  profile_.total = millisecondsSince(start);
  time_ += dt;
}

void World::refitBody(Body& b, Vec2 displacement) {
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

void World::updatePairs() {
  broadphase_.updatePairs(newPairs_);
  for (const ProxyPair& pair : newPairs_) {
    auto sa = static_cast<std::int32_t>(broadphase_.userData(pair.a));
    auto sb = static_cast<std::int32_t>(broadphase_.userData(pair.b));
    if (sa > sb) std::swap(sa, sb);
    const ShapeRecord& ra = shapes_[static_cast<std::size_t>(sa)];
    const ShapeRecord& rb = shapes_[static_cast<std::size_t>(sb)];
    if (ra.body == rb.body) continue;
    const Body& ba = bodies_[static_cast<std::size_t>(ra.body)];
    const Body& bb = bodies_[static_cast<std::size_t>(rb.body)];
    if (ra.isSensor || rb.isSensor) {
      // A sensor and a visitor, at least one of them able to move.
      if (ra.isSensor == rb.isSensor) continue;
      if (ba.type == BodyType::staticBody && bb.type == BodyType::staticBody) continue;
      const std::int32_t sensor = ra.isSensor ? sa : sb, visitor = ra.isSensor ? sb : sa;
      const std::uint64_t key = pairKey(sensor, visitor);
      if (sensorIndex_.count(key)) continue;
      sensorIndex_[key] = static_cast<std::int32_t>(sensorPairs_.size());
      sensorPairs_.push_back({sensor, visitor, false});
      continue;
    }
    if (ba.type != BodyType::dynamicBody && bb.type != BodyType::dynamicBody) continue;
    if (!hasManifold(ra.shape.type, rb.shape.type)) continue;
    const std::uint64_t key = pairKey(sa, sb);
    if (contactIndex_.count(key)) continue;
    Contact c;
    c.shapeA = sa;
    c.shapeB = sb;
    c.friction = mixFriction(ra.friction, rb.friction);
    c.restitution = mixRestitution(ra.restitution, rb.restitution);
    contactIndex_[key] = static_cast<std::int32_t>(contacts_.size());
    contacts_.push_back(c);
  }
}

void World::destroyContact(std::size_t index) {
  if (contacts_[index].touching)
    events_.end.push_back({shapeId(contacts_[index].shapeA), shapeId(contacts_[index].shapeB)});
  contactIndex_.erase(pairKey(contacts_[index].shapeA, contacts_[index].shapeB));
  if (index + 1 != contacts_.size()) {
    contacts_[index] = contacts_.back();
    contactIndex_[pairKey(contacts_[index].shapeA, contacts_[index].shapeB)] =
        static_cast<std::int32_t>(index);
  }
  contacts_.pop_back();
}

// The solver keeps a speculative point's gap from closing along the normal the manifold had at
// the start of the step: a linearisation, exact for bodies that approach head on, wrong for
// bodies that pass each other or meet at a glance. Two bullets crossing paths diagonally, 3 m
// apart with 220 m/s of approach along that normal, were pushed apart (and bounced, restitution
// 0.8) though their discs never came closer than 1.1 m; two passing side by side 5 cm apart
// bounced off each other; two grazing ones bounced back head on. So the manifold of a fast pair
// (margin beyond kSpeculativeDistance) whose every point is still farther than that, and whose
// linearised gap closes within the step, is taken where the pair actually meets: both bodies
// moved at their present velocities (gravity adds 1.4 mm in a 60 Hz step, well inside the
// 2 cm target), the time of impact found, and the manifold made there. Its points are carried
// back to the start of the step (anchors turned back with each body, the separation widened by
// what the approach closes until the impact), so the solver's linearised gap closes at the
// time of impact along the normal of the impact, and restitution reverses the approach along
// that normal. A pair that never comes within kSpeculativeDistance gets no points: a ghost.
// Frames as in narrowphase(): A's origin at zero.
void World::foresee(Manifold& m, const ShapeRecord& ra, const Transform& xfA, const ShapeRecord& rb,
                    const Transform& xfB, float dt) const {
  const Body& bodyA = bodies_[static_cast<std::size_t>(ra.body)];
  const Body& bodyB = bodies_[static_cast<std::size_t>(rb.body)];
  // A round body's shapes do not turn with it (as in continuous()).
  auto spin = [&](const Body& b) {
    return b.slot < 0 || b.round ? 0.0f : v_[3 * static_cast<std::size_t>(b.slot) + 2];
  };
  const Vec2 vA = velocityOf(bodyA), vB = velocityOf(bodyB);
  const float wA = spin(bodyA), wB = spin(bodyB);
  const Vec2 cA = apply(xfA, bodyA.localCenter), cB = apply(xfB, bodyB.localCenter);
  // (Every point is apart by more than kSpeculativeDistance: the caller checks.)
  bool closes = false;
  for (int k = 0; k < m.pointCount; ++k) {
    const ManifoldPoint& mp = m.points[k];
    const Vec2 dv = vB + cross(wB, mp.point - cB) - vA - cross(wA, mp.point - cA);
    closes = closes || mp.separation + dt * dot(dv, m.normal) <= kSpeculativeDistance;
  }
  if (!closes) return;  // the solver will not push these points: nothing to correct

  float t = 0.0f;
  if (bodyA.round && bodyB.round && ra.shape.type == ShapeType::circle &&
      rb.shape.type == ShapeType::circle) {
    // Exact for two discs: where they touch.
    const CastOutput cast =
        sweptCircles(cA, ra.shape.circle.radius, dt * vA, cB, rb.shape.circle.radius, dt * vB);
    if (!cast.hit) {
      m.pointCount = 0;
      return;
    }
    t = cast.fraction;
  } else {
    // Round bodies swept without turning (their angle is then 0 in the sweep: no sine and
    // cosine per iteration; their geometry does not depend on it).
    auto sweepOf = [&](const Body& b, Vec2 c, Vec2 v, float w) {
      const float a = b.round ? 0.0f : b.angle;
      return Sweep{b.localCenter, c, c + dt * v, a, a + dt * w};
    };
    const ToiOutput toi =
        timeOfImpact(makeProxy(ra.shape), sweepOf(bodyA, cA, vA, wA), makeProxy(rb.shape),
                     sweepOf(bodyB, cB, vB, wB), 1.0f, kLinearSlop);
    if (toi.state == ToiState::separated) {
      m.pointCount = 0;
      return;
    }
    if (toi.state != ToiState::hit) return;  // no better answer: the start's manifold
    t = toi.fraction;
  }
  if (t <= 0.0f) return;

  // Each body at the time of impact, turned by w t dt (round bodies keep their rotation).
  const float turnA = t * dt * wA, turnB = t * dt * wB;
  const Rot qA = turnA == 0.0f ? xfA.q : Rot::fromAngle(bodyA.angle + turnA);
  const Rot qB = turnB == 0.0f ? xfB.q : Rot::fromAngle(bodyB.angle + turnB);
  const Vec2 cAt = cA + (t * dt) * vA, cBt = cB + (t * dt) * vB;
  const Transform xfAt{cAt - rotate(qA, bodyA.localCenter), qA};
  const Transform xfBt{cBt - rotate(qB, bodyB.localCenter), qB};
  // Apart by about kSpeculativeDistance there (the time of impact's tolerance is a quarter
  // slop): twice that keeps its points.
  const Manifold at = collide(ra.shape, xfAt, rb.shape, xfBt, 2.0f * kSpeculativeDistance);
  if (at.pointCount == 0) return;
  auto turnBack = [](float turn, Vec2 r) {
    return turn == 0.0f ? r : rotate(Rot::fromAngle(-turn), r);
  };
  m.normal = at.normal;
  m.pointCount = at.pointCount;
  for (int k = 0; k < at.pointCount; ++k) {
    const ManifoldPoint& hit = at.points[k];
    ManifoldPoint& mp = m.points[k];
    // Lever arms at the start: the impact's, turned back with each body.
    const Vec2 rA = turnBack(turnA, hit.point - cAt), rB = turnBack(turnB, hit.point - cBt);
    mp.point = hit.point;  // where they meet (events report it)
    mp.anchorA = cA + rA;
    mp.anchorB = cB + rB - xfB.p;
    mp.id = hit.id;
    // Widened by the approach until the impact: the solver's gap closes to the impact's there.
    const float vn = dot(vB + cross(wB, rB) - vA - cross(wA, rA), at.normal);
    mp.separation = hit.separation - t * dt * vn;
  }
}

void World::narrowphase(float dt) {
  // Nothing awake: every contact is as it was when its bodies fell asleep (the loop below
  // would skip each one).
  if (awakeCount_ == 0) return;
  // How far a shape's surface can move towards anything this step: its body's speed plus its
  // turning speed times its reach from the centre of mass.
  auto reachSpeed = [&](const ShapeRecord& r) {
    const Body& b = bodies_[static_cast<std::size_t>(r.body)];
    if (b.slot < 0) return 0.0f;
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    const float reach = length(r.bound.center - b.localCenter) + r.bound.radius;
    return length(Vec2{v_[i], v_[i + 1]}) + std::fabs(v_[i + 2]) * reach;
  };
  // Back to front: a destroyed contact is replaced by the last one, already updated.
  for (std::size_t i = contacts_.size(); i-- > 0;) {
    Contact& c = contacts_[i];
    const ShapeRecord& ra = shapes_[static_cast<std::size_t>(c.shapeA)];
    const ShapeRecord& rb = shapes_[static_cast<std::size_t>(c.shapeB)];
    Body& bodyA = bodies_[static_cast<std::size_t>(ra.body)];
    Body& bodyB = bodies_[static_cast<std::size_t>(rb.body)];
    // Nothing awake on either side: the contact is as it was when they fell asleep.
    if (!awake(bodyA) && !awake(bodyB)) continue;
    if (!overlaps(broadphase_.fatAABB(ra.proxy), broadphase_.fatAABB(rb.proxy))) {
      destroyContact(i);
      continue;
    }
    // In A's frame translated to A's origin, B placed by the difference of the two origins
    // taken in double: far from the world origin the float origins are too coarse (1 mm apart
    // 10 km out) for the separations a resting contact needs.
    // (By component: as two arrays the origins went through memory, and their difference was
    // one vector load of two scalars just stored, a store-forwarding stall, a fifth of this loop.)
    const Transform xfA{{}, bodyA.xf.q};
    const Transform xfB{{static_cast<float>(preciseOrigin(bodyB, 0) - preciseOrigin(bodyA, 0)),
                         static_cast<float>(preciseOrigin(bodyB, 1) - preciseOrigin(bodyA, 1))},
                        bodyB.xf.q};
    const Manifold old = c.manifold;
    const float oldNormal[2] = {c.normalImpulse[0], c.normalImpulse[1]};
    const float oldTangent[2] = {c.tangentImpulse[0], c.tangentImpulse[1]};
    const float margin = def_.continuous
                             ? kSpeculativeDistance + dt * (reachSpeed(ra) + reachSpeed(rb))
                             : kSpeculativeDistance;
    // Constructed in place: the manifold function's result goes straight into the contact.
    // Assigned, it was built in a temporary and copied with wide loads of the narrow stores just
    // made (a store-forwarding stall, a sixth of this loop).
    // (Placement new, not std::construct_at, whose forwarding reference makes a temporary.)
    ::new (static_cast<void*>(&c.manifold)) Manifold(collide(ra.shape, xfA, rb.shape, xfB, margin));
    // Only apart beyond the usual margin (every point) is there anything to foresee; resting
    // and sliding contacts, nearly all of a pile's, stop here (the call was 2% of a pyramid).
    const Manifold& m = c.manifold;
    if (margin > kSpeculativeDistance && m.pointCount > 0 &&
        m.points[0].separation > kSpeculativeDistance &&
        (m.pointCount == 1 || m.points[1].separation > kSpeculativeDistance))
      foresee(c.manifold, ra, xfA, rb, xfB, dt);
    for (int k = 0; k < c.manifold.pointCount; ++k)
      c.manifold.points[k].point += bodyA.xf.p;
    // Warm start: a point keeps last step's impulses when the same features touch.
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      c.normalImpulse[k] = c.tangentImpulse[k] = 0.0f;
      for (int j = 0; j < old.pointCount; ++j)
        if (old.points[j].id == c.manifold.points[k].id) {
          c.normalImpulse[k] = oldNormal[j];
          c.tangentImpulse[k] = oldTangent[j];
        }
    }
    const bool was = c.touching;
    c.touching = c.manifold.pointCount > 0;
    // Touching something awake wakes a sleeping body's island.
    if (c.touching) {
      if (bodyA.island >= 0) wakeBody(bodyA);
      if (bodyB.island >= 0) wakeBody(bodyB);
    }
    if (c.touching && !was) {
      // How fast the surfaces close at the first point, from the velocities before the solve.
      const ManifoldPoint& mp = c.manifold.points[0];
      const Body& a = bodies_[static_cast<std::size_t>(ra.body)];
      const Body& b = bodies_[static_cast<std::size_t>(rb.body)];
      auto pointVelocity = [&](const Body& body) {
        if (body.slot < 0) return Vec2{};
        const auto k = 3 * static_cast<std::size_t>(body.slot);
        return Vec2{v_[k], v_[k + 1]} + cross(v_[k + 2], mp.point - center(body));
      };
      const float approach = -dot(pointVelocity(b) - pointVelocity(a), c.manifold.normal);
      const ShapeId idA = shapeId(c.shapeA), idB = shapeId(c.shapeB);
      events_.begin.push_back({idA, idB, mp.point, c.manifold.normal, approach});
      if (approach > def_.hitEventThreshold)
        events_.hit.push_back({idA, idB, mp.point, c.manifold.normal, approach});
    } else if (!c.touching && was) {
      events_.end.push_back({shapeId(c.shapeA), shapeId(c.shapeB)});
    }
  }
}

// ------------------------------------------------------------------------------------ solve

namespace {

// Impulse P at one contact point: -P on A, +P on B.
template <class Constraint, class Point>
void applyImpulse(const Constraint& cc, const Point& p, Vec2 P, Vec2& vA, float& wA, Vec2& vB,
                  float& wB) {
  vA -= cc.invMassA * P;
  wA -= cc.invIA * cross(p.rA, P);
  vB += cc.invMassB * P;
  wB += cc.invIB * cross(p.rB, P);
}

}  // namespace

void World::accelerations(std::span<const double> q, std::span<const float> v, float t,
                          std::span<float> a) {
  // The step's constant part (gathered in solve(): gravity, forces, torques), then the fields.
  std::copy_n(baseAccel_.begin(), 3 * static_cast<std::size_t>(awakeCount_), a.begin());
  if (!fields_.empty()) {
    ForceStage stage(*this, q, v, a, t);
    for (ForceField& field : fields_)
      field(stage);
  }
}

template <class Solve>
void World::forEachConstraint(Solve&& solve) {
  for (ContactConstraint& cc : bouncy_) {
    Vec2 vA{}, vB{};
    float wA = 0.0f, wB = 0.0f;
    const std::size_t iA = 3 * static_cast<std::size_t>(std::max(cc.slotA, 0));
    const std::size_t iB = 3 * static_cast<std::size_t>(std::max(cc.slotB, 0));
    if (cc.slotA >= 0) vA = {v_[iA], v_[iA + 1]}, wA = v_[iA + 2];
    if (cc.slotB >= 0) vB = {v_[iB], v_[iB + 1]}, wB = v_[iB + 2];
    solve(cc, vA, wA, vB, wB);
    if (cc.slotA >= 0) v_[iA] = vA.x, v_[iA + 1] = vA.y, v_[iA + 2] = wA;
    if (cc.slotB >= 0) v_[iB] = vB.x, v_[iB + 1] = vB.y, v_[iB + 2] = wB;
  }
}

void World::applyRestitution() {
  const float threshold = def_.restitutionThreshold;
  forEachConstraint([&](ContactConstraint& cc, Vec2& vA, float& wA, Vec2& vB, float& wB) {
    if (cc.restitution == 0.0f) return;
    const Vec2 n = cc.normal;
    for (int k = 0; k < cc.pointCount; ++k) {
      ConstraintPoint& p = cc.points[k];
      // Only points that were approaching fast enough and that the solver pushed, and that
      // were not already overlapping past the slop when the step began: an impact, not an
      // overlap the push-out is resolving. (A circle born inside two overlapping static boxes
      // is pushed both ways at once; bouncing it off both faces doubled its speed every few
      // steps.)
      if (p.relativeVelocity > -threshold || p.maxNormalImpulse == 0.0f) continue;
      if (p.baseSeparation < -kLinearSlop) continue;
      const float vn = dot(vB - vA, n) + wB * p.rnB - wA * p.rnA;
      const float impulse = -p.normalMass * (vn + cc.restitution * p.relativeVelocity);
      const float total = std::max(p.normalImpulse + impulse, 0.0f);
      const float applied = total - p.normalImpulse;
      p.normalImpulse = total;
      p.maxNormalImpulse = std::max(p.maxNormalImpulse, applied);
      const Vec2 P = applied * n;
      applyImpulse(cc, p, P, vA, wA, vB, wB);
    }
  });
}

void World::solve(float dt) {
  const auto slots = static_cast<std::size_t>(awakeCount_);
  // Prepare: one constraint per touching contact with an awake side, anchors from the centres of
  // mass. The solver colours them first (it needs only their bodies), then each constraint is
  // prepared straight into its lane.
  constraintSources_.clear();
  constraintBodies_.clear();
  bouncy_.clear();
  bouncyIndex_.clear();
  profile_.colours = profile_.overflow = 0;
  if (slots == 0) return;  // nothing awake: nothing to solve
  for (std::size_t ci = 0; ci < contacts_.size(); ++ci) {
    const Contact& c = contacts_[ci];
    if (!c.touching) continue;
    const std::int32_t bodyA = shapes_[static_cast<std::size_t>(c.shapeA)].body;
    const std::int32_t bodyB = shapes_[static_cast<std::size_t>(c.shapeB)].body;
    const Body& a = bodies_[static_cast<std::size_t>(bodyA)];
    const Body& b = bodies_[static_cast<std::size_t>(bodyB)];
    const std::int32_t slotA = awake(a) ? a.slot : -1, slotB = awake(b) ? b.slot : -1;
    if (slotA < 0 && slotB < 0) continue;  // asleep against asleep or static
    constraintSources_.push_back({static_cast<std::int32_t>(ci), bodyA, bodyB});
    constraintBodies_.push_back({slotA, slotB, a.invMass > 0.0f || a.invInertia > 0.0f,
                                 b.invMass > 0.0f || b.invInertia > 0.0f, c.manifold.pointCount});
  }
  contactSolver_.prepare(constraintBodies_, static_cast<int>(slots));
  profile_.colours = contactSolver_.colourCount();
  profile_.overflow = contactSolver_.overflowCount();

  for (std::size_t i = 0; i < constraintSources_.size(); ++i) {
    const ConstraintSource& source = constraintSources_[i];
    const auto ci = static_cast<std::size_t>(source.contact);
    const Contact& c = contacts_[ci];
    const Body& a = bodies_[static_cast<std::size_t>(source.bodyA)];
    const Body& b = bodies_[static_cast<std::size_t>(source.bodyB)];
    ContactConstraint cc;
    cc.contact = source.contact;
    cc.slotA = constraintBodies_[i].slotA;
    cc.slotB = constraintBodies_[i].slotB;
    // A sleeping body stays put for this step: it counts as static (and the solver's null body,
    // which static sides share, must never be moved).
    cc.invMassA = cc.slotA >= 0 ? a.invMass : 0.0f;
    cc.invIA = cc.slotA >= 0 ? a.invInertia : 0.0f;
    cc.invMassB = cc.slotB >= 0 ? b.invMass : 0.0f;
    cc.invIB = cc.slotB >= 0 ? b.invInertia : 0.0f;
    cc.normal = c.manifold.normal;
    cc.friction = c.friction;
    cc.restitution = c.restitution;
    cc.pointCount = c.manifold.pointCount;
    const Vec2 offsetA = rotate(a.xf.q, a.localCenter), offsetB = rotate(b.xf.q, b.localCenter);
    const Vec2 vA = cc.slotA >= 0 ? Vec2{v_[3 * static_cast<std::size_t>(cc.slotA)],
                                         v_[3 * static_cast<std::size_t>(cc.slotA) + 1]}
                                  : Vec2{};
    const float wA = cc.slotA >= 0 ? v_[3 * static_cast<std::size_t>(cc.slotA) + 2] : 0.0f;
    const Vec2 vB = cc.slotB >= 0 ? Vec2{v_[3 * static_cast<std::size_t>(cc.slotB)],
                                         v_[3 * static_cast<std::size_t>(cc.slotB) + 1]}
                                  : Vec2{};
    const float wB = cc.slotB >= 0 ? v_[3 * static_cast<std::size_t>(cc.slotB) + 2] : 0.0f;
    for (int k = 0; k < cc.pointCount; ++k) {
      const ManifoldPoint& mp = c.manifold.points[k];
      ConstraintPoint& p = cc.points[k];
      p.rA = mp.anchorA - offsetA;
      p.rB = mp.anchorB - offsetB;
      p.baseSeparation = mp.separation;
      p.normalImpulse = c.normalImpulse[k];
      p.tangentImpulse = c.tangentImpulse[k];
      p.maxNormalImpulse = 0.0f;
      const Vec2 dv = (vB + cross(wB, p.rB)) - (vA + cross(wA, p.rA));
      p.relativeVelocity = dot(dv, cc.normal);
    }
    contactSolver_.set(i, cc);
    if (cc.restitution != 0.0f) {
      bouncy_.push_back(cc);
      bouncyIndex_.push_back(static_cast<std::int32_t>(i));
    }
  }
  contactSolver_.computeMasses();

  startCenter_.resize(2 * slots);
  startAngle_.resize(slots);
  slotRound_.resize(slots);
  baseAccel_.resize(3 * slots);
  damped_.clear();
  solverBodies_.assign(slots + 1, SolverBody{});  // the last: the null body
  for (std::size_t s = 0; s < slots; ++s) {
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    startCenter_[2 * s] = q_[3 * s];
    startCenter_[2 * s + 1] = q_[3 * s + 1];
    startAngle_[s] = q_[3 * s + 2];
    slotRound_[s] = b.round;
    if (b.linearDamping > 0.0f || b.angularDamping > 0.0f)
      damped_.push_back(static_cast<std::int32_t>(s));
    // Gravity, force and torque do not change during the step: gathered once here, copied out
    // at every stage (the per-stage walk over the bodies was 8% of an arena step).
    float* a = &baseAccel_[3 * s];
    if (b.type == BodyType::dynamicBody) {
      a[0] = b.gravityScale * def_.gravity.x + b.invMass * b.force.x;
      a[1] = b.gravityScale * def_.gravity.y + b.invMass * b.force.y;
      a[2] = b.invInertia * b.torque;
    } else {
      a[0] = a[1] = a[2] = 0.0f;
    }
  }

  const float h = dt / static_cast<float>(def_.substeps);
  const ContactSoftness soft =
      ContactSoftness::make(h, def_.contactHertz, def_.contactDampingRatio, def_.maxPushoutSpeed);
  auto accel = [this](std::span<const double> q, std::span<const float> v, float t,
                      std::span<float> a) { accelerations(q, v, t, a); };
  // The awake bodies' velocities into solver bodies (v and w; the rest as it is).
  auto loadVelocities = [&](std::vector<SolverBody>& to) {
    for (std::size_t s = 0; s < slots; ++s) {
      to[s].v = {v_[3 * s], v_[3 * s + 1]};
      to[s].w = v_[3 * s + 2];
    }
  };
  for (int sub = 0; sub < def_.substeps; ++sub) {
    const float t = static_cast<float>(time_) + static_cast<float>(sub) * h;
    // Free motion by the world's integrator, then damping (implicit, unconditionally stable).
    const std::span<double> q(q_.data(), 3 * slots);
    const std::span<float> v(v_.data(), 3 * slots);
    // Restitution reverses the approach speed at the impact, read from the velocity the
    // integrator moves the bodies with over the substep: semi-implicit Euler moves them with the
    // velocity after the substep's forces (taken below), explicit Euler with the one before;
    // Verlet and RK4 with one between the two, of which the one before is the lower bound (the
    // one after bounced a ball dropped from 10 m to 10.035 m at restitution 1).
    const bool bouncy = !bouncy_.empty();
    const bool moveWithNew = def_.integrator == Integrator::semiImplicitEuler;
    if (bouncy && !moveWithNew) {
      freeMotion_.assign(slots + 1, SolverBody{});
      loadVelocities(freeMotion_);
    }
    integrate<float, double>(def_.integrator, q, v, t, h, accel, scratch_);
    // (Only the damped bodies: reading every awake body's damping was a cache miss per body and
    // substep: the 5000-circle arena 283 -> 271 ms for its run, 4%.)
    for (const std::int32_t slot : damped_) {
      const auto s = static_cast<std::size_t>(slot);
      const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
      if (b.linearDamping > 0.0f) {
        const float f = 1.0f / (1.0f + h * b.linearDamping);
        v_[3 * s] *= f;
        v_[3 * s + 1] *= f;
      }
      if (b.angularDamping > 0.0f) v_[3 * s + 2] *= 1.0f / (1.0f + h * b.angularDamping);
    }
    freeV_.assign(v.begin(), v.end());
    // Warm start with the impulses carried so far, then solve with the soft bias.
    loadVelocities(solverBodies_);
    // (Before any warm start: see warmStartBatch.)
    if (bouncy && moveWithNew) freeMotion_.assign(solverBodies_.begin(), solverBodies_.end());
    contactSolver_.warmStart(solverBodies_, bouncy ? std::span<const SolverBody>{freeMotion_}
                                                   : std::span<const SolverBody>{});
    // Symmetric Gauss-Seidel: the relax pass sweeps the colours the other way from the solve
    // pass, and each substep starts the way the last one ended.
    const bool backward = sub % 2 == 1;
    contactSolver_.solve(solverBodies_, soft, true, backward);
    // Positions: the free motion plus what the contacts changed in the velocity (read from the
    // solver's bodies; v_ takes them after the relax pass).
    reserveTurns(slots);
    for (std::size_t s = 0; s < slots; ++s) {
      SolverBody& sb = solverBodies_[s];
      // Kept in registers: read back from q_, the three double stores would stall the loads
      // (a third of the solve in the 1000-circle arena).
      const double x = q_[3 * s] + h * (sb.v.x - freeV_[3 * s]);
      const double y = q_[3 * s + 1] + h * (sb.v.y - freeV_[3 * s + 1]);
      const double a = q_[3 * s + 2] + h * (sb.w - freeV_[3 * s + 2]);
      q_[3 * s] = x;
      q_[3 * s + 1] = y;
      q_[3 * s + 2] = a;
      sb.dp = {static_cast<float>(x - startCenter_[2 * s]),
               static_cast<float>(y - startCenter_[2 * s + 1])};
      // Bodies that do not turn (fixed rotation, or just not spinning) cost no trigonometry,
      // and neither do round ones: the anchors rotate with the body so that a turning body's
      // corners move, but a circle about the centre of mass has no corners, and rotating its
      // anchor would only tilt the separation estimate by r (1 - cos turned).
      const auto turned = static_cast<float>(a - startAngle_[s]);
      sb.dq = Rot{};
      if (turned != 0.0f && !slotRound_[s]) {
        turnAngles_.push_back(turned);
        turnOwners_.push_back(static_cast<std::int32_t>(s));
      }
    }
    applyTurns([&](std::int32_t s, Rot dq) { solverBodies_[static_cast<std::size_t>(s)].dq = dq; });
    // Relax: the same solve without the push-out bias, so separating bodies keep no speed
    // from it (the bias pushes positions apart; relax removes its velocity).
    contactSolver_.solve(solverBodies_, soft, false, !backward);
    for (std::size_t s = 0; s < slots; ++s) {
      v_[3 * s] = solverBodies_[s].v.x;
      v_[3 * s + 1] = solverBodies_[s].v.y;
      v_[3 * s + 2] = solverBodies_[s].w;
    }
  }
  // The impulses back into the contacts, for the next step's warm start; restitution first, for
  // the constraints that have it (in the constraints' order).
  for (std::size_t i = 0; i < constraintSources_.size(); ++i) {
    Contact& c = contacts_[static_cast<std::size_t>(constraintSources_[i].contact)];
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      const SolvedPoint p = contactSolver_.solved(i, k);
      c.normalImpulse[k] = p.normalImpulse;
      c.tangentImpulse[k] = p.tangentImpulse;
    }
  }
  if (bouncy_.empty()) return;
  for (std::size_t j = 0; j < bouncy_.size(); ++j) {
    ContactConstraint& cc = bouncy_[j];
    for (int k = 0; k < cc.pointCount; ++k)
      cc.points[k] = contactSolver_.point(static_cast<std::size_t>(bouncyIndex_[j]), k);
  }
  applyRestitution();
  for (const ContactConstraint& cc : bouncy_) {
    Contact& c = contacts_[static_cast<std::size_t>(cc.contact)];
    for (int k = 0; k < cc.pointCount; ++k)
      c.normalImpulse[k] = cc.points[k].normalImpulse;
  }
}

// ---------------------------------------------------------------------------------- sensors

void World::destroySensorPair(std::size_t index) {
  SensorPair& sp = sensorPairs_[index];
  if (sp.overlapping) sensorEvents_.end.push_back({shapeId(sp.sensor), shapeId(sp.visitor)});
  sensorIndex_.erase(pairKey(sp.sensor, sp.visitor));
  if (index + 1 != sensorPairs_.size()) {
    sensorPairs_[index] = sensorPairs_.back();
    sensorIndex_[pairKey(sensorPairs_[index].sensor, sensorPairs_[index].visitor)] =
        static_cast<std::int32_t>(index);
  }
  sensorPairs_.pop_back();
}

void World::updateSensors() {
  // Runs after the refit: transforms are the step's end; the awake bodies' slots still hold
  // where they started (startCenter_, startAngle_).
  for (std::size_t k = sensorPairs_.size(); k-- > 0;) {
    SensorPair& sp = sensorPairs_[k];
    const ShapeRecord& sensor = shapes_[static_cast<std::size_t>(sp.sensor)];
    const ShapeRecord& visitor = shapes_[static_cast<std::size_t>(sp.visitor)];
    const Body& sb = bodies_[static_cast<std::size_t>(sensor.body)];
    const Body& vb = bodies_[static_cast<std::size_t>(visitor.body)];
    if (!awake(sb) && !awake(vb)) continue;  // nothing moved
    const bool now = testOverlap(sensor.shape, sb.xf, visitor.shape, vb.xf);
    bool passed = false;
    if (!now && !sp.overlapping && awake(vb)) {
      // Not in it before or after: did the visitor's path cross it? (Its translation only;
      // the sensor at its end transform.)
      const Sweep sweep = stepSweep(vb);
      const Vec2 move = sweep.c2 - sweep.c1;
      if (move != Vec2{}) {
        const CastOutput cast = shapeCast(makeProxy(visitor.shape), sweepTransform(sweep, 0.0f),
                                          move, makeProxy(sensor.shape), sb.xf);
        passed = cast.hit;
      }
    }
    const ShapeId sid = shapeId(sp.sensor), vid = shapeId(sp.visitor);
    if ((now && !sp.overlapping) || passed) sensorEvents_.begin.push_back({sid, vid});
    if ((!now && sp.overlapping) || passed) sensorEvents_.end.push_back({sid, vid});
    sp.overlapping = now;
    if (!now && !overlaps(broadphase_.fatAABB(sensor.proxy), broadphase_.fatAABB(visitor.proxy)))
      destroySensorPair(k);
  }
}

// ------------------------------------------------------------------------------- continuous

void World::continuous() {
  // Speculative contacts cover what was known at the start of the step; a fast body deflected
  // during the step (by another body, or a bounce) can still reach static geometry it had no
  // contact with. Such bodies are swept from where they started to where they ended against
  // the static shapes their path touches, and stopped at the first time of impact (the
  // speculative contact of the next step then bounces them). Bodies that moved less than half
  // their smallest extent cannot pass through anything and are skipped.
  //
  // Bullets are swept against moving bodies too, each along its own motion of the step,
  // bullets included (two bullets crossing paths mid-step meet; Box2D v3 skips bullet pairs).
  // A bullet that hits a moving body stops at the time of impact, and so does the body it hit:
  // both are where they touched, and the next step's contact makes them respond there.
  // Bodies are taken in slot order; one already stopped sweeps only as far as it went.
  auto sweepOf = [&](const Body& body) -> Sweep {
    if (!awake(body)) return {{}, body.xf.p, body.xf.p, body.angle, body.angle};
    return stepSweep(body);
  };
  // Back along the step's motion to the fraction t of it, in double like the positions.
  auto placeAt = [&](const Body& body, float t) {
    const auto s = static_cast<std::size_t>(body.slot);
    const std::size_t i = 3 * s;
    for (std::size_t k = 0; k < 2; ++k)
      q_[i + k] = startCenter_[2 * s + k] + t * (q_[i + k] - startCenter_[2 * s + k]);
    q_[i + 2] = startAngle_[s] + t * (q_[i + 2] - startAngle_[s]);
  };
  // The sweep a body's shapes follow: a round body with its centre of mass at its origin turns
  // none of its shapes and its transform does not depend on its angle, so it is swept without
  // turning: the same geometry, with no sine and cosine per transform (those were a tenth of the
  // bullets' step: every time of impact iteration builds two transforms).
  auto shapeSweep = [&](const Body& body, Sweep sweep) {
    if (body.round && body.localCenter == Vec2{}) sweep.a1 = sweep.a2 = 0.0f;
    return sweep;
  };
  auto fast = [&](const Body& b, const Sweep& sweep) {
    if (b.type != BodyType::dynamicBody || b.shapes.empty()) return false;
    const float motion = length(sweep.c2 - sweep.c1) + std::fabs(sweep.a2 - sweep.a1) * b.maxExtent;
    return motion >= 0.5f * b.minExtent;
  };
  // A shape's path: the union of its boxes where the body starts and ends (xf1, xf2).
  auto pathOf = [&](const ShapeRecord& r, const Transform& xf1, const Transform& xf2) {
    return unionOf(computeAABB(r.shape, xf1), computeAABB(r.shape, xf2));
  };
  // Candidates without the broadphase: a shape whose path stays inside its fat AABB (a steady
  // mover's box is stretched along its motion to hold the next step's sweep) can only meet
  // shapes whose fat AABBs overlap its own, and every such pair has a contact here (pairs are
  // updated at the start of the step; the refit comes after). So its candidates are its
  // contacts' other shapes, those whose fat AABB meets the path: the query's set, from a list
  // built in one pass over the contacts. 500 bullets' queries were a fifth of their arena's
  // step. Segments and chain links are left to the query: a pair of them has no contact.
  const std::size_t slots = static_cast<std::size_t>(awakeCount_);
  if (contactSwept_.size() < shapes_.size()) contactSwept_.resize(shapes_.size(), -1);
  sweptShapes_.clear();
  fastSlots_.clear();
  for (std::size_t s = 0; s < slots; ++s) {
    const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const Sweep full = sweepOf(b);
    if (!fast(b, full)) continue;
    fastSlots_.push_back(static_cast<std::int32_t>(s));
    const Sweep sweep = shapeSweep(b, full);
    const Transform xf1 = sweepTransform(sweep, 0.0f), xf2 = sweepTransform(sweep, 1.0f);
    for (std::int32_t own : b.shapes) {
      const ShapeRecord& mine = shapes_[static_cast<std::size_t>(own)];
      if (mine.isSensor || mine.shape.type == ShapeType::segment ||
          mine.shape.type == ShapeType::chainSegment ||
          !broadphase_.fatAABB(mine.proxy).contains(pathOf(mine, xf1, xf2)))
        continue;
      contactSwept_[static_cast<std::size_t>(own)] = static_cast<std::int32_t>(sweptShapes_.size());
      sweptShapes_.push_back(own);
    }
  }
  // The lists, by counting sort on the swept shape (in contact order within each).
  candidateStart_.assign(sweptShapes_.size() + 1, 0);
  candidates_.clear();
  if (!sweptShapes_.empty()) {
    auto eachCandidate = [&](auto&& visit) {
      for (const Contact& c : contacts_) {
        const std::int32_t a = contactSwept_[static_cast<std::size_t>(c.shapeA)];
        const std::int32_t b = contactSwept_[static_cast<std::size_t>(c.shapeB)];
        if (a >= 0) visit(a, c.shapeB);
        if (b >= 0) visit(b, c.shapeA);
      }
    };
    eachCandidate([&](std::int32_t k, std::int32_t) { ++candidateStart_[k + 1]; });
    for (std::size_t k = 1; k < candidateStart_.size(); ++k)
      candidateStart_[k] += candidateStart_[k - 1];
    candidates_.resize(static_cast<std::size_t>(candidateStart_.back()));
    fillCursor_.assign(candidateStart_.begin(), candidateStart_.end() - 1);
    eachCandidate([&](std::int32_t k, std::int32_t other) {
      candidates_[static_cast<std::size_t>(fillCursor_[static_cast<std::size_t>(k)]++)] = other;
    });
  }

  // In slot order, as found above; a body an earlier one stopped sweeps only as far as it went
  // (and may no longer be fast).
  for (std::int32_t s : fastSlots_) {
    Body& b = bodies_[static_cast<std::size_t>(slotBody_[static_cast<std::size_t>(s)])];
    const Sweep full = sweepOf(b);
    if (!fast(b, full)) continue;
    const Sweep sweep = shapeSweep(b, full);
    const Transform xf1 = sweepTransform(sweep, 0.0f), xf2 = sweepTransform(sweep, 1.0f);
    float first = 1.0f;
    std::int32_t hitBody = -1;  // a moving body hit first, if any
    for (std::int32_t own : b.shapes) {
      const ShapeRecord& mine = shapes_[static_cast<std::size_t>(own)];
      if (mine.isSensor) continue;
      const ShapeProxy proxy = makeProxy(mine.shape);
      const AABB path = pathOf(mine, xf1, xf2);
      auto visit = [&](std::int32_t shape) {
        const ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
        if (r.isSensor || r.body == mine.body) return true;
        const Body& ob = bodies_[static_cast<std::size_t>(r.body)];
        const bool moving = ob.type != BodyType::staticBody;
        if (moving && !b.bullet) return true;
        const Sweep otherSweep = shapeSweep(ob, sweepOf(ob));
        const ShapeProxy otherProxy = makeProxy(r.shape);
        const ToiOutput toi = timeOfImpact(proxy, sweep, otherProxy, otherSweep, first);
        if (toi.state != ToiState::hit || toi.fraction >= first) return true;
        // Already touching at the start (sliding along a wall, or where the last step's impact
        // left it: within the tolerance of the target separation, a hit at fraction 0): the
        // contact handles it. Stopped there instead, a fast body moving away from a wall it
        // was stopped at stayed frozen at the wall step after step, its velocity growing.
        // Unless the step took it into a static shape deeper than the slop: another contact
        // solved after the wall's pushed it in (a bullet at a wall, deflected into it by a
        // ball wedged against the same wall, went 13 cm in and out of the arena at 1000 m/s);
        // it then stays where it started, and the next step's contact stops it there.
        if (toi.fraction == 0.0f && (moving || dot(sweep.c2 - sweep.c1, toi.normal) <= kLinearSlop))
          return true;
        // Two moving bodies already touching (a bullet that hit and rides along the body it
        // hit) stay to their contact; stopping them at the start of every step would freeze
        // both in place.
        if (moving &&
            shapeDistance(proxy, xf1, otherProxy, sweepTransform(otherSweep, 0.0f)).distance <
                2.0f * kLinearSlop)
          return true;
        first = toi.fraction;
        hitBody = moving && awake(ob) ? r.body : -1;
        return true;
      };
      const std::int32_t listed = contactSwept_[static_cast<std::size_t>(own)];
      // The list holds while the path (shortened if an earlier body stopped this one) is
      // still inside the fat AABB.
      if (listed >= 0 && broadphase_.fatAABB(mine.proxy).contains(path)) {
        for (std::int32_t k = candidateStart_[static_cast<std::size_t>(listed)];
             k < candidateStart_[static_cast<std::size_t>(listed) + 1]; ++k) {
          const std::int32_t other = candidates_[static_cast<std::size_t>(k)];
          if (overlaps(broadphase_.fatAABB(shapes_[static_cast<std::size_t>(other)].proxy), path))
            visit(other);
        }
      } else {
        broadphase_.queryAABB(path, broadphase_.filter(mine.proxy), [&](ProxyId other) {
          return visit(static_cast<std::int32_t>(broadphase_.userData(other)));
        });
      }
    }
    if (first < 1.0f) {
      if (hitBody >= 0) {
        const Body& other = bodies_[static_cast<std::size_t>(hitBody)];
        if (other.type == BodyType::dynamicBody) placeAt(other, first);
      }
      placeAt(b, first);
    }
  }
  for (std::int32_t own : sweptShapes_)
    contactSwept_[static_cast<std::size_t>(own)] = -1;
}

// ---------------------------------------------------------------------------------- queries

const World::ShapeRecord& World::shapeRecord(ShapeId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= shapes_.size() ||
      !shapes_[static_cast<std::size_t>(id.index)].alive ||
      shapes_[static_cast<std::size_t>(id.index)].generation != id.generation)
    throw std::invalid_argument("world: shape " + std::to_string(id.index) + " does not exist");
  return shapes_[static_cast<std::size_t>(id.index)];
}

BodyId World::bodyOf(ShapeId shape) const {
  const ShapeRecord& r = shapeRecord(shape);
  return {r.body, bodies_[static_cast<std::size_t>(r.body)].generation};
}

template <class Exact>
std::optional<WorldHit> World::closest(const RayCastInput& in, float radius, ProxyFilter filter,
                                       Exact&& exact) const {
  const ProxyHit h = castClosest(broadphase_, in, radius, filter, exact);
  if (!h.out.hit) return std::nullopt;
  const auto index = static_cast<std::int32_t>(broadphase_.userData(h.id));
  return WorldHit{shapeId(index), bodyOf(shapeId(index)), h.out.point, h.out.normal,
                  h.out.fraction};
}

namespace {
void checkCast(const char* what, Vec2 origin, Vec2 translation) {
  requireFinite(what, "origin", origin);
  requireFinite(what, "translation", translation);
}
}  // namespace

CastOutput World::rayAgainst(ProxyId proxy, const RayCastInput& ray) const {
  const ShapeRecord& r = shapes_[broadphase_.userData(proxy)];
  if (r.isSensor) return {};
  return rayCast(r.shape, bodies_[static_cast<std::size_t>(r.body)].xf, ray);
}

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation, ProxyFilter filter) const {
  checkCast("castRay", origin, translation);
  const RayCastInput in{origin, translation, 1.0f};
  return closest(in, 0.0f, filter,
                 [this](ProxyId id, const RayCastInput& ray) { return rayAgainst(id, ray); });
}

std::vector<WorldHit> World::castRayAll(Vec2 origin, Vec2 translation, ProxyFilter filter) const {
  checkCast("castRayAll", origin, translation);
  const RayCastInput in{origin, translation, 1.0f};
  std::vector<WorldHit> out;
  for (const ProxyHit& h :
       castAll(broadphase_, in, 0.0f, filter,
               [this](ProxyId id, const RayCastInput&ray) { return rayAgainst(id, ray); })) {
    const auto index = static_cast<std::int32_t>(broadphase_.userData(h.id));
    out.push_back(
        {shapeId(index), bodyOf(shapeId(index)), h.out.point, h.out.normal, h.out.fraction});
  }
  return out;
}

std::optional<WorldHit> World::castCircle(Vec2 center, float radius, Vec2 translation,
                                          ProxyFilter filter) const {
  checkCast("castCircle", center, translation);
  if (!(radius > 0.0f) || !std::isfinite(radius))
    fail("castCircle", "radius", "is " + std::to_string(radius) + " (must be > 0)");
  const RayCastInput in{center, translation, 1.0f};
  const ShapeProxy disc = makeProxy(&center, 1, radius);
  return closest(in, radius, filter, [&](ProxyId id, const RayCastInput&) {
    const ShapeRecord& r = shapes_[broadphase_.userData(id)];
    if (r.isSensor) return CastOutput{};
    return shapeCast(disc, Transform{}, translation, makeProxy(r.shape),
                     bodies_[static_cast<std::size_t>(r.body)].xf);
  });
}

std::vector<ShapeId> World::overlapAABB(const AABB& box, ProxyFilter filter) const {
  std::vector<ShapeId> out;
  for (ProxyId id : broadphase_.queryAABB(box, filter)) {
    const auto index = static_cast<std::int32_t>(broadphase_.userData(id));
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(index)];
    if (overlaps(computeAABB(r.shape, bodies_[static_cast<std::size_t>(r.body)].xf), box))
      out.push_back(shapeId(index));
  }
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation, ProxyFilter filter,
                                       Wake wake) {
  std::optional<WorldHit> hit = std::as_const(*this).castRay(origin, translation, filter);
  if (hit && wake == Wake::yes) wakeBody(body(hit->body));
  return hit;
}

std::vector<ShapeId> World::overlapAABB(const AABB& box, ProxyFilter filter, Wake wake) {
  std::vector<ShapeId> found = std::as_const(*this).overlapAABB(box, filter);
  if (wake == Wake::yes)
    for (ShapeId shape : found)
      wakeBody(body(bodyOf(shape)));
  return found;
}

std::vector<ShapeId> World::overlapPoint(Vec2 point, ProxyFilter filter) const {
  requireFinite("overlapPoint", "point", point);
  std::vector<ShapeId> out;
  for (ProxyId id : broadphase_.queryPoint(point, filter)) {
    const auto index = static_cast<std::int32_t>(broadphase_.userData(id));
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(index)];
    if (containsPoint(r.shape, bodies_[static_cast<std::size_t>(r.body)].xf, point))
      out.push_back(shapeId(index));
  }
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

StepAccumulator::StepAccumulator(float dt, int maxSteps) : dt_(dt), maxSteps_(maxSteps) {
  if (!(std::isfinite(dt) && dt > 0.0f))
    throw InvalidDefinition("StepAccumulator: dt must be finite and positive, got " +
                            std::to_string(dt));
  if (maxSteps < 1)
    throw InvalidDefinition("StepAccumulator: maxSteps must be at least 1, got " +
                            std::to_string(maxSteps));
}

int StepAccumulator::advance(World& world, double elapsedSeconds) {
  if (!(std::isfinite(elapsedSeconds) && elapsedSeconds >= 0.0))
    throw InvalidDefinition("StepAccumulator: elapsed time must be finite and not negative, got " +
                            std::to_string(elapsedSeconds));
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
