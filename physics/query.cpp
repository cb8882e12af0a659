// Queries: ray and shape casts, overlaps; each takes a filter (bitmask and callback) and names
// the shape, its body and their user data in what it finds.
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

void checkPlacedShape(const char* what, const Shape& shape, const Transform& xf) {
  try {
    validate(shape);
  } catch (const InvalidShape& e) {
    throw InvalidDefinition(std::string(what) + ": " + e.what());
  }
  requireFinite(what, "position", xf.p);
  requireFinite(what, "rotation", Vec2{xf.q.c, xf.q.s});
}

}  // namespace

bool WorldState::accepts(const QueryFilter& filter, std::int32_t shape) const {
  return !filter.accept || filter.accept(ref(shape));
}

template <class Exact>
std::optional<WorldHit> WorldState::closest(const RayCastInput& in, float radius,
                                            const QueryFilter& filter, Exact&& exact) const {
  // Ties go to the lower shape id (a proxy's userData), not the lower proxy id.
  const ProxyHit h = castClosest(
      broadphase_, in, radius, filter.bits,
      [&](ProxyId id, const RayCastInput& ray) {
        const auto shape = static_cast<std::int32_t>(broadphase_.userData(id));
        const ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
        if (r.isSensor || !accepts(filter, shape)) return CastOutput{};
        return exact(r, ray);
      },
      [this](ProxyId id) { return broadphase_.userData(id); });
  if (!h.out.hit) return std::nullopt;
  return hitOf(h);
}

WorldHit WorldState::hitOf(const ProxyHit& h) const {
  WorldHit hit;
  static_cast<ShapeRef&>(hit) = ref(static_cast<std::int32_t>(broadphase_.userData(h.id)));
  hit.point = h.out.point;
  hit.normal = h.out.normal;
  hit.fraction = h.out.fraction;
  return hit;
}

template <class Exact>
std::vector<ShapeRef> WorldState::overlapping(const AABB& box, const QueryFilter& filter,
                                              Exact&& exact) const {
  std::vector<std::int32_t> found;
  broadphase_.queryAABB(box, filter.bits, [&](ProxyId id) {
    const auto shape = static_cast<std::int32_t>(broadphase_.userData(id));
    const ShapeRecord& r = shapes_[static_cast<std::size_t>(shape)];
    if (exact(r) && accepts(filter, shape)) found.push_back(shape);
    return true;
  });
  std::sort(found.begin(), found.end());
  std::vector<ShapeRef> out;
  out.reserve(found.size());
  for (std::int32_t shape : found)
    out.push_back(ref(shape));
  return out;
}

const Transform& WorldState::transformOf(const ShapeRecord& r) const {
  return bodies_[static_cast<std::size_t>(r.body)].xf;
}

// ----------------------------------------------------------------------------------- casts

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation,
                                       const QueryFilter& filter) const {
  checkCast("castRay", origin, translation);
  const WorldState& s = *s_;
  return s.closest({origin, translation, 1.0f}, 0.0f, filter,
                   [&s](const WorldState::ShapeRecord& r, const RayCastInput& ray) {
                     return rayCast(r.shape, s.transformOf(r), ray);
                   });
}

std::vector<WorldHit> World::castRayAll(Vec2 origin, Vec2 translation,
                                        const QueryFilter& filter) const {
  checkCast("castRayAll", origin, translation);
  const WorldState& s = *s_;
  std::vector<WorldHit> out;
  for (const ProxyHit& h : castAll(
           s.broadphase_, {origin, translation, 1.0f}, 0.0f, filter.bits,
           [&s, &filter](ProxyId id, const RayCastInput&ray) {
             const auto shape = static_cast<std::int32_t>(s.broadphase_.userData(id));
             const WorldState::ShapeRecord& r = s.shapes_[static_cast<std::size_t>(shape)];
             if (r.isSensor || !s.accepts(filter, shape)) return CastOutput{};
             return rayCast(r.shape, s.transformOf(r), ray);
           },
           [&s](ProxyId id) { return s.broadphase_.userData(id); }))
    out.push_back(s.hitOf(h));
  return out;
}

std::optional<WorldHit> World::castCircle(Vec2 center, float radius, Vec2 translation,
                                          const QueryFilter& filter) const {
  checkCast("castCircle", center, translation);
  if (!(radius > 0.0f) || !std::isfinite(radius))
    failDefinition("castCircle", "radius", "is " + formatNumber(radius) + " (must be > 0)");
  const ShapeProxy disc = makeProxy(&center, 1, radius);
  const WorldState& s = *s_;
  return s.closest({center, translation, 1.0f}, radius, filter,
                   [&](const WorldState::ShapeRecord& r, const RayCastInput&) {
                     return shapeCast(disc, Transform{}, translation, makeProxy(r.shape),
                                      s.transformOf(r));
                   });
}

std::optional<WorldHit> World::castShape(const Shape& shape, const Transform& start,
                                         Vec2 translation, const QueryFilter& filter) const {
  checkPlacedShape("castShape", shape, start);
  requireFinite("castShape", "translation", translation);
  // The broadphase sweeps the shape's bounding circle; the exact test, the shape.
  const BoundingCircle bound = computeBoundingCircle(shape);
  const ShapeProxy mover = makeProxy(shape);
  const WorldState& s = *s_;
  return s.closest({apply(start, bound.center), translation, 1.0f}, bound.radius, filter,
                   [&](const WorldState::ShapeRecord& r, const RayCastInput&) {
                     return shapeCast(mover, start, translation, makeProxy(r.shape),
                                      s.transformOf(r));
                   });
}

std::optional<WorldHit> World::castRay(Vec2 origin, Vec2 translation, const QueryFilter& filter,
                                       Wake wake) {
  std::optional<WorldHit> hit = std::as_const(*this).castRay(origin, translation, filter);
  if (hit && wake == Wake::yes) s_->wakeBody(s_->body(hit->body));
  return hit;
}

// -------------------------------------------------------------------------------- overlaps

std::vector<ShapeRef> World::overlapAABB(const AABB& box, const QueryFilter& filter) const {
  requireFinite("overlapAABB", "lower", box.lower);
  requireFinite("overlapAABB", "upper", box.upper);
  const WorldState& s = *s_;
  return s.overlapping(box, filter, [&](const WorldState::ShapeRecord& r) {
    return overlaps(computeAABB(r.shape, s.transformOf(r)), box);
  });
}

std::vector<ShapeRef> World::overlapPoint(Vec2 point, const QueryFilter& filter) const {
  requireFinite("overlapPoint", "point", point);
  const WorldState& s = *s_;
  return s.overlapping({point, point}, filter, [&](const WorldState::ShapeRecord& r) {
    return containsPoint(r.shape, s.transformOf(r), point);
  });
}

std::vector<ShapeRef> World::overlapShape(const Shape& shape, const Transform& where,
                                          const QueryFilter& filter) const {
  checkPlacedShape("overlapShape", shape, where);
  const WorldState& s = *s_;
  return s.overlapping(computeAABB(shape, where), filter, [&](const WorldState::ShapeRecord& r) {
    return testOverlap(shape, where, r.shape, s.transformOf(r));
  });
}

std::vector<ShapeRef> World::overlapAABB(const AABB& box, const QueryFilter& filter, Wake wake) {
  std::vector<ShapeRef> found = std::as_const(*this).overlapAABB(box, filter);
  if (wake == Wake::yes)
    for (const ShapeRef& r : found)
      s_->wakeBody(s_->body(r.body));
  return found;
}

std::vector<ShapeRef> World::overlapShape(const Shape& shape, const Transform& where,
                                          const QueryFilter& filter, Wake wake) {
  std::vector<ShapeRef> found = std::as_const(*this).overlapShape(shape, where, filter);
  if (wake == Wake::yes)
    for (const ShapeRef& r : found)
      s_->wakeBody(s_->body(r.body));
  return found;
}

}  // namespace rc
