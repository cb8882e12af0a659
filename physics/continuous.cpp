// Continuous collision after the solve: fast bodies swept to their first time of impact.
#include <cmath>

#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

void WorldState::continuous() {
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
  // A first look from the slots' own arrays, when they still describe the awake set: a body
  // whose motion, in double, is short of half its smallest extent by more than the float
  // rounding `fast` works in (a few ulps of each coordinate) is not fast, and its record is
  // not read. The rest get the test itself, so the same bodies are swept.
  const bool firstLook = slotExtentsEpoch_ == awakeEpoch_ && slotHalfMinExtent_.size() >= slots;
  for (std::size_t s = 0; s < slots; ++s) {
    if (firstLook) {
      const std::size_t i = 3 * s;
      const double x1 = startCenter_[2 * s], y1 = startCenter_[2 * s + 1];
      const double a1 = startAngle_[s], a2 = q_[i + 2];
      const double dx = q_[i] - x1, dy = q_[i + 1] - y1;
      const double rounding =
          1e-6 * (std::fabs(x1) + std::fabs(y1) + std::fabs(q_[i]) + std::fabs(q_[i + 1]) +
                  (std::fabs(a1) + std::fabs(a2)) * slotMaxExtent_[s]);
      // |d| + turn + rounding below the bound, squared (a hypot per body cost more than the
      // record's miss).
      const double room = 0.999 * static_cast<double>(slotHalfMinExtent_[s]) -
                          std::fabs(a2 - a1) * slotMaxExtent_[s] - rounding;
      if (room > 0.0 && dx * dx + dy * dy < room * room) continue;
    }
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
    Vec2 heldOff{};             // the normal of a static shape that holds it, or stopped its centre
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
        if (r.shape.type == ShapeType::chainSegment && r.shape.chainSegment.oneSided) {
          // A one-sided link lets out what starts behind it (the manifold's rule: the shape's
          // centre on the link's left); swept against it, such a body would stop at the link.
          const Vec2 p1 = apply(ob.xf, r.shape.chainSegment.segment.point1);
          const Vec2 p2 = apply(ob.xf, r.shape.chainSegment.segment.point2);
          if (dot(apply(xf1, mine.bound.center) - p1, rightPerp(p2 - p1)) < 0.0f) return true;
        }
        const Sweep otherSweep = shapeSweep(ob, sweepOf(ob));
        const ShapeProxy otherProxy = makeProxy(r.shape);
        const ToiOutput toi = timeOfImpact(proxy, sweep, otherProxy, otherSweep, first);
        // A bullet already touching a moving body when the step began is left to their contact
        // (stopping both at the start of every step froze a bullet riding along what it hit),
        // but its centre of mass is swept, as a point with a slop's radius, against the other
        // (Box2D v3's fallback for a body that starts touching): the contact may fail to hold it
        // (a box spinning at 1,000 rad/s, touching a 1 cm plank, went through it: a corner
        // turning 17 rad a step), and the centre cannot pass through without meeting the
        // other. Riding along the other, the centre meets nothing.
        if (moving && (toi.state == ToiState::overlapped ||
                       (toi.state == ToiState::hit && toi.fraction == 0.0f))) {
          const ShapeProxy centre = makeProxy(&sweep.localCenter, 1, kLinearSlop);
          const ToiOutput c = timeOfImpact(centre, sweep, otherProxy, otherSweep, first, 0.0f);
          if (c.state == ToiState::hit && c.fraction > 0.0f && c.fraction < first) {
            first = c.fraction;
            hitBody = awake(ob) ? r.body : -1;
            heldOff = Vec2{};
          }
          return true;
        }
        // Closer than the target when the step began (resting on or sliding along a static
        // shape, within the slop) and taken into it deeper than the slop by the step: kept where
        // it started, as a hit at fraction 0 is below (a 5 cm ball sliding along a 1 cm wall,
        // struck by a body at 800 m/s, went through the wall). The normal is zero when the
        // cores overlap, and then this does not apply.
        // (Deeper than the slop measured from where it started: within the target, up to a slop
        // out, so a move in of more than two slops. One slop held a body pressed to a wall by a
        // force, 6 mm off it, which closed the gap each step by 6.9 mm, legitimately, and was held
        // there step after step while it fell along the wall at up to 280 m/s.)
        if (toi.state == ToiState::overlapped && !moving &&
            dot(sweep.c2 - sweep.c1, toi.normal) > 2.0f * kLinearSlop) {
          first = 0.0f;
          hitBody = -1;
          heldOff = toi.normal;
          return true;
        }
        // Overlapping it already, cores and all (a sharp box with a corner in the wall): no
        // normal to judge by. The centre of mass is swept instead, as a point with a slop's
        // radius (Box2D v3's fallback): it stops before it enters the shape, and is held where
        // it started, as above, when it starts at the shape and the step takes it in. A 5 cm
        // box with a corner in a 1 cm wall, struck into it at 800 m/s, went through. Stopped
        // with its centre at the face, half the body is in the shape: its speed into it goes
        // (below), or the next step carries it on before the contact stops it.
        if (toi.state == ToiState::overlapped && !moving && toi.normal == Vec2{}) {
          const ShapeProxy centre = makeProxy(&sweep.localCenter, 1, kLinearSlop);
          const ToiOutput c = timeOfImpact(centre, sweep, otherProxy, otherSweep, first, 0.0f);
          if (c.state == ToiState::hit && c.fraction > 0.0f && c.fraction < first) {
            first = c.fraction;
            hitBody = -1;
            heldOff = c.normal;
          } else if ((c.state == ToiState::hit || c.state == ToiState::overlapped) &&
                     dot(sweep.c2 - sweep.c1, c.normal) > kLinearSlop) {
            first = 0.0f;
            hitBody = -1;
            heldOff = c.normal;
          }
          return true;
        }
        // Out of iterations (a small body spinning tens of radians in the step makes
        // conservative advancement crawl): the fraction reached is a safe time before contact
        // (toi.h), so the body stops there. Ignored, it went on into the wall: triangles at
        // 100 m/s, spun to 5,000 rad/s by collisions, ended a step inside 1 m thick walls.
        if ((toi.state != ToiState::hit && toi.state != ToiState::failed) || toi.fraction >= first)
          return true;
        // Already touching at the start (sliding along a wall, or where the last step's impact
        // left it: within the tolerance of the target separation, a hit at fraction 0): the
        // contact handles it. Stopped there instead, a fast body moving away from a wall it
        // was stopped at stayed frozen at the wall step after step, its velocity growing.
        // Unless the step took it into a static shape deeper than the slop: another contact
        // solved after the wall's pushed it in (a bullet at a wall, deflected into it by a
        // ball wedged against the same wall, went 13 cm in and out of the arena at 1000 m/s);
        // it then stays where it started, and the next step's contact stops it there.
        if (toi.fraction == 0.0f &&
            (moving || dot(sweep.c2 - sweep.c1, toi.normal) <= 2.0f * kLinearSlop))
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
        heldOff = first == 0.0f && !moving ? toi.normal : Vec2{};
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
      // Held where it started by a static shape the solve drove it into, or stopped by one with
      // its centre at the face: what it had of velocity into that shape goes, as in an
      // inelastic contact. Held, its spin goes too, since it did not turn either. Kept, it made the
      // same motion next step, and the next, held each time while forces and contact impulses added
      // to it: a polygon spinning against a wall under gravity reached 75 m/s standing still,
      // another pushed by a constant force 137 m/s and 465 rad/s, and their energy grew without
      // bound. With the spin kept, a body whose touching corner the spin swung away from a wall (so
      // that the contact let it come) while a force drove its centre in was held step after step,
      // falling along the wall at 280 m/s standing still; and a long body spinning a corner into
      // the floor slid along it at 140 m/s standing still.
      if (hitBody < 0 && (first == 0.0f || heldOff != Vec2{})) {
        const std::size_t i = 3 * static_cast<std::size_t>(b.slot);
        const float closing = v_[i] * heldOff.x + v_[i + 1] * heldOff.y;
        if (closing > 0.0f) {
          v_[i] -= closing * heldOff.x;
          v_[i + 1] -= closing * heldOff.y;
        }
        if (first == 0.0f) v_[i + 2] = 0.0f;
      }
    }
  }
  for (std::int32_t own : sweptShapes_)
    contactSwept_[static_cast<std::size_t>(own)] = -1;
}

}  // namespace rc
