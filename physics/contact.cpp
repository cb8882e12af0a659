// Contacts: pairs from the broadphase, the narrowphase (manifolds, warm-start matching,
// speculative points and their foresight), contact events.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "physics/collide.h"
#include "physics/simd.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

namespace {

// Where a shape is taken to be, relative to where it is, when its centre coincides with
// another's (see narrowphase()): a point of the R2 sequence (Roberts' plastic-number
// sequence, in 32-bit fixed point), distinct for every shape index, scaled to 0.4 mm.
Vec2 coincidenceOffset(std::int32_t shape) {
  const auto i = static_cast<std::uint32_t>(shape);
  const std::uint32_t x = i * 0xC13FA9A9u, y = i * 0x91E10DA6u;  // frac(i a1), frac(i a2)
  constexpr float kScale = 4e-4f / 4294967296.0f;
  return {kScale * static_cast<float>(x) - 2e-4f, kScale * static_cast<float>(y) - 2e-4f};
}

}  // namespace

void WorldState::updatePairs() {
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
    if (!contactListStale_) awakeContacts_.push_back(static_cast<std::int32_t>(contacts_.size()));
    contacts_.push_back(c);
    lanesCurrent_ = false;
  }
}

void WorldState::destroyContact(std::size_t index, bool destroyed) {
  lanesCurrent_ = false;  // another contact moves into `index`
  const Contact& c = contacts_[index];
  if (c.touching && wantsContactEvents(c))
    contactSink().end.push_back({ref(c.shapeA), ref(c.shapeB), destroyed});
  contactIndex_.erase(pairKey(contacts_[index].shapeA, contacts_[index].shapeB));
  // The last contact moves into `index`. Both listed (or `index` the last): i's entry now
  // names the one moved in and the last entry goes (a loop walking the list back to front has
  // walked both). The last one unlisted: i's entry, if any, names a contact with nothing awake,
  // which the loops pass over. Only the last one listed and `index` not needs an entry moved
  // into the middle: the list is made again instead (a filter refusing two sleeping bodies that
  // do not touch: nothing wakes).
  if (!contactListStale_ && !awakeContacts_.empty() &&
      awakeContacts_.back() == static_cast<std::int32_t>(contacts_.size() - 1)) {
    // (A list of every contact, an awake crowd's, needs no search.)
    const auto i = static_cast<std::int32_t>(index);
    if (i == awakeContacts_.back() || awakeContacts_.size() == contacts_.size() ||
        std::binary_search(awakeContacts_.begin(), awakeContacts_.end(), i))
      awakeContacts_.pop_back();
    else
      contactListStale_ = true;
  }
  if (index + 1 != contacts_.size()) {
    contacts_[index] = contacts_.back();
    contactIndex_[pairKey(contacts_[index].shapeA, contacts_[index].shapeB)] =
        static_cast<std::int32_t>(index);
    if (index < contactAsleep_.size())
      contactAsleep_[index] =
          contacts_.size() <= contactAsleep_.size() ? contactAsleep_[contacts_.size() - 1] : 0;
  }
  contacts_.pop_back();
  if (contactAsleep_.size() > contacts_.size()) contactAsleep_.resize(contacts_.size());
}

const std::vector<std::int32_t>& WorldState::awakeContactList() {
  if (!contactMarksHold()) {
    contactAsleep_.resize(contacts_.size());
    for (std::size_t i = 0; i < contacts_.size(); ++i) {
      const Contact& c = contacts_[i];
      const Body& a =
          bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeA)].body)];
      const Body& b =
          bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeB)].body)];
      contactAsleep_[i] = !awake(a) && !awake(b) ? 1 : 0;
    }
    contactSleepEpoch_ = awakeEpoch_;
    contactListStale_ = true;
  }
  if (contactListStale_) {
    awakeContacts_.clear();
    for (std::size_t i = 0; i < contacts_.size(); ++i)
      if (i >= contactAsleep_.size() || contactAsleep_[i] == 0)
        awakeContacts_.push_back(static_cast<std::int32_t>(i));
    contactListStale_ = false;
  }
  return awakeContacts_;
}

// The solver keeps a speculative point's gap from closing along the normal the manifold had at
// the start of the step: a linearisation, exact for bodies that approach head on, wrong for
// bodies that pass each other or meet at a glance (fast pairs passing close by would be pushed
// apart, grazing ones bounced back head on: ghost collisions). So the manifold of a fast pair
// (margin beyond kSpeculativeDistance) whose every point is still farther than that, and whose
// linearised gap closes within the step, is taken where the pair actually meets: both bodies
// moved at their present velocities (gravity adds 1.4 mm in a 60 Hz step, well inside the
// 2 cm target), the time of impact found, and the manifold made there. Its points are carried
// back to the start of the step (anchors turned back with each body, the separation widened by
// what the approach closes until the impact), so the solver's linearised gap closes at the
// time of impact along the normal of the impact, and restitution reverses the approach along
// that normal. A pair that never comes within kSpeculativeDistance gets no points: a ghost.
// Frames as in narrowphase(): A's origin at zero.
void WorldState::foresee(Manifold& m, const ShapeRecord& ra, const Transform& xfA,
                         const ShapeRecord& rb, const Transform& xfB, float dt) const {
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

// Contact recycling, the idea of Box2D v3's (Erin Catto's): while two touching bodies have
// barely moved relative to each other since their manifold was made, the manifold is still the
// answer the shapes would give, so it is carried along instead of made again: each point stays
// on both bodies (its anchors turned with them) and its separation is the one it was made with
// plus how far the two material points have since closed along the normal, which is what the
// solver does between substeps. Bounded by the tolerance: the points' relative motion, plus the
// smaller body's reach times the relative turn (a corner that could come into the manifold),
// and each body turned by no more than kTurn (the normal, fixed, is off by at most that).
// Not for pairs moving fast enough to need foresight (margin), nor for manifolds foreseen or
// moved off a coincidence (their anchors are not one point on each body).
// (Inlined into its one caller, the narrowphase loop: as a call it was half a percent of a
// resting pyramid's step.)
[[gnu::always_inline]] inline bool WorldState::recycle(Contact& c, const Body& a, const Body& b,
                                                       Vec2 offset, float margin) const {
  const float tolerance = def_.contactRecycleDistance;
  constexpr float kTurn = 0.02f;  // rad: cos 0.9998
  if (!c.recyclable || margin > kSpeculativeDistance + tolerance) return false;
  // Four lanes at a time where the two bodies do the same arithmetic (each lane the scalar
  // expression's operations in its order, so the same bits; a - b as a + (-b), exact): the
  // turns since the manifold was made, (dqA.c, dqA.s, dqB.c, dqB.s) = invMul(made, now), that
  // is q.c r.c + q.s r.s and q.c r.s + q.s (-r.c).
  using simd::F;
  const F made = {c.madeQA.c, c.madeQA.s, c.madeQB.c, c.madeQB.s};
  const F now = {a.xf.q.c, a.xf.q.s, b.xf.q.c, b.xf.q.s};
  const F dq = __builtin_shufflevector(made, made, 0, 0, 2, 2) * now +
               __builtin_shufflevector(made, made, 1, 1, 3, 3) *
                   __builtin_shufflevector(now, -now, 1, 4, 3, 6);
  const Rot dqA{dq[0], dq[1]}, dqB{dq[2], dq[3]};
  if (std::fabs(dqA.s) > kTurn || std::fabs(dqB.s) > kTurn || dqA.c < 0.0f || dqB.c < 0.0f)
    return false;
  const float reachA =
      a.type == BodyType::staticBody ? std::numeric_limits<float>::max() : a.maxExtent;
  const float reachB =
      b.type == BodyType::staticBody ? std::numeric_limits<float>::max() : b.maxExtent;
  // What is left of the tolerance for the points' own motion.
  const float reach = tolerance - std::min(reachA, reachB) * std::fabs(invMul(dqA, dqB).s);
  if (reach < 0.0f) return false;
  Manifold& m = c.manifold;
  Vec2 onA[2], carried[2];  // A's point turned with it; B's carried point from A's
  // A point's two anchors (adjacent in ManifoldPoint) turned at once: rotate's c x - s y and
  // s x + c y as x (c, s) + y (-s, c).
  static_assert(offsetof(ManifoldPoint, anchorB) ==
                offsetof(ManifoldPoint, anchorA) + sizeof(Vec2));
  const F across = __builtin_shufflevector(dq, -dq, 5, 0, 7, 2);  // (-dqA.s, dqA.c, -dqB.s, dqB.c)
  for (int k = 0; k < m.pointCount; ++k) {
    const ManifoldPoint& mp = m.points[k];
    F anchors;
    std::memcpy(&anchors, &mp.anchorA, sizeof anchors);
    const F turned = __builtin_shufflevector(anchors, anchors, 0, 0, 2, 2) * dq +
                     __builtin_shufflevector(anchors, anchors, 1, 1, 3, 3) * across;
    onA[k] = {turned[0], turned[1]};
    carried[k] = offset + Vec2{turned[2], turned[3]} - onA[k];
    if (!(lengthSquared(carried[k]) <= reach * reach)) return false;
  }
  // The point reported (events, contactPoints): midway between the two carried points.
  for (int k = 0; k < m.pointCount; ++k) {
    ManifoldPoint& mp = m.points[k];
    mp.separation = c.madeSeparation[k] + dot(carried[k], m.normal);
    mp.point = a.xf.p + onA[k] + 0.5f * carried[k];
  }
  c.recycled = true;
  return true;
}

void WorldState::narrowphase(float dt) {
  // Nothing awake: every contact is as it was when its bodies fell asleep (the loop below
  // would skip each one).
  profile_.recycled = profile_.made = 0;
  if (awakeCount_ == 0) return;
  awakeContactList();
  // Each awake body's origin in double and its speeds, once per body where there are more
  // contacts than awake bodies (a pile's: three a body in a pyramid, each worked out from both
  // sides of every contact it is in, was a fifth of this loop); a sparse crowd's, where a pass
  // over every awake body would cost more than it saves, per contact side. The same
  // expressions either way, so the same bits. Waking a body mid-loop gives it a slot past these
  // (wakeBody leaves the awake slots where they are).
  std::size_t posed = 0;
  if (awakeContacts_.size() >= static_cast<std::size_t>(awakeCount_)) {
    posed = static_cast<std::size_t>(awakeCount_);
    slotPoses_.resize(posed);
    for (std::size_t s = 0; s < posed; ++s) {
      const Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
      const Vec2 turned = rotate(b.xf.q, b.localCenter);
      slotPoses_[s] = {preciseOrigin(b, 0, turned), preciseOrigin(b, 1, turned),
                       length(Vec2{v_[3 * s], v_[3 * s + 1]}), std::fabs(v_[3 * s + 2])};
    }
  }
  const SlotPose* const poses = slotPoses_.data();
  auto isPosed = [posed](const Body& b) {
    return b.slot >= 0 && static_cast<std::size_t>(b.slot) < posed;
  };
  // How far a shape's surface can move towards anything this step: its body's speed plus its
  // turning speed times its reach from the centre of mass.
  auto reachSpeed = [&](const ShapeRecord& r) {
    const Body& b = bodies_[static_cast<std::size_t>(r.body)];
    if (b.slot < 0) return 0.0f;
    if (isPosed(b)) {
      const SlotPose& p = poses[static_cast<std::size_t>(b.slot)];
      return p.speed + p.spin * r.reach;
    }
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    return length(Vec2{v_[i], v_[i + 1]}) + std::fabs(v_[i + 2]) * r.reach;
  };
  // (By component into two doubles: as an array the origins went through memory, and their
  // difference was one vector load of two scalars just stored, a store-forwarding stall, a
  // fifth of this loop. Each body's local centre turned once for both.)
  auto origin = [&](const Body& b, double& x, double& y) {
    if (isPosed(b)) {
      const SlotPose& p = poses[static_cast<std::size_t>(b.slot)];
      x = p.x;
      y = p.y;
      return;
    }
    const Vec2 turned = rotate(b.xf.q, b.localCenter);
    x = preciseOrigin(b, 0, turned);
    y = preciseOrigin(b, 1, turned);
  };
  // Back to front: a destroyed contact is replaced by the last one, already updated. The listed
  // contacts while the list holds; once a contact wakes an island, every contact below the one
  // at hand (the woken island's among them).
  std::size_t listed = awakeContacts_.size(), i = contacts_.size();
  for (;;) {
    if (contactMarksHold()) {
      if (listed == 0) break;
      i = static_cast<std::size_t>(awakeContacts_[--listed]);
    } else {
      if (i == 0) break;
      --i;
    }
    Contact& c = contacts_[i];
    const ShapeRecord& ra = shapes_[static_cast<std::size_t>(c.shapeA)];
    const ShapeRecord& rb = shapes_[static_cast<std::size_t>(c.shapeB)];
    Body& bodyA = bodies_[static_cast<std::size_t>(ra.body)];
    Body& bodyB = bodies_[static_cast<std::size_t>(rb.body)];
    // Nothing awake on either side: the contact is as it was when they fell asleep.
    if (!awake(bodyA) && !awake(bodyB)) continue;
    if (!overlaps(broadphase_.liveFatAABB(ra.proxy), broadphase_.liveFatAABB(rb.proxy))) {
      destroyContact(i);
      continue;
    }
    // In A's frame translated to A's origin, B placed by the difference of the two origins
    // taken in double: far from the world origin the float origins are too coarse (1 mm apart
    // 10 km out) for the separations a resting contact needs.
    double ax, ay, bx, by;
    origin(bodyA, ax, ay);
    origin(bodyB, bx, by);
    const Transform xfA{{}, bodyA.xf.q};
    const Transform xfB{{static_cast<float>(bx - ax), static_cast<float>(by - ay)}, bodyB.xf.q};
    const float margin = def_.continuous
                             ? kSpeculativeDistance + dt * (reachSpeed(ra) + reachSpeed(rb))
                             : kSpeculativeDistance;
    if (c.touching && def_.contactRecycleDistance > 0.0f &&
        recycle(c, bodyA, bodyB, xfB.p, margin)) {
      ++profile_.recycled;
      if (bodyA.island >= 0) wakeBody(bodyA);
      if (bodyB.island >= 0) wakeBody(bodyB);
      continue;
    }
    // What the warm start matches by: last step's point ids (the whole manifold copied was a
    // sixth of this loop in a pyramid) and impulses. (A recycled manifold keeps both.)
    const int oldCount = c.manifold.pointCount;
    std::uint16_t oldIds[2] = {};
    for (int j = 0; j < oldCount; ++j)
      oldIds[j] = c.manifold.points[j].id;
    const float oldNormal[2] = {c.normalImpulse[0], c.normalImpulse[1]};
    const std::uint8_t oldRows = c.stackRows;
    const float oldTangent[2] = {c.tangentImpulse[0], c.tangentImpulse[1]};
    // Constructed in place: the manifold function's result goes straight into the contact.
    // Assigned, it was built in a temporary and copied with wide loads of the narrow stores just
    // made (a store-forwarding stall, a sixth of this loop).
    // (Placement new, not std::construct_at, whose forwarding reference makes a temporary.)
    ::new (static_cast<void*>(&c.manifold)) Manifold(collide(ra.shape, xfA, rb.shape, xfB, margin));
    c.recycled = false;
    c.recyclable = true;
    c.madeQA = bodyA.xf.q;
    c.madeQB = bodyB.xf.q;
    for (int k = 0; k < c.manifold.pointCount; ++k)
      c.madeSeparation[k] = c.manifold.points[k].separation;
    // Only apart beyond the usual margin (every point) is there anything to foresee; resting
    // and sliding contacts, nearly all of a pile's, stop here (the call was 2% of a pyramid).
    const Manifold& m = c.manifold;
    if (margin > kSpeculativeDistance && m.pointCount > 0 &&
        m.points[0].separation > kSpeculativeDistance &&
        (m.pointCount == 1 || m.points[1].separation > kSpeculativeDistance)) {
      foresee(c.manifold, ra, xfA, rb, xfB, dt);
      c.recyclable = false;
    }
    // Shapes whose centres coincide give no direction to be pushed apart in: the geometry
    // picks the same one for every such pair (up for two circles, a fixed face for two
    // polygons), which lines a pile of them up along one line. Each shape is taken instead to
    // be a fraction of a millimetre from where it is, in a direction of its own: one offset per
    // shape, so that the pairs' directions fit one arrangement of the bodies (directions of
    // each pair's own ask for motions that no bodies can make at once).
    if (m.pointCount > 0 && m.points[0].separation < -kLinearSlop &&
        rotate(xfA.q, ra.bound.center) == xfB.p + rotate(xfB.q, rb.bound.center)) {
      const Vec2 offset = coincidenceOffset(c.shapeB) - coincidenceOffset(c.shapeA);
      ::new (static_cast<void*>(&c.manifold))
          Manifold(collide(ra.shape, xfA, rb.shape, {xfB.p + offset, xfB.q}, margin));
      c.recyclable = false;
    }
    for (int k = 0; k < c.manifold.pointCount; ++k)
      c.manifold.points[k].point += bodyA.xf.p;
    // Warm start: a point keeps last step's impulses when the same features touch. (Each
    // point's pair written once: zeroed first, the two were two calls to memset, a variable
    // length to the compiler, a seventh of this loop.)
    c.stackRows = 0;
    for (int k = 0; k < c.manifold.pointCount; ++k) {
      float normal = 0.0f, tangent = 0.0f;
      for (int j = 0; j < oldCount; ++j)
        if (oldIds[j] == c.manifold.points[k].id) {
          normal = oldNormal[j];
          tangent = oldTangent[j];
          c.stackRows |= static_cast<std::uint8_t>(((oldRows >> j) & 1) << k);
        }
      c.normalImpulse[k] = normal;
      c.tangentImpulse[k] = tangent;
    }
    const bool was = c.touching;
    c.touching = c.manifold.pointCount > 0;
    profile_.made += c.touching ? 1 : 0;
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
      if (wantsContactEvents(c))
        events_.begin.push_back(
            {ref(c.shapeA), ref(c.shapeB), mp.point, c.manifold.normal, approach});
      if (approach > def_.hitEventThreshold && (ra.hitEvents || rb.hitEvents))
        events_.hit.push_back(
            {ref(c.shapeA), ref(c.shapeB), mp.point, c.manifold.normal, approach});
    } else if (!c.touching && was && wantsContactEvents(c)) {
      events_.end.push_back({ref(c.shapeA), ref(c.shapeB), false});
    }
  }
}

std::vector<World::ContactPointView> World::contactPoints() const {
  std::vector<ContactPointView> out;
  for (const WorldState::Contact& c : s_->contacts_) {
    if (!c.touching) continue;
    for (int k = 0; k < c.manifold.pointCount; ++k)
      out.push_back({c.manifold.points[k].point, c.manifold.normal, c.manifold.points[k].separation,
                     c.normalImpulse[k]});
  }
  return out;
}

int World::touchingContactCount() const {
  int n = 0;
  for (const WorldState::Contact& c : s_->contacts_)
    n += c.touching;
  return n;
}

}  // namespace rc
