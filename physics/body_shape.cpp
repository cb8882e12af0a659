// The shapes bodies carry: creation and destruction (generational slots), mass from shapes,
// broadphase proxies, and the shape properties a game reads and changes.
#include <algorithm>
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

void checkMaterial(const char* what, float friction, float restitution) {
  requireNonNegative(what, "friction", friction);
  requireNonNegative(what, "restitution", restitution);
}

}  // namespace

// ------------------------------------------------------------------------ creation, destruction

ShapeId WorldState::createShape(BodyId bodyId, const Shape& shape, const ShapeDef& def) {
  const std::size_t bi = checked(bodyId);
  try {
    validate(shape);
  } catch (const InvalidShape& e) {
    throw InvalidDefinition(std::string("shape: ") + e.what());
  }
  requireNonNegative("shape", "density", def.density);
  checkMaterial("shape", def.friction, def.restitution);
  if (!shape.isSolid() && bodies_[bi].type == BodyType::dynamicBody)
    failDefinition("shape", "type",
                   std::string("is a ") + shapeTypeName(shape.type) +
                       ", which has no area: only static and kinematic bodies may carry it");
  std::int32_t index;
  if (!freeShapes_.empty()) {
    index = freeShapes_.back();
    freeShapes_.pop_back();
  } else {
    index = static_cast<std::int32_t>(shapes_.size());
    shapes_.emplace_back();
  }
  ShapeRecord& r = shapes_[static_cast<std::size_t>(index)];
  const std::uint32_t generation = r.generation + 1;
  r = ShapeRecord{};
  r.shape = shape;
  r.body = bodyId.index;
  r.generation = generation;
  r.alive = true;
  r.isSensor = def.isSensor;
  r.contactEvents = def.contactEvents;
  r.hitEvents = def.hitEvents;
  r.sensorEvents = def.sensorEvents;
  r.density = def.density;
  r.friction = def.friction;
  r.restitution = def.restitution;
  r.filter = def.filter;
  r.userData = def.userData;
  r.bound = computeBoundingCircle(shape);
  Body& b = bodies_[bi];
  if (b.enabled) addProxy(b, index);
  b.shapes.push_back(index);
  ++shapeCount_;
  if (b.type == BodyType::dynamicBody) {
    updateMass(b);
  } else {
    // No mass to combine: the new shape only widens the extents, which updateMass would find by
    // walking every shape of the body again (quadratic for a level's thousands of wall tiles
    // on one static body).
    if (b.shapes.size() == 1) {
      b.minExtent = std::numeric_limits<float>::max();
      b.maxExtent = 0.0f;
      b.round = true;
    }
    widenExtents(b.minExtent, b.maxExtent, shape, r.bound);
    b.round = b.round && centredCircle(shape, b.localCenter);
    r.setReach(b.localCenter);
  }
  if (b.slot >= 0) pendingRefit_.push_back(bodyId.index);
  return {index, generation};
}

void WorldState::destroyShape(ShapeId id) {
  shapeRecord(id);  // throws for a stale id
  const auto index = static_cast<std::size_t>(id.index);
  Body& b = bodies_[static_cast<std::size_t>(shapes_[index].body)];
  wakeBody(b);
  if (shapes_[index].proxy != kNullProxy) removeProxy(id.index);
  b.shapes.erase(std::find(b.shapes.begin(), b.shapes.end(), id.index));
  shapes_[index].alive = false;
  freeShapes_.push_back(id.index);
  --shapeCount_;
  updateMass(b);
  if (b.slot >= 0) pendingRefit_.push_back(shapes_[index].body);
}

// ----------------------------------------------------------------------------------- mass

bool WorldState::isRound(const Body& b) const {
  if (b.shapes.empty()) return false;
  for (std::int32_t s : b.shapes) {
    if (!centredCircle(shapes_[static_cast<std::size_t>(s)].shape, b.localCenter)) return false;
  }
  return true;
}

void WorldState::updateMass(Body& b) {
  const std::array<double, 2> origin = preciseOrigin(b);
  const Vec2 oldLocalCenter = b.localCenter;
  massProperties(b);
  lanesCurrent_ = false;  // the lanes hold the masses and the arms from the centre of mass
  if (b.slot < 0 || b.localCenter == oldLocalCenter) return;
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

void WorldState::massProperties(Body& b) {
  b.mass = b.invMass = b.inertia = b.invInertia = 0.0f;
  b.minExtent = std::numeric_limits<float>::max();
  b.maxExtent = 0.0f;
  for (std::int32_t s : b.shapes) {
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    widenExtents(b.minExtent, b.maxExtent, r.shape, r.bound);
  }
  if (b.type != BodyType::dynamicBody) {
    b.localCenter = {};
  } else {
    std::vector<MassData> parts;
    for (std::int32_t s : b.shapes) {
      const ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
      if (r.shape.isSolid() && r.density > 0.0f) parts.push_back(computeMass(r.shape, r.density));
    }
    const MassData m = combineMass(parts);
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
  }
  b.round = isRound(b);
  for (std::int32_t s : b.shapes)
    shapes_[static_cast<std::size_t>(s)].setReach(b.localCenter);
}

// ------------------------------------------------------------------------------ proxies

void WorldState::addProxy(Body& b, std::int32_t shape) {
  ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
  ProxyDef proxy;
  proxy.aabb = computeAABB(r.shape, b.xf);
  proxy.filter = r.filter;
  proxy.isStatic = b.type == BodyType::staticBody;
  proxy.userData = static_cast<std::uint64_t>(shape);
  r.proxy = broadphase_.createProxy(proxy);
}

void WorldState::addProxies(Body& b) {
  for (std::int32_t s : b.shapes)
    addProxy(b, s);
}

void WorldState::removeProxy(std::int32_t shape) {
  // Back to front: removal swaps the last one in. What the shape touched wakes.
  const std::int32_t body = shapes_[static_cast<std::size_t>(shape)].body;
  for (std::size_t c = contacts_.size(); c-- > 0;) {
    const Contact& k = contacts_[c];
    if (k.shapeA != shape && k.shapeB != shape) continue;
    const std::int32_t other =
        shapes_[static_cast<std::size_t>(k.shapeA == shape ? k.shapeB : k.shapeA)].body;
    if (k.touching && other != body) wakeBody(bodies_[static_cast<std::size_t>(other)]);
    destroyContact(c, true);
  }
  for (std::size_t k = sensorPairs_.size(); k-- > 0;)
    if (sensorPairs_[k].sensor == shape || sensorPairs_[k].visitor == shape)
      destroySensorPair(k, true);
  ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
  broadphase_.destroyProxy(r.proxy);
  r.proxy = kNullProxy;
}

void WorldState::removeProxies(Body& b) {
  // One pass over the contacts for all the body's shapes (back to front, as above).
  const auto index = static_cast<std::int32_t>(&b - bodies_.data());
  for (std::size_t c = contacts_.size(); c-- > 0;) {
    const Contact& k = contacts_[c];
    const std::int32_t bodyA = shapes_[static_cast<std::size_t>(k.shapeA)].body;
    const std::int32_t bodyB = shapes_[static_cast<std::size_t>(k.shapeB)].body;
    if (bodyA != index && bodyB != index) continue;
    if (k.touching) wakeBody(bodies_[static_cast<std::size_t>(bodyA == index ? bodyB : bodyA)]);
    destroyContact(c, true);
  }
  for (std::size_t k = sensorPairs_.size(); k-- > 0;) {
    const SensorPair& sp = sensorPairs_[k];
    if (shapes_[static_cast<std::size_t>(sp.sensor)].body == index ||
        shapes_[static_cast<std::size_t>(sp.visitor)].body == index)
      destroySensorPair(k, true);
  }
  for (std::int32_t s : b.shapes) {
    ShapeRecord& r = shapes_[static_cast<std::size_t>(s)];
    if (r.proxy == kNullProxy) continue;
    broadphase_.destroyProxy(r.proxy);
    r.proxy = kNullProxy;
  }
}

// ------------------------------------------------------------------------------ lookups

const WorldState::ShapeRecord& WorldState::shapeRecord(ShapeId id) const {
  if (id.index < 0 || static_cast<std::size_t>(id.index) >= shapes_.size() ||
      !shapes_[static_cast<std::size_t>(id.index)].alive ||
      shapes_[static_cast<std::size_t>(id.index)].generation != id.generation)
    throw std::invalid_argument("world: shape " + std::to_string(id.index) + " (generation " +
                                std::to_string(id.generation) + ") does not exist");
  return shapes_[static_cast<std::size_t>(id.index)];
}

ShapeRef WorldState::ref(std::int32_t shape) const {
  const ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
  const Body& b = bodies_[static_cast<std::size_t>(r.body)];
  return {{shape, r.generation}, {r.body, b.generation}, r.userData, b.userData};
}

// ------------------------------------------------------------------------------ the API

ShapeId World::createShape(BodyId body, const Shape& shape, const ShapeDef& def) {
  return s_->createShape(body, shape, def);
}
void World::destroyShape(ShapeId id) {
  s_->destroyShape(id);
}
bool World::isValid(ShapeId id) const {
  const auto& shapes = s_->shapes_;
  return id.index >= 0 && static_cast<std::size_t>(id.index) < shapes.size() &&
         shapes[static_cast<std::size_t>(id.index)].alive &&
         shapes[static_cast<std::size_t>(id.index)].generation == id.generation;
}
int World::shapeCount() const {
  return s_->shapeCount_;
}

std::vector<ShapeId> World::shapesOf(BodyId id) const {
  std::vector<ShapeId> out;
  for (std::int32_t shape : s_->body(id).shapes)
    out.push_back(s_->shapeId(shape));
  return out;
}
BodyId World::bodyOf(ShapeId shape) const {
  return s_->bodyId(s_->shapeRecord(shape).body);
}
ShapeRef World::ref(ShapeId shape) const {
  s_->shapeRecord(shape);
  return s_->ref(shape.index);
}

const Shape& World::shape(ShapeId id) const {
  return s_->shapeRecord(id).shape;
}
std::uint64_t World::userData(ShapeId id) const {
  return s_->shapeRecord(id).userData;
}
bool World::isSensor(ShapeId id) const {
  return s_->shapeRecord(id).isSensor;
}
ProxyFilter World::filter(ShapeId id) const {
  return s_->shapeRecord(id).filter;
}
float World::friction(ShapeId id) const {
  return s_->shapeRecord(id).friction;
}
float World::restitution(ShapeId id) const {
  return s_->shapeRecord(id).restitution;
}

void World::setUserData(ShapeId id, std::uint64_t userData) {
  s_->shapeRecord(id).userData = userData;
}

void World::setFilter(ShapeId id, ProxyFilter filter) {
  WorldState& s = *s_;
  WorldState::ShapeRecord& r = s.shapeRecord(id);
  r.filter = filter;
  if (r.proxy == kNullProxy) return;  // a disabled body's shape: taken up when it is enabled
  s.broadphase_.setFilter(r.proxy, filter);
  // The pairs the new filter refuses end now (their events come with the next step).
  auto refused = [&](std::int32_t other) {
    return !shouldCollide(filter, s.shapes_[static_cast<std::size_t>(other)].filter);
  };
  for (std::size_t c = s.contacts_.size(); c-- > 0;) {
    const WorldState::Contact& k = s.contacts_[c];
    if (k.shapeA != id.index && k.shapeB != id.index) continue;
    if (!refused(k.shapeA == id.index ? k.shapeB : k.shapeA)) continue;
    if (k.touching)
      for (std::int32_t shape : {k.shapeA, k.shapeB})
        s.wakeBody(
            s.bodies_[static_cast<std::size_t>(s.shapes_[static_cast<std::size_t>(shape)].body)]);
    s.destroyContact(c, true);
  }
  for (std::size_t k = s.sensorPairs_.size(); k-- > 0;) {
    const WorldState::SensorPair& sp = s.sensorPairs_[k];
    if (sp.sensor != id.index && sp.visitor != id.index) continue;
    if (refused(sp.sensor == id.index ? sp.visitor : sp.sensor)) s.destroySensorPair(k, true);
  }
}

void World::setFriction(ShapeId id, float friction) {
  WorldState& s = *s_;
  WorldState::ShapeRecord& r = s.shapeRecord(id);
  checkMaterial("setFriction", friction, r.restitution);
  r.friction = friction;
  s.lanesCurrent_ = false;
  for (WorldState::Contact& c : s.contacts_)
    if (c.shapeA == id.index || c.shapeB == id.index)
      c.friction = mixFriction(s.shapes_[static_cast<std::size_t>(c.shapeA)].friction,
                               s.shapes_[static_cast<std::size_t>(c.shapeB)].friction);
}

void World::setRestitution(ShapeId id, float restitution) {
  WorldState& s = *s_;
  WorldState::ShapeRecord& r = s.shapeRecord(id);
  checkMaterial("setRestitution", r.friction, restitution);
  r.restitution = restitution;
  s.lanesCurrent_ = false;
  for (WorldState::Contact& c : s.contacts_)
    if (c.shapeA == id.index || c.shapeB == id.index)
      c.restitution = mixRestitution(s.shapes_[static_cast<std::size_t>(c.shapeA)].restitution,
                                     s.shapes_[static_cast<std::size_t>(c.shapeB)].restitution);
}

void World::setSensor(ShapeId id, bool isSensor) {
  WorldState& s = *s_;
  WorldState::ShapeRecord& r = s.shapeRecord(id);
  if (r.isSensor == isSensor) return;
  WorldState::Body& b = s.bodies_[static_cast<std::size_t>(r.body)];
  // Its pairs are of the other kind now: ended, and found again by the next step.
  s.wakeBody(b);
  if (r.proxy != kNullProxy) {
    s.removeProxy(id.index);
    r.isSensor = isSensor;
    s.addProxy(b, id.index);
  } else {
    r.isSensor = isSensor;
  }
}

void World::setEventFlags(ShapeId id, bool contactEvents, bool hitEvents, bool sensorEvents) {
  WorldState::ShapeRecord& r = s_->shapeRecord(id);
  r.contactEvents = contactEvents;
  r.hitEvents = hitEvents;
  r.sensorEvents = sensorEvents;
}

}  // namespace rc
