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
#include <type_traits>
#include <utility>

#include "physics/bytes.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {
namespace {

constexpr std::uint32_t kMagic = 0x53574352;  // "RCWS"
constexpr std::uint32_t kFormat = 3;

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
  visit("contactRecycleDistance", d.contactRecycleDistance);
  visit("stackSolveDepth", static_cast<float>(d.stackSolveDepth));
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

// Every field, once, for both directions: io(a, value) writes through an Out archive and reads
// through an In archive, so the two cannot disagree on what is in a snapshot or in what order.
class Out {
 public:
  static constexpr bool reading = false;
  explicit Out(ByteWriter& w) : w_(w) {}
  void operator()(const bool& v) { w_.boolean(v); }
  void operator()(const std::uint8_t& v) { w_.u8(v); }
  void operator()(const std::uint16_t& v) { w_.u16(v); }
  void operator()(const std::int32_t& v) { w_.i32(v); }
  void operator()(const std::uint32_t& v) { w_.u32(v); }
  void operator()(const std::uint64_t& v) { w_.u64(v); }
  void operator()(const float& v) { w_.f32(v); }
  void operator()(const double& v) { w_.f64(v); }
  void operator()(const Vec2& v) {
    w_.f32(v.x);
    w_.f32(v.y);
  }
  void operator()(const Rot& q) {
    w_.f32(q.c);
    w_.f32(q.s);
  }
  template <class E>
  requires std::is_enum_v<E>
  void operator()(const E& e, int) { w_.u8(static_cast<std::uint8_t>(e)); }
  std::size_t count(std::size_t n, std::size_t) {
    w_.count(n);
    return n;
  }

 private:
  ByteWriter& w_;
};

class In {
 public:
  static constexpr bool reading = true;
  explicit In(ByteReader& r) : r_(r) {}
  void operator()(bool& v) { v = r_.boolean(); }
  void operator()(std::uint8_t& v) { v = r_.u8(); }
  void operator()(std::uint16_t& v) { v = r_.u16(); }
  void operator()(std::int32_t& v) { v = r_.i32(); }
  void operator()(std::uint32_t& v) { v = r_.u32(); }
  void operator()(std::uint64_t& v) { v = r_.u64(); }
  void operator()(float& v) { v = r_.f32(); }
  void operator()(double& v) { v = r_.f64(); }
  void operator()(Vec2& v) {
    v.x = r_.f32();
    v.y = r_.f32();
  }
  void operator()(Rot& q) {
    q.c = r_.f32();
    q.s = r_.f32();
  }
  // An enumeration of `values` values, refused outside them.
  template <class E>
  requires std::is_enum_v<E>
  void operator()(E& e, int values) {
    const std::uint8_t v = r_.u8();
    if (v >= values) r_.fail("an enumeration's value is " + std::to_string(v));
    e = static_cast<E>(v);
  }
  // A count of items of at least minBytes each, refused when what is left cannot hold them.
  std::size_t count(std::size_t, std::size_t minBytes) { return r_.count(minBytes); }
  [[noreturn]] void fail(const std::string& why) const { r_.fail(why); }

 private:
  ByteReader& r_;
};

template <class A, class V, class Each>
void list(A& a, V& items, std::size_t minBytes, Each&& each) {
  const std::size_t n = a.count(items.size(), minBytes);
  if constexpr (A::reading) items.resize(n);
  for (auto& item : items)
    each(item);
}
template <class A, class V>
void indices(A& a, V& items) {
  list(a, items, 4, [&](auto& i) { a(i); });
}

template <class A, class S>
void io(A& a, S& s) requires std::is_same_v<std::remove_const_t<S>, Shape> {
  a(s.type, kShapeTypeCount);
  if constexpr (A::reading) {
    // The union's member for the type read (zeroed), before its fields are read into it.
    switch (s.type) {
      case ShapeType::circle:
        s = Circle{};
        break;
      case ShapeType::box:
        s = Box{};
        break;
      case ShapeType::polygon:
        s = Polygon{};
        break;
      case ShapeType::capsule:
        s = Capsule{};
        break;
      case ShapeType::segment:
        s = Segment{};
        break;
      case ShapeType::chainSegment:
        s = ChainSegment{};
        break;
    }
  }
  switch (s.type) {
    case ShapeType::circle:
      a(s.circle.center);
      a(s.circle.radius);
      return;
    case ShapeType::box:
      a(s.box.center);
      a(s.box.halfExtents);
      return;
    case ShapeType::polygon:
      a(s.polygon.count);
      if constexpr (A::reading)
        if (s.polygon.count < 3 || s.polygon.count > kMaxPolygonVertices)
          a.fail("a polygon's vertex count is " + std::to_string(s.polygon.count));
      a(s.polygon.radius);
      a(s.polygon.centroid);
      a(s.polygon.boxHalfExtents);
      for (int i = 0; i < s.polygon.count; ++i) {
        a(s.polygon.vertices[i]);
        a(s.polygon.normals[i]);
      }
      return;
    case ShapeType::capsule:
      a(s.capsule.center1);
      a(s.capsule.center2);
      a(s.capsule.radius);
      return;
    case ShapeType::segment:
      a(s.segment.point1);
      a(s.segment.point2);
      return;
    case ShapeType::chainSegment:
      a(s.chainSegment.ghost1);
      a(s.chainSegment.segment.point1);
      a(s.chainSegment.segment.point2);
      a(s.chainSegment.ghost2);
      a(s.chainSegment.oneSided);
      return;
  }
}

template <class A, class R>
void ioRef(A& a, R& r) {
  a(r.shape.index);
  a(r.shape.generation);
  a(r.body.index);
  a(r.body.generation);
  a(r.shapeUserData);
  a(r.bodyUserData);
}

// Begin and hit events have the same fields.
template <class A, class E>
void ioTouch(A& a, E& e) {
  ioRef(a, e.a);
  ioRef(a, e.b);
  a(e.point);
  a(e.normal);
  a(e.approachSpeed);
}

template <class A, class C, class S>
void ioEvents(A& a, C& contacts, S& sensors) {
  list(a, contacts.begin, 56, [&](auto& e) { ioTouch(a, e); });
  list(a, contacts.hit, 56, [&](auto& e) { ioTouch(a, e); });
  list(a, contacts.end, 33, [&](auto& e) {
    ioRef(a, e.a);
    ioRef(a, e.b);
    a(e.destroyed);
  });
  for (auto* events : {&sensors.begin, &sensors.end})
    list(a, *events, 33, [&](auto& e) {
      ioRef(a, e.sensor);
      ioRef(a, e.visitor);
      a(e.destroyed);
    });
}

// The state, in the order it is written; W is WorldState or const WorldState.
template <class A, class W>
void ioState(A& a, W& s) {
  a(s.time_);
  {
    bool wanted = s.stackSolver_.wanted();  // the stack solve's bounds for the next pass
    a(wanted);
    if constexpr (A::reading) s.stackSolver_.setWanted(wanted);
  }
  a(s.pileLayout_);
  a(s.pileLayoutCount_);
  a(s.pileLayoutValid_);
  a(s.bodyCount_);
  a(s.shapeCount_);
  a(s.awakeCount_);
  list(a, s.bodies_, 78, [&](auto& b) {  // (the least bytes of each item)
    a(b.type, 3);
    for (auto* flag : {&b.alive, &b.fixedRotation, &b.bullet, &b.allowSleep, &b.enabled})
      a(*flag);
    a(b.generation);
    a(b.xf.p);
    a(b.xf.q);
    a(b.angle);
    a(b.force);
    for (auto* f : {&b.torque, &b.linearDamping, &b.angularDamping, &b.gravityScale, &b.sleepTime})
      a(*f);
    a(b.island);
    a(b.userData);
    a(b.slot);
    indices(a, b.shapes);
  });
  indices(a, s.freeBodies_);
  list(a, s.shapes_, 58, [&](auto& r) {
    io(a, r.shape);
    a(r.body);
    a(r.generation);
    for (auto* flag : {&r.alive, &r.isSensor, &r.contactEvents, &r.hitEvents, &r.sensorEvents})
      a(*flag);
    for (auto* f : {&r.density, &r.friction, &r.restitution})
      a(*f);
    a(r.filter.category);
    a(r.filter.mask);
    a(r.proxy);
    a(r.userData);
  });
  indices(a, s.freeShapes_);
  list(a, s.contacts_, 68, [&](auto& c) {
    a(c.shapeA);
    a(c.shapeB);
    a(c.manifold.normal);
    a(c.manifold.pointCount);
    if constexpr (A::reading)
      if (c.manifold.pointCount < 0 || c.manifold.pointCount > 2)
        a.fail("a manifold's point count is " + std::to_string(c.manifold.pointCount));
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      auto& p = c.manifold.points[k];
      a(p.point);
      a(p.anchorA);
      a(p.anchorB);
      a(p.separation);
      a(p.id);
      a(c.madeSeparation[k]);
    }
    a(c.madeQA);
    a(c.madeQB);
    a(c.recyclable);
    a(c.recycled);
    a(c.stackRows);
    if constexpr (A::reading)
      if (c.stackRows > 3) a.fail("a contact's stack rows are " + std::to_string(c.stackRows));
    for (int k = 0; k < 2; ++k) {
      a(c.normalImpulse[k]);
      a(c.tangentImpulse[k]);
    }
    a(c.friction);
    a(c.restitution);
    a(c.touching);
  });
  indices(a, s.slotBody_);
  if constexpr (A::reading) {
    s.q_.resize(3 * s.slotBody_.size());
    s.v_.resize(3 * s.slotBody_.size());
    s.stillFrom_.resize(2 * s.slotBody_.size());
  }
  for (std::size_t k = 0; k < s.q_.size(); ++k) {
    a(s.q_[k]);
    a(s.v_[k]);
  }
  for (auto& x : s.stillFrom_)
    a(x);
  list(a, s.islands_, 4, [&](auto& island) { indices(a, island); });
  indices(a, s.freeIslands_);
  indices(a, s.pendingRefit_);
  list(a, s.sensorPairs_, 9, [&](auto& p) {
    a(p.sensor);
    a(p.visitor);
    a(p.overlapping);
  });
  ioEvents(a, s.events_, s.sensorEvents_);
  ioEvents(a, s.pendingEvents_, s.pendingSensorEvents_);
  list(a, s.quarantineEvents_, 17, [&](auto& e) {
    a(e.body.index);
    a(e.body.generation);
    a(e.userData);
    a(e.cause, 3);
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
  Out out(w);
  ioState(out, s);
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

// A rotation of unit length (within rounding; NaN is not): what a body's must be, and a
// contact's copies of its bodies' (recycling turns the anchors by them: off unit, it would
// scale them).
bool isUnit(Rot q) {
  return std::fabs(q.c * q.c + q.s * q.s - 1.0f) < 1e-4f;
}
// A touching manifold's normal likewise (every collide function normalizes it; the solver's
// tangent and effective masses assume it): off unit it would scale every impulse it carries.
bool isUnit(Vec2 n) {
  return std::fabs(n.x * n.x + n.y * n.y - 1.0f) < 1e-4f;
}

// The rest of the snapshot into s, checked.
void decode(ByteReader& r, WorldState& s) {
  auto need = [&](bool ok, const char* what) {
    if (!ok) r.fail(what);
  };
  In in(r);
  ioState(in, s);
  s.broadphase_.load(r);
  need(r.atEnd(), "bytes after the end");

  // Every float usable, every shape a valid one.
  for (const WorldState::Body& b : s.bodies_) {
    need(isFinite(b.xf.p) && std::isfinite(b.angle) && isFinite(b.force) &&
             std::isfinite(b.torque) && std::isfinite(b.linearDamping) &&
             std::isfinite(b.angularDamping) && std::isfinite(b.gravityScale) &&
             std::isfinite(b.sleepTime) && isUnit(b.xf.q),
         "a body's state is not finite");
  }
  for (const WorldState::ShapeRecord& rec : s.shapes_) {
    try {
      validate(rec.shape);
    } catch (const InvalidShape& e) {
      r.fail(std::string("a shape: ") + e.what());
    }
    need(
        std::isfinite(rec.density) && std::isfinite(rec.friction) && std::isfinite(rec.restitution),
        "a shape's material is not finite");
  }
  for (const WorldState::Contact& c : s.contacts_) {
    bool finite =
        isFinite(c.manifold.normal) && std::isfinite(c.friction) && std::isfinite(c.restitution);
    for (int k = 0; k < 2; ++k)
      finite = finite && std::isfinite(c.normalImpulse[k]) && std::isfinite(c.tangentImpulse[k]);
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      const ManifoldPoint& p = c.manifold.points[k];
      finite = finite && isFinite(p.point) && isFinite(p.anchorA) && isFinite(p.anchorB) &&
               std::isfinite(p.separation) && std::isfinite(c.madeSeparation[k]);
    }
    finite = finite && isUnit(c.madeQA) && isUnit(c.madeQB) &&
             (c.manifold.pointCount == 0 || isUnit(c.manifold.normal));
    need(finite, "a contact is not finite, or its normal or rotations are not of unit length");
  }
  // (A position floats cannot hold would overflow the step's boxes.)
  for (std::size_t k = 0; k < s.q_.size(); ++k)
    need(std::fabs(s.q_[k]) < 1e30 && std::isfinite(s.v_[k]), "a body's state is out of range");
  for (const double x : s.stillFrom_)
    need(std::isfinite(x), "a body's state is out of range");

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
    // The narrowphase reads a contact's proxies unchecked (Broadphase::liveFatAABB).
    need(s.shapes_[static_cast<std::size_t>(c.shapeA)].proxy != kNullProxy &&
             s.shapes_[static_cast<std::size_t>(c.shapeB)].proxy != kNullProxy,
         "a contact of a disabled body's shape");
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
  // What follows from the shapes is computed again, not read: the same bits as the world's
  // (the same functions on the same shapes), and nothing a corrupt snapshot can make absurd.
  for (WorldState::ShapeRecord& rec : s.shapes_)
    if (rec.alive) rec.bound = computeBoundingCircle(rec.shape);
  for (WorldState::Body& b : s.bodies_)
    if (b.alive) s.massProperties(b);
}

}  // namespace

std::uint64_t World::stateHash() const {
  return fnv1a(snapshot());
}

}  // namespace rc
