// Islands and sleep: still islands of touching bodies stop being simulated until woken.
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "physics/union_find.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {

void WorldState::wakeBody(Body& b) {
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
  return s_->awake(s_->body(id));
}

void World::wake(BodyId id) {
  s_->wakeBody(s_->body(id));
}

void WorldState::updateSleep(float dt) {
  // With sleeping off every still time stays 0 (nothing else raises one): nothing to do.
  if (!def_.enableSleep) return;
  const auto n = static_cast<std::size_t>(awakeCount_);
  const float lin2 = def_.linearSleepTolerance * def_.linearSleepTolerance;
  const float ang2 = def_.angularSleepTolerance * def_.angularSleepTolerance;
  // Each awake body's still time; bodies that may not sleep count as never still. Still is
  // slower than the tolerances, and moved on average no faster than the linear one since it
  // became still: the push-out moves overlapping bodies by their positions while the relax
  // pass takes its speed back out, so a body being pushed out of an overlap can end every step
  // at rest. (A load resting on a soft contact deeper than the slop, which is where it
  // settles, does not drift, and sleeps; the average lets a settled stack's jitter, which
  // cancels, through.)
  bool anyReady = false;  // a body still for timeToSleep: without one, no island sleeps
  for (std::size_t s = 0; s < n; ++s) {
    Body& b = bodies_[static_cast<std::size_t>(slotBody_[s])];
    const float v2 = v_[3 * s] * v_[3 * s] + v_[3 * s + 1] * v_[3 * s + 1];
    const float w2 = v_[3 * s + 2] * v_[3 * s + 2];
    const bool slow = b.allowSleep && v2 <= lin2 && w2 <= ang2;
    if (!slow) {
      b.sleepTime = 0.0f;
      continue;
    }
    double* from = &stillFrom_[2 * s];
    if (b.sleepTime == 0.0f) {
      from[0] = q_[3 * s];
      from[1] = q_[3 * s + 1];
    }
    const double dx = q_[3 * s] - from[0], dy = q_[3 * s + 1] - from[1];
    const double moved2 = dx * dx + dy * dy;
    const auto tolerance = static_cast<double>(def_.linearSleepTolerance);
    // Still to a tenth of the tolerances (at the step's end and, on average, since it became
    // still), still time counts three times as fast: a third of timeToSleep that still is a
    // thirtieth of the motion the rule allows in the whole of it. A pile the stack solve holds
    // (physics/README.md, "Piles") sleeps at step 14 / 14-18 instead of 30 / 32 (base 20 / 40); a
    // body at the top of a throw is that slow for a millisecond, and one pushed out of an
    // overlap by its position, still at every step's end, moves on average faster than that.
    const float quick = 3.0f * dt;
    const double tenth = 0.1 * tolerance * static_cast<double>(b.sleepTime + quick) / 3.0;
    const bool stiller = v2 <= 0.01f * lin2 && w2 <= 0.01f * ang2 && moved2 <= tenth * tenth;
    b.sleepTime += stiller ? quick : dt;
    const double reach = tolerance * b.sleepTime;
    if (moved2 > reach * reach) {
      b.sleepTime = dt;
      from[0] = q_[3 * s];
      from[1] = q_[3 * s + 1];
    }
    anyReady = anyReady || b.sleepTime >= def_.timeToSleep;
  }
  // An island sleeps when its stillest-for-shortest body has been still for timeToSleep: while
  // no body has, the islands are not looked for (a crowd in motion pays this pass over its
  // bodies, not the one over every contact below).
  if (!anyReady) return;
  // Islands: awake dynamic bodies joined by touching contacts (union-find over slots).
  islandParent_.resize(n);
  for (std::size_t s = 0; s < n; ++s)
    islandParent_[s] = static_cast<std::int32_t>(s);
  // Union by size, so that no tree grows deep (which body is an island's root does not matter:
  // islands are numbered and filled in slot order below).
  std::vector<std::int32_t>& size = islandSize_;
  size.assign(n, 1);
  auto root = [&](std::int32_t x) { return unionFindRoot(islandParent_, x); };
  // An island touching something that moves and cannot join it (a moving kinematic body)
  // stays awake: its root gets a still time of 0 below. So does one with a contact deeper
  // than a quarter of its thinner dynamic body (or two slops, for slivers): a load settles on
  // a soft contact a few millimetres deep, but bodies created inside each other may be pushed
  // apart slower than the sleep tolerance (a crowd of circles born at one point, each in
  // hundreds of overlaps, spreads at 3 cm/s), and asleep they would stay inside each other.
  std::vector<float>& still = freeV_;  // reused scratch: the island's shortest still time
  still.assign(n, std::numeric_limits<float>::max());
  for (const std::int32_t index : awakeContactList()) {
    const Contact& c = contacts_[static_cast<std::size_t>(index)];
    if (!c.touching) continue;
    const Body& a =
        bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeA)].body)];
    const Body& b =
        bodies_[static_cast<std::size_t>(shapes_[static_cast<std::size_t>(c.shapeB)].body)];
    const bool da = a.type == BodyType::dynamicBody && awake(a);
    const bool db = b.type == BodyType::dynamicBody && awake(b);
    const Manifold& m = c.manifold;
    const float deepest = m.pointCount > 1
                              ? std::min(m.points[0].separation, m.points[1].separation)
                              : m.points[0].separation;
    const float thinnest = std::min(da ? a.minExtent : std::numeric_limits<float>::max(),
                                    db ? b.minExtent : std::numeric_limits<float>::max());
    if (-deepest > std::max(0.25f * thinnest, 2.0f * kLinearSlop)) {
      if (da) still[static_cast<std::size_t>(a.slot)] = 0.0f;
      if (db) still[static_cast<std::size_t>(b.slot)] = 0.0f;
    }
    if (da && db) {
      auto ra = static_cast<std::size_t>(root(a.slot)), rb = static_cast<std::size_t>(root(b.slot));
      if (ra != rb) {
        if (size[ra] > size[rb]) std::swap(ra, rb);
        islandParent_[ra] = static_cast<std::int32_t>(rb);
        size[rb] += size[ra];
      }
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

}  // namespace rc
