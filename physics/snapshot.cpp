// The world's whole state as bytes and back (World::snapshot, World::restore), and its hash.
//
// Everything the next step reads is written: bodies and their slots, shapes, contacts with their
// manifolds and warm starts, sleeping islands and timers, sensor overlaps, the broadphase's
// proxies and cells, bodies waiting for their first refit, pending events. What a step rebuilds
// before reading it (the solver's lanes, scratch arrays, the profile) is not. Restoring decodes
// into a new state, checks every index and count in it, and only then replaces the world's, so a
// refused snapshot leaves the world as it was.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "physics/bytes.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {
namespace {

constexpr std::uint32_t kMagic = 0x53574352;  // "RCWS"
constexpr std::uint32_t kFormat = 1;

// The definition's fields that decide the simulation, by name (the solver's width does not:
// either width gives the same bits).
template <class Visit>
void defFields(const WorldDef& d, Visit&& visit) {
  visit("gravity.x", d.gravity.x);
  visit("gravity.y", d.gravity.y);
  visit("integrator", static_cast<float>(d.integrator));
  visit("substeps", static_cast<float>(d.substeps));
  visit("restitutionThreshold", d.restitutionThreshold);
  visit("hitEventThreshold", d.hitEventThreshold);
  visit("contactHertz", d.contactHertz);
  visit("contactDampingRatio", d.contactDampingRatio);
  visit("maxPushoutSpeed", d.maxPushoutSpeed);
  visit("continuous", d.continuous ? 1.0f : 0.0f);
  visit("enableSleep", d.enableSleep ? 1.0f : 0.0f);
  visit("timeToSleep", d.timeToSleep);
  visit("linearSleepTolerance", d.linearSleepTolerance);
  visit("angularSleepTolerance", d.angularSleepTolerance);
  visit("quarantineSpeed", d.quarantineSpeed);
  visit("bounds.lower.x", d.bounds.lower.x);
  visit("bounds.lower.y", d.bounds.lower.y);
  visit("bounds.upper.x", d.bounds.upper.x);
  visit("bounds.upper.y", d.bounds.upper.y);
}

void put(ByteWriter& w, Vec2 v) {
  w.f32(v.x);
  w.f32(v.y);
}
Vec2 getVec2(ByteReader& r) {
  const float x = r.f32();
  return {x, r.f32()};
}

void put(ByteWriter& w, const Shape& s) {
  w.u8(static_cast<std::uint8_t>(s.type));
  switch (s.type) {
    case ShapeType::circle:
      put(w, s.circle.center);
      w.f32(s.circle.radius);
      return;
    case ShapeType::box:
      put(w, s.box.center);
      put(w, s.box.halfExtents);
      return;
    case ShapeType::polygon:
      w.i32(s.polygon.count);
      w.f32(s.polygon.radius);
      put(w, s.polygon.centroid);
      put(w, s.polygon.boxHalfExtents);
      for (int i = 0; i < s.polygon.count; ++i) {
        put(w, s.polygon.vertices[i]);
        put(w, s.polygon.normals[i]);
      }
      return;
    case ShapeType::capsule:
      put(w, s.capsule.center1);
      put(w, s.capsule.center2);
      w.f32(s.capsule.radius);
      return;
    case ShapeType::segment:
      put(w, s.segment.point1);
      put(w, s.segment.point2);
      return;
    case ShapeType::chainSegment:
      put(w, s.chainSegment.ghost1);
      put(w, s.chainSegment.segment.point1);
      put(w, s.chainSegment.segment.point2);
      put(w, s.chainSegment.ghost2);
      w.boolean(s.chainSegment.oneSided);
      return;
  }
}

Shape getShape(ByteReader& r) {
  const std::uint8_t type = r.u8();
  Shape s = Circle{};
  switch (static_cast<ShapeType>(type)) {
    case ShapeType::circle: {
      Circle c;
      c.center = getVec2(r);
      c.radius = r.f32();
      s = c;
      break;
    }
    case ShapeType::box: {
      Box b;
      b.center = getVec2(r);
      b.halfExtents = getVec2(r);
      s = b;
      break;
    }
    case ShapeType::polygon: {
      Polygon p;
      p.count = r.i32();
      if (p.count < 3 || p.count > kMaxPolygonVertices) r.fail("a polygon's vertex count");
      p.radius = r.f32();
      p.centroid = getVec2(r);
      p.boxHalfExtents = getVec2(r);
      for (int i = 0; i < p.count; ++i) {
        p.vertices[i] = getVec2(r);
        p.normals[i] = getVec2(r);
      }
      s = p;
      break;
    }
    case ShapeType::capsule: {
      Capsule c;
      c.center1 = getVec2(r);
      c.center2 = getVec2(r);
      c.radius = r.f32();
      s = c;
      break;
    }
    case ShapeType::segment: {
      Segment g;
      g.point1 = getVec2(r);
      g.point2 = getVec2(r);
      s = g;
      break;
    }
    case ShapeType::chainSegment: {
      ChainSegment c;
      c.ghost1 = getVec2(r);
      c.segment.point1 = getVec2(r);
      c.segment.point2 = getVec2(r);
      c.ghost2 = getVec2(r);
      c.oneSided = r.boolean();
      s = c;
      break;
    }
    default:
      r.fail("a shape type of " + std::to_string(type));
  }
  try {
    validate(s);
  } catch (const InvalidShape& e) {
    r.fail(std::string("a shape: ") + e.what());
  }
  return s;
}

void put(ByteWriter& w, const ShapeRef& s) {
  w.i32(s.shape.index);
  w.u32(s.shape.generation);
  w.i32(s.body.index);
  w.u32(s.body.generation);
  w.u64(s.shapeUserData);
  w.u64(s.bodyUserData);
}
ShapeRef getRef(ByteReader& r) {
  ShapeRef s;
  s.shape.index = r.i32();
  s.shape.generation = r.u32();
  s.body.index = r.i32();
  s.body.generation = r.u32();
  s.shapeUserData = r.u64();
  s.bodyUserData = r.u64();
  return s;
}

template <class T, class Put>
void putList(ByteWriter& w, const std::vector<T>& list, Put&& one) {
  w.count(list.size());
  for (const T& item : list)
    one(item);
}
template <class T, class Get>
void getList(ByteReader& r, std::vector<T>& list, std::size_t minBytes, Get&& one) {
  const std::size_t n = r.count(minBytes);
  list.clear();
  list.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    list.push_back(one());
}

void putEvents(ByteWriter& w, const ContactEvents& e, const SensorEvents& s) {
  auto touch = [&](const auto& t) {
    put(w, t.a);
    put(w, t.b);
    put(w, t.point);
    put(w, t.normal);
    w.f32(t.approachSpeed);
  };
  putList(w, e.begin, touch);
  putList(w, e.hit, touch);
  putList(w, e.end, [&](const ContactEndEvent& t) {
    put(w, t.a);
    put(w, t.b);
    w.boolean(t.destroyed);
  });
  for (const auto* list : {&s.begin, &s.end})
    putList(w, *list, [&](const SensorEvent& t) {
      put(w, t.sensor);
      put(w, t.visitor);
      w.boolean(t.destroyed);
    });
}

void getEvents(ByteReader& r, ContactEvents& e, SensorEvents& s) {
  auto touch = [&]<class T>(T& t) {
    t.a = getRef(r);
    t.b = getRef(r);
    t.point = getVec2(r);
    t.normal = getVec2(r);
    t.approachSpeed = r.f32();
    return t;
  };
  getList(r, e.begin, 52, [&] {
    ContactBeginEvent t;
    return touch(t);
  });
  getList(r, e.hit, 52, [&] {
    ContactHitEvent t;
    return touch(t);
  });
  getList(r, e.end, 33, [&] {
    ContactEndEvent t;
    t.a = getRef(r);
    t.b = getRef(r);
    t.destroyed = r.boolean();
    return t;
  });
  for (auto* list : {&s.begin, &s.end})
    getList(r, *list, 33, [&] {
      SensorEvent t;
      t.sensor = getRef(r);
      t.visitor = getRef(r);
      t.destroyed = r.boolean();
      return t;
    });
}

}  // namespace

WorldSnapshot World::snapshot() const {
  const WorldState& s = *s_;
  WorldSnapshot bytes;
  ByteWriter w(bytes);
  w.u32(kMagic);
  w.u32(kFormat);
  defFields(s.def_, [&](const char*, float v) { w.f32(v); });
  w.f64(s.time_);
  w.i32(s.bodyCount_);
  w.i32(s.shapeCount_);
  w.i32(s.awakeCount_);

  putList(w, s.bodies_, [&](const WorldState::Body& b) {
    w.u8(static_cast<std::uint8_t>(b.type));
    w.u8(static_cast<std::uint8_t>(b.alive | b.fixedRotation << 1 | b.bullet << 2 |
                                   b.allowSleep << 3 | b.enabled << 4 | b.round << 5));
    w.u32(b.generation);
    put(w, b.xf.p);
    w.f32(b.xf.q.c);
    w.f32(b.xf.q.s);
    w.f32(b.angle);
    put(w, b.localCenter);
    put(w, b.force);
    for (float f : {b.torque, b.mass, b.invMass, b.inertia, b.invInertia, b.linearDamping,
                    b.angularDamping, b.gravityScale, b.minExtent, b.maxExtent, b.sleepTime})
      w.f32(f);
    w.i32(b.island);
    w.u64(b.userData);
    w.i32(b.slot);
    putList(w, b.shapes, [&](std::int32_t shape) { w.i32(shape); });
  });
  putList(w, s.freeBodies_, [&](std::int32_t i) { w.i32(i); });
  putList(w, s.shapes_, [&](const WorldState::ShapeRecord& r) {
    put(w, r.shape);
    w.i32(r.body);
    w.u32(r.generation);
    w.u8(static_cast<std::uint8_t>(r.alive | r.isSensor << 1 | r.contactEvents << 2 |
                                   r.hitEvents << 3 | r.sensorEvents << 4));
    for (float f :
         {r.density, r.friction, r.restitution, r.bound.center.x, r.bound.center.y, r.bound.radius})
      w.f32(f);
    w.u32(r.filter.category);
    w.u32(r.filter.mask);
    w.i32(r.proxy);
    w.u64(r.userData);
  });
  putList(w, s.freeShapes_, [&](std::int32_t i) { w.i32(i); });
  putList(w, s.contacts_, [&](const WorldState::Contact& c) {
    w.i32(c.shapeA);
    w.i32(c.shapeB);
    put(w, c.manifold.normal);
    w.i32(c.manifold.pointCount);
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      const ManifoldPoint& p = c.manifold.points[k];
      put(w, p.point);
      put(w, p.anchorA);
      put(w, p.anchorB);
      w.f32(p.separation);
      w.u16(p.id);
    }
    for (float f : {c.normalImpulse[0], c.normalImpulse[1], c.tangentImpulse[0],
                    c.tangentImpulse[1], c.friction, c.restitution})
      w.f32(f);
    w.boolean(c.touching);
  });
  putList(w, s.slotBody_, [&](std::int32_t i) { w.i32(i); });
  for (std::size_t k = 0; k < s.q_.size(); ++k) {
    w.f64(s.q_[k]);
    w.f32(s.v_[k]);
  }
  putList(w, s.islands_, [&](const std::vector<std::int32_t>& island) {
    putList(w, island, [&](std::int32_t i) { w.i32(i); });
  });
  putList(w, s.freeIslands_, [&](std::int32_t i) { w.i32(i); });
  putList(w, s.pendingRefit_, [&](std::int32_t i) { w.i32(i); });
  putList(w, s.sensorPairs_, [&](const WorldState::SensorPair& p) {
    w.i32(p.sensor);
    w.i32(p.visitor);
    w.boolean(p.overlapping);
  });
  putEvents(w, s.events_, s.sensorEvents_);
  putEvents(w, s.pendingEvents_, s.pendingSensorEvents_);
  putList(w, s.quarantineEvents_, [&](const QuarantineEvent& e) {
    w.i32(e.body.index);
    w.u32(e.body.generation);
    w.u64(e.userData);
    w.u8(static_cast<std::uint8_t>(e.cause));
  });
  s.broadphase_.save(w);
  return bytes;
}

namespace {
void decode(ByteReader& r, WorldState& s);
}  // namespace

void World::restore(std::span<const std::uint8_t> bytes) {
  ByteReader r(bytes, "snapshot");
  if (r.u32() != kMagic) r.fail("not a world snapshot");
  if (const std::uint32_t format = r.u32(); format != kFormat)
    r.fail("format " + std::to_string(format) + ", this build reads format " +
           std::to_string(kFormat));
  defFields(s_->def_, [&](const char* name, float mine) {
    const float theirs = r.f32();
    if (std::bit_cast<std::uint32_t>(theirs) != std::bit_cast<std::uint32_t>(mine))
      r.fail(std::string("taken from a world whose ") + name + " is " + formatNumber(theirs) +
             ", this one's is " + formatNumber(mine));
  });
  // The new state borrows the world's broadphase (its finest levels hold a million cells: a new
  // one per restore would cost milliseconds) and gives it back, as it was, if it is refused.
  WorldSnapshot oldTree;
  ByteWriter treeWriter(oldTree);
  s_->broadphase_.save(treeWriter);
  auto t = std::make_unique<WorldState>(s_->def_, 0);
  t->broadphase_ = std::move(s_->broadphase_);
  try {
    decode(r, *t);
  } catch (...) {
    s_->broadphase_ = std::move(t->broadphase_);
    ByteReader treeReader(oldTree, "snapshot");
    s_->broadphase_.load(treeReader);
    throw;
  }
  t->fields_ = std::move(s_->fields_);
  s_ = std::move(t);
}

namespace {

// The rest of the snapshot into s, checked.
void decode(ByteReader& r, WorldState& s) {
  auto need = [&](bool ok, const char* what) {
    if (!ok) r.fail(what);
  };
  s.time_ = r.f64();
  s.bodyCount_ = r.i32();
  s.shapeCount_ = r.i32();
  s.awakeCount_ = r.i32();

  getList(r, s.bodies_, 90, [&] {
    WorldState::Body b;
    const std::uint8_t type = r.u8();
    need(type <= 2, "a body type");
    b.type = static_cast<BodyType>(type);
    const std::uint8_t flags = r.u8();
    need(flags < 64, "a body's flags");
    b.alive = flags & 1;
    b.fixedRotation = flags & 2;
    b.bullet = flags & 4;
    b.allowSleep = flags & 8;
    b.enabled = flags & 16;
    b.round = flags & 32;
    b.generation = r.u32();
    b.xf.p = getVec2(r);
    b.xf.q.c = r.f32();
    b.xf.q.s = r.f32();
    b.angle = r.f32();
    b.localCenter = getVec2(r);
    b.force = getVec2(r);
    for (float* f : {&b.torque, &b.mass, &b.invMass, &b.inertia, &b.invInertia, &b.linearDamping,
                     &b.angularDamping, &b.gravityScale, &b.minExtent, &b.maxExtent, &b.sleepTime})
      *f = r.f32();
    const float c = b.xf.q.c, sn = b.xf.q.s;
    need(isFinite(b.xf.p) && std::isfinite(b.angle) && isFinite(b.localCenter) &&
             isFinite(b.force) && std::isfinite(b.torque) && std::isfinite(b.mass) &&
             std::isfinite(b.invMass) && std::isfinite(b.inertia) && std::isfinite(b.invInertia) &&
             std::isfinite(b.linearDamping) && std::isfinite(b.angularDamping) &&
             std::isfinite(b.gravityScale) && std::isfinite(b.minExtent) &&
             std::isfinite(b.maxExtent) && std::isfinite(b.sleepTime) &&
             std::fabs(c * c + sn * sn - 1.0f) < 1e-4f,
         "a body's state is not finite");
    b.island = r.i32();
    b.userData = r.u64();
    b.slot = r.i32();
    getList(r, b.shapes, 4, [&] { return r.i32(); });
    return b;
  });
  getList(r, s.freeBodies_, 4, [&] { return r.i32(); });
  getList(r, s.shapes_, 60, [&] {
    WorldState::ShapeRecord rec;
    rec.shape = getShape(r);
    rec.body = r.i32();
    rec.generation = r.u32();
    const std::uint8_t flags = r.u8();
    need(flags < 32, "a shape's flags");
    rec.alive = flags & 1;
    rec.isSensor = flags & 2;
    rec.contactEvents = flags & 4;
    rec.hitEvents = flags & 8;
    rec.sensorEvents = flags & 16;
    for (float* f : {&rec.density, &rec.friction, &rec.restitution, &rec.bound.center.x,
                     &rec.bound.center.y, &rec.bound.radius})
      *f = r.f32();
    need(std::isfinite(rec.density) && std::isfinite(rec.friction) &&
             std::isfinite(rec.restitution) && isFinite(rec.bound.center) &&
             std::isfinite(rec.bound.radius),
         "a shape's material is not finite");
    rec.filter.category = r.u32();
    rec.filter.mask = r.u32();
    rec.proxy = r.i32();
    rec.userData = r.u64();
    return rec;
  });
  getList(r, s.freeShapes_, 4, [&] { return r.i32(); });
  getList(r, s.contacts_, 45, [&] {
    WorldState::Contact c;
    c.shapeA = r.i32();
    c.shapeB = r.i32();
    c.manifold.normal = getVec2(r);
    c.manifold.pointCount = r.i32();
    need(c.manifold.pointCount >= 0 && c.manifold.pointCount <= 2, "a manifold's point count");
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      ManifoldPoint& p = c.manifold.points[k];
      p.point = getVec2(r);
      p.anchorA = getVec2(r);
      p.anchorB = getVec2(r);
      p.separation = r.f32();
      p.id = r.u16();
    }
    for (float* f : {&c.normalImpulse[0], &c.normalImpulse[1], &c.tangentImpulse[0],
                     &c.tangentImpulse[1], &c.friction, &c.restitution})
      *f = r.f32();
    c.touching = r.boolean();
    bool finite =
        isFinite(c.manifold.normal) && std::isfinite(c.friction) && std::isfinite(c.restitution);
    for (int k = 0; k < 2; ++k)
      finite = finite && std::isfinite(c.normalImpulse[k]) && std::isfinite(c.tangentImpulse[k]);
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      const ManifoldPoint& p = c.manifold.points[k];
      finite = finite && isFinite(p.point) && isFinite(p.anchorA) && isFinite(p.anchorB) &&
               std::isfinite(p.separation);
    }
    need(finite, "a contact is not finite");
    return c;
  });
  getList(r, s.slotBody_, 4, [&] { return r.i32(); });
  s.q_.resize(3 * s.slotBody_.size());
  s.v_.resize(3 * s.slotBody_.size());
  for (std::size_t k = 0; k < s.q_.size(); ++k) {
    s.q_[k] = r.f64();
    s.v_[k] = r.f32();
    // (A position floats cannot hold would overflow the step's boxes.)
    need(std::fabs(s.q_[k]) < 1e30 && std::isfinite(s.v_[k]), "a body's state is out of range");
  }
  getList(r, s.islands_, 4, [&] {
    std::vector<std::int32_t> island;
    getList(r, island, 4, [&] { return r.i32(); });
    return island;
  });
  getList(r, s.freeIslands_, 4, [&] { return r.i32(); });
  getList(r, s.pendingRefit_, 4, [&] { return r.i32(); });
  getList(r, s.sensorPairs_, 9, [&] {
    WorldState::SensorPair p;
    p.sensor = r.i32();
    p.visitor = r.i32();
    p.overlapping = r.boolean();
    return p;
  });
  getEvents(r, s.events_, s.sensorEvents_);
  getEvents(r, s.pendingEvents_, s.pendingSensorEvents_);
  getList(r, s.quarantineEvents_, 17, [&] {
    QuarantineEvent e;
    e.body.index = r.i32();
    e.body.generation = r.u32();
    e.userData = r.u64();
    const std::uint8_t cause = r.u8();
    need(cause <= 2, "a quarantine cause");
    e.cause = static_cast<QuarantineCause>(cause);
    return e;
  });
  s.broadphase_.load(r);
  need(r.atEnd(), "bytes after the end");

  // Every index in range and every cross-reference consistent: what the step relies on.
  const auto bodies = static_cast<std::int32_t>(s.bodies_.size());
  const auto shapes = static_cast<std::int32_t>(s.shapes_.size());
  const auto slots = static_cast<std::int32_t>(s.slotBody_.size());
  auto aliveBody = [&](std::int32_t i) {
    return i >= 0 && i < bodies && s.bodies_[static_cast<std::size_t>(i)].alive;
  };
  auto aliveShape = [&](std::int32_t i) {
    return i >= 0 && i < shapes && s.shapes_[static_cast<std::size_t>(i)].alive;
  };
  need(s.awakeCount_ >= 0 && s.awakeCount_ <= slots, "the awake count");
  const auto islands = static_cast<std::int32_t>(s.islands_.size());
  int aliveBodies = 0, aliveShapes = 0, proxied = 0;
  std::size_t listed = 0;
  for (std::int32_t i = 0; i < bodies; ++i) {
    const WorldState::Body& b = s.bodies_[static_cast<std::size_t>(i)];
    if (!b.alive) continue;
    ++aliveBodies;
    need((b.slot < 0) == (b.type == BodyType::staticBody) && b.slot >= -1 && b.slot < slots,
         "a body's slot");
    need(b.slot < 0 || s.slotBody_[static_cast<std::size_t>(b.slot)] == i, "a slot's body");
    // Awake slots come first and hold enabled bodies in no island; an island's bodies sleep.
    const bool awake = b.slot >= 0 && b.slot < s.awakeCount_;
    need(!awake || (b.enabled && b.island < 0), "an awake body");
    need(b.island >= -1 && b.island < islands && (b.island < 0 || (b.slot >= 0 && !awake)),
         "a body's island");
    for (std::int32_t shape : b.shapes)
      need(aliveShape(shape) && s.shapes_[static_cast<std::size_t>(shape)].body == i,
           "a body's shape");
    listed += b.shapes.size();
  }
  for (std::int32_t i = 0; i < shapes; ++i) {
    const WorldState::ShapeRecord& rec = s.shapes_[static_cast<std::size_t>(i)];
    if (!rec.alive) continue;
    ++aliveShapes;
    need(aliveBody(rec.body), "a shape's body");
    const WorldState::Body& body = s.bodies_[static_cast<std::size_t>(rec.body)];
    const bool enabled = body.enabled;
    proxied += enabled;
    // Where the step will put it must be a box floats can hold with room to move (finite
    // numbers near the float limit overflow in the step's sums).
    const AABB box = computeAABB(rec.shape, body.xf);
    need(box.isValid() && std::fabs(box.lower.x) < 1e30f && std::fabs(box.lower.y) < 1e30f &&
             std::fabs(box.upper.x) < 1e30f && std::fabs(box.upper.y) < 1e30f,
         "a shape is out of range");
    // (userData throws for a proxy that is not alive.)
    need(enabled
             ? rec.proxy >= 0 && static_cast<std::int32_t>(s.broadphase_.userData(rec.proxy)) == i
             : rec.proxy == kNullProxy,
         "a shape's proxy");
  }
  // Each alive shape in exactly one body's list (a shape listed twice leaves another out).
  need(aliveBodies == s.bodyCount_ && aliveShapes == s.shapeCount_ &&
           listed == static_cast<std::size_t>(aliveShapes),
       "the body or shape count");
  need(s.broadphase_.proxyCount() == proxied, "the proxy count");
  for (std::int32_t i : s.slotBody_)
    need(aliveBody(i), "a slot's body");
  // Free lists: distinct, and exactly the unused slots (creation pops them).
  auto freeList = [&](const std::vector<std::int32_t>& list, std::int32_t size, auto&& unused,
                      const char* what) {
    std::vector<char> seen(static_cast<std::size_t>(size), 0);
    std::size_t count = 0;
    for (std::int32_t i = 0; i < size; ++i)
      count += unused(i);
    for (std::int32_t i : list)
      need(i >= 0 && i < size && unused(i) && !std::exchange(seen[static_cast<std::size_t>(i)], 1),
           what);
    need(list.size() == count, what);
  };
  freeList(
      s.freeBodies_, bodies, [&](std::int32_t i) { return !aliveBody(i); }, "a free body");
  freeList(
      s.freeShapes_, shapes, [&](std::int32_t i) { return !aliveShape(i); }, "a free shape");
  for (std::int32_t k = 0; k < islands; ++k)
    for (std::int32_t i : s.islands_[static_cast<std::size_t>(k)])
      need(aliveBody(i) && s.bodies_[static_cast<std::size_t>(i)].island == k, "an island's body");
  freeList(
      s.freeIslands_, islands,
      [&](std::int32_t k) { return s.islands_[static_cast<std::size_t>(k)].empty(); },
      "a free island");
  for (std::int32_t i : s.pendingRefit_)
    need(i >= 0 && i < bodies, "a body to refit");
  for (std::size_t k = 0; k < s.contacts_.size(); ++k) {
    const WorldState::Contact& c = s.contacts_[k];
    need(aliveShape(c.shapeA) && aliveShape(c.shapeB) && c.shapeA < c.shapeB, "a contact's shapes");
    need(s.contactIndex_.emplace(pairKey(c.shapeA, c.shapeB), static_cast<std::int32_t>(k)).second,
         "a contact twice");
  }
  for (std::size_t k = 0; k < s.sensorPairs_.size(); ++k) {
    const WorldState::SensorPair& p = s.sensorPairs_[k];
    need(aliveShape(p.sensor) && aliveShape(p.visitor) &&
             s.shapes_[static_cast<std::size_t>(p.sensor)].isSensor &&
             !s.shapes_[static_cast<std::size_t>(p.visitor)].isSensor,
         "a sensor pair's shapes");
    need(s.sensorIndex_.emplace(pairKey(p.sensor, p.visitor), static_cast<std::int32_t>(k)).second,
         "a sensor pair twice");
  }
}

}  // namespace

std::uint64_t World::stateHash() const {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::uint8_t byte : snapshot()) {
    h ^= byte;
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace rc
