#include "game/match/match.h"

#include <bit>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "game/match/actors.h"
#include "game/weapons/weapon_table.h"

namespace game {

std::optional<GameRef> gameRefOf(std::uint64_t userData) {
  if ((userData & (std::uint64_t{0xFF} << 56)) != kGameUserDataTag) return std::nullopt;
  const auto kind = static_cast<std::uint8_t>(userData >> 48);
  if (kind > static_cast<std::uint8_t>(GameKind::projectile)) return std::nullopt;
  return GameRef{static_cast<GameKind>(kind), static_cast<std::size_t>(userData & 0xFFFFFFFFu)};
}

Match::Match(Level level, const MatchConfig& config) {
  if (config.players < 0 || config.bots < -1)
    throw std::invalid_argument("match: players and bots must not be negative");
  s_.level = std::move(level);
  s_.config = config;
  s_.rng = rc::Random(config.seed);
  s_.weapons = config.weapons ? *config.weapons : loadWeaponTable(bundledWeaponTablePath());
  s_.world = std::make_unique<rc::World>(levelWorldDef(s_.level));
  s_.built = buildLevel(s_.level, *s_.world);
  s_.nav = buildNavGrid(s_.level, s_.built, *s_.world, s_.tuning.radius);
  for (std::size_t i = 0; i < s_.level.objects.size(); ++i) {
    const LevelObject& o = s_.level.objects[i];
    if (o.material.health > 0.0f) s_.props.push_back({i, s_.built.bodies[i], o.material.health});
  }
  spawnActors(s_);
}

void Match::tick(std::span<const PlayerInput> inputs) {
  MatchState& s = s_;
  s.shots.clear();
  s.explosions.clear();
  s.sightRays.clear();
  s.heard.clear();
  decideBots(s, inputs);
  s.sounds.clear();  // heard (or not) by now; this tick's are made from here on
  moveActors(s);
  fireWeapons(s);
  s.world->step(kTickSeconds);
  applyRules(s);
  ++s.tick;
}

std::uint64_t Match::hash() const {
  std::uint64_t h = 0xcbf29ce484222325ull;
  auto mix = [&](std::uint64_t bits, int bytes) {
    for (int k = 0; k < bytes; ++k) {
      h ^= (bits >> (8 * k)) & 0xFFu;
      h *= 0x100000001b3ull;
    }
  };
  auto mixFloat = [&](float f) { mix(std::bit_cast<std::uint32_t>(f), 4); };
  auto mixField = [&](const auto& v) {
    using T = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<T, rc::Vec2>) {
      mixFloat(v.x);
      mixFloat(v.y);
    } else if constexpr (std::is_same_v<T, float>) {
      mixFloat(v);
    } else {
      static_assert(std::is_integral_v<T> || std::is_enum_v<T>);
      mix(static_cast<std::uint64_t>(v), static_cast<int>(sizeof(T)));
    }
  };
  mix(s_.world->stateHash(), 8);
  mix(static_cast<std::uint64_t>(s_.tick), 8);
  mix(s_.rng.state(), 8);
  for (const Actor& a : s_.actors) {
    mix(a.alive, 1);
    mixFloat(a.health);
    mixFloat(a.aim);
    mix(static_cast<std::uint64_t>(a.respawnTick), 8);
    mix(static_cast<std::uint32_t>(a.kills), 4);
    mix(static_cast<std::uint32_t>(a.deaths), 4);
    mix(static_cast<std::uint32_t>(a.cooldown), 4);
    for (std::size_t w = 0; w < s_.weapons.weapons.size(); ++w)
      mix(static_cast<std::uint32_t>(a.ammo[w]), 4);
    for (std::uint8_t b : toBytes(a.input))
      mix(b, 1);
  }
  for (const PropState& p : s_.props) {
    mixFloat(p.health);
    mix(p.destroyed, 1);
  }
  for (const Grenade& g : s_.grenades) {
    mix(g.live, 1);
    mix(g.thrower, 4);
    mix(g.weapon, 1);
    mix(static_cast<std::uint32_t>(g.fuse), 4);
    mix(static_cast<std::uint32_t>(g.bounces), 4);
  }
  for (const BotMind& m : s_.minds)
    forEachField(m, mixField);
  mix(s_.sounds.size(), 4);
  for (const Sound& sound : s_.sounds)
    forEachField(sound, mixField);
  return h;
}

}  // namespace game
