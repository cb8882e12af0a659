// Queries: ray and shape casts, overlaps, each with a filter.
#include <algorithm>
#include <cmath>
#include <utility>

#include "physics/collide.h"
#include "physics/distance.h"
#include "physics/world.h"
#include "physics/world_state.h"

namespace rc {
namespace {

void checkCast(const char* what, Vec2 origin, Vec2 translation) {
  requireFinite(what, "origin", origin);
  requireFinite(what, "translation", translation);
}

}  // namespace

template <class Exact>
std::optional<WorldHit> WorldState::closest(const RayCastInput& in, float radius,
                                            ProxyFilter filter, Exact&& exact) const {
  const ProxyHit h = castClosest(broadphase_, in, radius, filter, exact);
  if (!h.out.hit) return std::nullopt;
  const auto index = static_cast<std::int32_t>(broadphase_.userData(h.id));
  return WorldHit{shapeId(index), bodyId(shapes_[static_cast<std::size_t>(index)].body),
                  h.out.point, h.out.normal, h.out.fraction};
}

CastOutput WorldState::rayAgainst(ProxyId proxy, const RayCastInput& ray) const {
  const ShapeRecord& r = shapes_[broadphase_.userData(proxy)];
  if (r.isSensor) return {};
  return rayCast(r.shape, bodies_[static_cast<std::size_t>(r.body)].xf, ray);
}

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation, ProxyFilter filter) const {
  checkCast("castRay", origin, translation);
  const RayCastInput in{origin, translation, 1.0f};
  const WorldState& s = *s_;
  return s.closest(in, 0.0f, filter,
                   [&s](ProxyId id, const RayCastInput& ray) { return s.rayAgainst(id, ray); });
}

std::vector<WorldHit> World::castRayAll(Vec2 origin, Vec2 translation, ProxyFilter filter) const {
  checkCast("castRayAll", origin, translation);
  const RayCastInput in{origin, translation, 1.0f};
  const WorldState& s = *s_;
  std::vector<WorldHit> out;
  for (const ProxyHit& h :
       castAll(s.broadphase_, in, 0.0f, filter,
               [&s](ProxyId id, const RayCastInput&ray) { return s.rayAgainst(id, ray); })) {
    const auto index = static_cast<std::int32_t>(s.broadphase_.userData(h.id));
    out.push_back({s.shapeId(index), s.bodyId(s.shapes_[static_cast<std::size_t>(index)].body),
                   h.out.point, h.out.normal, h.out.fraction});
  }
  return out;
}

std::optional<WorldHit> World::castCircle(Vec2 center, float radius, Vec2 translation,
                                          ProxyFilter filter) const {
  checkCast("castCircle", center, translation);
  if (!(radius > 0.0f) || !std::isfinite(radius))
    failDefinition("castCircle", "radius", "is " + formatNumber(radius) + " (must be > 0)");
  const RayCastInput in{center, translation, 1.0f};
  const ShapeProxy disc = makeProxy(&center, 1, radius);
  const WorldState& s = *s_;
  return s.closest(in, radius, filter, [&](ProxyId id, const RayCastInput&) {
    const WorldState::ShapeRecord& r = s.shapes_[s.broadphase_.userData(id)];
    if (r.isSensor) return CastOutput{};
    return shapeCast(disc, Transform{}, translation, makeProxy(r.shape),
                     s.bodies_[static_cast<std::size_t>(r.body)].xf);
  });
}

std::vector<ShapeId> World::overlapAABB(const AABB& box, ProxyFilter filter) const {
  const WorldState& s = *s_;
  std::vector<ShapeId> out;
  for (ProxyId id : s.broadphase_.queryAABB(box, filter)) {
    const auto index = static_cast<std::int32_t>(s.broadphase_.userData(id));
    const WorldState::ShapeRecord& r = s.shapes_[static_cast<std::size_t>(index)];
    if (overlaps(computeAABB(r.shape, s.bodies_[static_cast<std::size_t>(r.body)].xf), box))
      out.push_back(s.shapeId(index));
  }
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation, ProxyFilter filter,
                                       Wake wake) {
  std::optional<WorldHit> hit = std::as_const(*this).castRay(origin, translation, filter);
  if (hit && wake == Wake::yes) s_->wakeBody(s_->body(hit->body));
  return hit;
}

std::vector<ShapeId> World::overlapAABB(const AABB& box, ProxyFilter filter, Wake wake) {
  std::vector<ShapeId> found = std::as_const(*this).overlapAABB(box, filter);
  if (wake == Wake::yes)
    for (ShapeId shape : found)
      s_->wakeBody(s_->body(bodyOf(shape)));
  return found;
}

std::vector<ShapeId> World::overlapPoint(Vec2 point, ProxyFilter filter) const {
  requireFinite("overlapPoint", "point", point);
  const WorldState& s = *s_;
  std::vector<ShapeId> out;
  for (ProxyId id : s.broadphase_.queryPoint(point, filter)) {
    const auto index = static_cast<std::int32_t>(s.broadphase_.userData(id));
    const WorldState::ShapeRecord& r = s.shapes_[static_cast<std::size_t>(index)];
    if (containsPoint(r.shape, s.bodies_[static_cast<std::size_t>(r.body)].xf, point))
      out.push_back(s.shapeId(index));
  }
  std::sort(out.begin(), out.end(), [](ShapeId a, ShapeId b) { return a.index < b.index; });
  return out;
}

}  // namespace rc
