#include "game/weapons/hitscan.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "game/rules/damage.h"
#include "physics/trig.h"

namespace game {
namespace {

// The cast back that finds an exit runs this far past the entry (m), so that a ray that only
// grazes a shape (entry and exit one point) still finds its exit despite rounding.
constexpr float kPastEntry = 1e-4f;
// Surfaces a shot may meet at most: bounces are capped by the weapon, crossings by the budget,
// but a material of thickness 0 costs nothing, and a shot must end whatever a level holds.
constexpr int kMaxSurfaces = 64;

struct ShotMaterial {
  float thickness = kImpenetrable;
  bool hard = true;
};

// What the shot meets: a level object's material, an actor's (never hard: bodies do not
// ricochet), and anything unknown as an impenetrable hard wall.
ShotMaterial materialOf(const MatchState& s, const rc::WorldHit& hit) {
  if (const std::optional<GameRef> ref = gameRefOf(hit.bodyUserData)) {
    if (ref->kind == GameKind::actor) return {s.tuning.thickness, false};
    return {kImpenetrable, false};
  }
  if (const std::optional<LevelRef> ref = levelRefOf(hit.bodyUserData);
      ref && ref->index < s.level.objects.size()) {
    const LevelMaterial& m = s.level.objects[ref->index].material;
    return {m.thickness, m.hard};
  }
  return {};
}

// Something the shot met, and what it carried there.
struct Impact {
  rc::ShapeRef what;
  rc::Vec2 point, dir;
  float share;  // of the weapon's damage and impulse
};

}  // namespace

// A ray starting inside a solid reports fraction 0 and a one-sided chain sees nothing from
// inside, so the exit is found from the other side: a cast back from `reach` m ahead towards
// the entry. For a solid (convex) shape the first thing that cast meets on the shape is its far
// side. A chain link is one-sided: cast back, the body shows only the faces where a forward ray
// leaves its solid (a merged tile region's outline, holes included), and the exit is the one
// nearest the entry.
std::optional<RayExit> exitOf(const rc::World& world, const rc::WorldHit& entry, rc::Vec2 dir,
                              float reach) {
  const rc::Vec2 far = entry.point + reach * dir;
  const float length = reach + kPastEntry;
  const rc::Vec2 back = -length * dir;
  std::optional<rc::WorldHit> hit;
  if (world.shape(entry.shape).isSolid()) {
    const rc::ShapeId shape = entry.shape;
    const rc::QueryFilter only(kShotFilter,
                               [shape](const rc::ShapeRef& r) { return r.shape == shape; });
    hit = world.castRay(far, back, only);
  } else {
    const rc::BodyId body = entry.body;
    const rc::QueryFilter only(kShotFilter,
                               [body](const rc::ShapeRef& r) { return r.body == body; });
    std::vector<rc::WorldHit> hits = world.castRayAll(far, back, only);
    // Sorted by fraction: the last is the nearest to the entry.
    if (!hits.empty()) hit = hits.back();
  }
  if (!hit) return std::nullopt;
  return RayExit{*hit, std::max(0.0f, reach - hit->fraction * length)};
}

float falloffAt(const HitscanSpec& weapon, float distance) {
  if (distance <= weapon.falloffStart) return 1.0f;
  if (distance >= weapon.falloffEnd) return weapon.minDamage;
  const float t = (distance - weapon.falloffStart) / (weapon.falloffEnd - weapon.falloffStart);
  return 1.0f - t * (1.0f - weapon.minDamage);
}

float damageAt(const HitscanSpec& weapon, float distance) {
  return weapon.damage * falloffAt(weapon, distance);
}

float expectedDamagePerTick(const WeaponSpec& weapon, float distance, float radius) {
  const HitscanSpec& w = weapon.hitscan;
  if (weapon.kind != WeaponKind::hitscan || !(distance <= w.range)) return 0.0f;
  float share = 1.0f;
  if (w.spread > 0.0f && distance > radius) {
    // asin(r / d) by our own atan2: what feeds the simulation never comes from libm.
    const float half = rc::atan2(radius, std::sqrt(distance * distance - radius * radius));
    share = std::min(1.0f, half / w.spread);
  }
  return static_cast<float>(w.pellets) * damageAt(w, distance) * share /
         static_cast<float>(std::max(1, weapon.cooldownTicks));
}

void traceShot(MatchState& s, std::size_t shooter, std::size_t weapon, int pellet, rc::Vec2 from,
               rc::Vec2 dir) {
  const HitscanSpec& w = s.weapons.weapons[weapon].hitscan;
  Shot shot;
  shot.shooter = shooter;
  shot.weapon = weapon;
  shot.pellet = pellet;
  shot.path.push_back(from);
  const rc::BodyId self = s.actors[shooter].body;
  std::vector<Impact> impacts;
  float budget = w.penetration;
  float kept = 1.0f;  // what bounces left of the damage
  float travelled = 0.0f;
  int bounces = 0;
  rc::Vec2 at = from;
  rc::ShapeId leaving;  // the shape the ray starts on: just crossed or bounced off
  for (int surface = 0; surface < kMaxSurfaces && travelled < w.range; ++surface) {
    const float reach = w.range - travelled;
    const rc::QueryFilter filter(kShotFilter, [self, leaving](const rc::ShapeRef& r) {
      return !(r.body == self) && !(r.shape == leaving);
    });
    const std::optional<rc::WorldHit> hit = s.world->castRay(at, reach * dir, filter);
    if (!hit) {
      shot.path.push_back(at + reach * dir);
      break;
    }
    const float distance = travelled + hit->fraction * reach;
    const float budgetShare = w.penetration > 0.0f ? budget / w.penetration : 1.0f;
    impacts.push_back({*hit, hit->point, dir, falloffAt(w, distance) * kept * budgetShare});
    shot.path.push_back(hit->point);
    const ShotMaterial m = materialOf(s, *hit);
    // The sine of the angle between the ray and the surface.
    const float grazing = -rc::dot(dir, hit->normal);
    if (m.hard && bounces < w.ricochets && grazing < w.ricochetSin) {
      dir = rc::normalize(dir - 2.0f * rc::dot(dir, hit->normal) * hit->normal);
      // From the hit point itself, the surface left out of the next cast (a bounced ray cannot
      // meet the same convex shape or straight link again): no offset bends the path.
      at = hit->point;
      leaving = hit->shape;
      travelled = distance;
      kept *= 1.0f - w.ricochetLoss;
      ++bounces;
      continue;
    }
    if (!(m.thickness <= budget)) break;  // stops in it
    const float left = w.range - distance;
    const std::optional<RayExit> exit = exitOf(*s.world, *hit, dir, left);
    if (!exit) break;  // a chain region that goes on past the range: spent inside
    budget -= m.thickness;
    travelled = distance + exit->distance;
    at = exit->hit.point;
    leaving = exit->hit.shape;
    shot.path.push_back(at);
  }
  // Effects last, so that the path was traced against the world as the shot found it.
  for (const Impact& i : impacts) {
    if (const std::optional<GameRef> ref = gameRefOf(i.what.bodyUserData);
        ref && ref->kind == GameKind::actor) {
      shot.actorsHit.push_back(ref->index);
      damageActor(s, ref->index, w.damage * i.share, shooter);
    } else if (const std::optional<LevelRef> level = levelRefOf(i.what.bodyUserData)) {
      damageProp(s, level->index, w.damage * i.share);
    }
    // Killed actors are disabled and destroyed props gone: only what is still there is pushed.
    if (s.world->isValid(i.what.body) && s.world->isEnabled(i.what.body) &&
        s.world->type(i.what.body) == rc::BodyType::dynamicBody)
      s.world->applyLinearImpulse(i.what.body, w.impulse * i.share * i.dir, i.point);
  }
  s.shots.push_back(std::move(shot));
}

}  // namespace game
