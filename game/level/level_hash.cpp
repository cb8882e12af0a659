#include "game/level/level_hash.h"

#include <bit>
#include <string>

#include "physics/bytes.h"

namespace game {
namespace {

class Hasher {
 public:
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) {
      h_ ^= p[k];
      h_ *= rc::kFnvPrime;
    }
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) {
      const auto b = static_cast<unsigned char>(v >> (8 * k));
      bytes(&b, 1);
    }
  }
  void f32(float v) { u64(std::bit_cast<std::uint32_t>(v)); }
  void vec(rc::Vec2 v) {
    f32(v.x);
    f32(v.y);
  }
  // Length first, so that "ab" + "c" and "a" + "bc" differ.
  void text(const std::string& s) {
    u64(s.size());
    bytes(s.data(), s.size());
  }
  void properties(const TiledProperties& p) {
    u64(p.list.size());
    for (const TiledProperty& q : p.list) {
      text(q.name);
      u64(static_cast<std::uint64_t>(q.type));
      text(q.text);
      u64(std::bit_cast<std::uint64_t>(q.number));
      u64(q.flag);
    }
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = rc::kFnvOffset;
};

}  // namespace

std::uint64_t levelContentHash(const Level& level, std::uint64_t builtWorldHash) {
  Hasher h;
  h.u64(builtWorldHash);
  const LevelSettings& s = level.settings;
  h.f32(s.pixelsPerMeter);
  h.vec(s.gravity);
  h.u64(static_cast<std::uint64_t>(s.width));
  h.u64(static_cast<std::uint64_t>(s.height));
  h.f32(s.tileWidth);
  h.f32(s.tileHeight);
  h.vec(s.bounds.lower);
  h.vec(s.bounds.upper);
  h.properties(s.properties);
  h.u64(level.objects.size());
  for (const LevelObject& o : level.objects) {
    h.u64(static_cast<std::uint64_t>(o.kind));
    h.u64(static_cast<std::uint64_t>(o.tiledId));
    h.text(o.layer);
    h.text(o.name);
    h.text(o.type);
    h.f32(o.material.thickness);
    h.f32(o.material.health);
    h.u64(o.material.hard);
    h.properties(o.properties);
  }
  h.u64(level.spawns.size());
  for (const LevelSpawn& p : level.spawns) {
    h.u64(static_cast<std::uint64_t>(p.kind));
    h.text(p.name);
    h.vec(p.position);
    h.f32(p.facing);
    h.u64(static_cast<std::uint64_t>(p.team));
    h.properties(p.properties);
  }
  h.u64(level.pickups.size());
  for (const LevelPickup& p : level.pickups) {
    h.text(p.name);
    h.text(p.item);
    h.f32(p.amount);
    h.f32(p.respawn);
    h.f32(p.radius);
    h.vec(p.position);
    h.properties(p.properties);
  }
  h.u64(level.triggers.size());
  for (const LevelTrigger& t : level.triggers) {
    h.u64(t.object);
    h.text(t.action);
  }
  h.u64(level.paths.size());
  for (const LevelPath& p : level.paths) {
    h.text(p.name);
    h.u64(p.points.size());
    for (rc::Vec2 q : p.points)
      h.vec(q);
    h.u64(p.loop);
    h.properties(p.properties);
  }
  h.u64(level.markers.size());
  for (const LevelMarker& m : level.markers) {
    h.text(m.name);
    h.text(m.type);
    h.vec(m.position);
    h.properties(m.properties);
  }
  return h.value();
}

}  // namespace game
