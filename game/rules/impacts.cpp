#include "game/rules/impacts.h"

#include <optional>
#include <vector>

#include "game/rules/damage.h"

namespace game {
namespace {

// What one side of a hit event is to the rules.
struct Side {
  rc::BodyId body;
  std::int32_t actor = -1;    // an actor's index
  std::int32_t object = -1;   // a level object's index
  std::int32_t grenade = -1;  // a live grenade's slot
  float mass = 0.0f;
};

Side sideOf(const MatchState& s, const rc::ShapeRef& ref) {
  Side side;
  side.body = ref.body;
  if (const std::optional<GameRef> g = gameRefOf(ref.bodyUserData)) {
    if (g->kind == GameKind::actor && g->index < s.actors.size())
      side.actor = static_cast<std::int32_t>(g->index);
    if (g->kind == GameKind::projectile && g->index < s.grenades.size() &&
        s.grenades[g->index].live && s.grenades[g->index].body == ref.body)
      side.grenade = static_cast<std::int32_t>(g->index);
  } else if (const std::optional<LevelRef> l = levelRefOf(ref.bodyUserData)) {
    side.object = static_cast<std::int32_t>(l->index);
  }
  if (s.world->isValid(ref.body)) side.mass = s.world->mass(ref.body);
  return side;
}

// Whether an impact can hurt this side now.
bool hurtable(MatchState& s, const Side& side) {
  if (side.actor >= 0) return s.actors[static_cast<std::size_t>(side.actor)].alive;
  if (side.object >= 0) {
    const PropState* p = propOf(s, static_cast<std::size_t>(side.object));
    return p != nullptr && p->destructible && !p->destroyed;
  }
  return false;
}

// Who pushed this side last, and when, if within the blame window.
struct Blame {
  std::int32_t actor = -1;
  std::int64_t tick = -1;
};
Blame blameOf(MatchState& s, const Side& side) {
  Blame b;
  if (side.actor >= 0) {
    const Actor& a = s.actors[static_cast<std::size_t>(side.actor)];
    b = {a.blamed, a.blamedTick};
  } else if (side.object >= 0) {
    if (const PropState* p = propOf(s, static_cast<std::size_t>(side.object)))
      b = {p->blamed, p->blamedTick};
  }
  if (b.actor < 0 || s.tick - b.tick > s.rules.blameTicks) return {};
  return b;
}

std::int32_t creditOf(MatchState& s, const Side& a, const Side& b) {
  for (const Side* side : {&a, &b})
    if (side->grenade >= 0)
      return static_cast<std::int32_t>(s.grenades[static_cast<std::size_t>(side->grenade)].thrower);
  const Blame ba = blameOf(s, a), bb = blameOf(s, b);
  return bb.tick > ba.tick ? bb.actor : ba.actor;
}

}  // namespace

float reducedMass(float massA, float massB) {
  if (!(massA > 0.0f)) return massB > 0.0f ? massB : 0.0f;
  if (!(massB > 0.0f)) return massA;
  return massA * massB / (massA + massB);
}

float impactDamage(const RuleTuning& rules, float mu, float speed) {
  if (!(speed > rules.impactSpeed) || !(mu > 0.0f)) return 0.0f;
  return rules.impactDamage * mu * (speed - rules.impactSpeed);
}

void blameBlast(MatchState& s, std::uint64_t userData, std::size_t thrower) {
  if (const std::optional<GameRef> g = gameRefOf(userData)) {
    if (g->kind != GameKind::actor || g->index >= s.actors.size()) return;
    Actor& a = s.actors[g->index];
    a.blamed = static_cast<std::int32_t>(thrower);
    a.blamedTick = s.tick;
  } else if (const std::optional<LevelRef> l = levelRefOf(userData)) {
    if (PropState* p = propOf(s, l->index)) {
      p->blamed = static_cast<std::int32_t>(thrower);
      p->blamedTick = s.tick;
    }
  }
}

void applyImpacts(MatchState& s) {
  // Gathered first (masses, credit) against the world as the step left it, then applied: a
  // prop the first crash destroys still counts in the second.
  struct Pending {
    Side a, b;
    Crash crash;
  };
  std::vector<Pending> pending;
  for (const rc::ContactHitEvent& e : s.world->contactEvents().hit) {
    if (!(e.approachSpeed > s.rules.impactSpeed)) continue;
    const Side a = sideOf(s, e.a), b = sideOf(s, e.b);
    if (a.actor >= 0 && b.actor >= 0) continue;
    if (!hurtable(s, a) && !hurtable(s, b)) continue;
    // One crash per pair of bodies: the fastest.
    Pending* same = nullptr;
    for (Pending& p : pending)
      if ((p.a.body == a.body && p.b.body == b.body) || (p.a.body == b.body && p.b.body == a.body))
        same = &p;
    if (same != nullptr && same->crash.speed >= e.approachSpeed) continue;
    Crash c;
    c.point = e.point;
    c.speed = e.approachSpeed;
    c.damage = impactDamage(s.rules, reducedMass(a.mass, b.mass), e.approachSpeed);
    c.actor = {a.actor, b.actor};
    c.object = {a.object, b.object};
    c.credited = creditOf(s, a, b);
    if (same != nullptr) {
      *same = {a, b, c};
    } else {
      pending.push_back({a, b, c});
    }
  }
  for (const Pending& p : pending) {
    if (!(p.crash.damage > 0.0f)) continue;
    const std::optional<std::size_t> credit =
        p.crash.credited >= 0 ? std::optional<std::size_t>(p.crash.credited) : std::nullopt;
    for (const Side* side : {&p.a, &p.b}) {
      if (side->actor >= 0) {
        damageActor(s, static_cast<std::size_t>(side->actor), p.crash.damage, credit);
      } else if (side->object >= 0) {
        damageProp(s, static_cast<std::size_t>(side->object), p.crash.damage);
      }
    }
    s.crashes.push_back(p.crash);
  }
}

}  // namespace game
