#include "game/match/match.h"

#include <bit>
#include <stdexcept>
#include <utility>

#include "game/match/actors.h"
#include "game/rules/pickups.h"
#include "game/rules/score.h"
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
  for (std::size_t i = 0; i < s_.level.objects.size(); ++i) {
    const LevelObject& o = s_.level.objects[i];
    const bool destructible = o.material.health > 0.0f;
    if (!destructible && o.bodyType != rc::BodyType::dynamicBody) continue;
    PropState p;
    p.object = i;
    p.body = s_.built.bodies[i];
    p.health = destructible ? o.material.health : 0.0f;
    p.destructible = destructible;
    s_.props.push_back(p);
  }
  s_.pickups = makePickups(s_.level, s_.built, s_.weapons);
  spawnActors(s_);
  makeTeams(s_);
}

void Match::tick(std::span<const PlayerInput> inputs) {
  MatchState& s = s_;
  s.shots.clear();
  s.explosions.clear();
  s.crashes.clear();
  decideBots(s, inputs);
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
  auto mixInt = [&](std::int64_t v, int bytes) { mix(static_cast<std::uint64_t>(v), bytes); };
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
    mixInt(a.suicides, 4);
    mixInt(a.exits, 4);
    mixInt(a.score, 4);
    mixInt(a.blamed, 4);
    mixInt(a.blamedTick, 8);
    mix(static_cast<std::uint32_t>(a.cooldown), 4);
    for (std::size_t w = 0; w < s_.weapons.weapons.size(); ++w)
      mix(static_cast<std::uint32_t>(a.ammo[w]), 4);
    for (std::uint8_t b : toBytes(a.input))
      mix(b, 1);
  }
  for (const PropState& p : s_.props) {
    mixInt(static_cast<std::int64_t>(p.object), 4);
    mixFloat(p.health);
    mix(p.destructible, 1);
    mix(p.destroyed, 1);
    mixInt(p.blamed, 4);
    mixInt(p.blamedTick, 8);
  }
  for (const PickupState& p : s_.pickups) {
    mixInt(p.pickup, 4);
    mix(static_cast<std::uint8_t>(p.item), 1);
    mix(p.weapon, 1);
    mixFloat(p.amount);
    mixFloat(p.position.x);
    mixFloat(p.position.y);
    mixFloat(p.radius);
    mixInt(p.respawnTicks, 4);
    mix(p.available, 1);
    mixInt(p.respawnTick, 8);
    mixInt(p.takenBy, 4);
    mixInt(p.timesTaken, 4);
  }
  for (const TeamScore& t : s_.teams) {
    for (const std::int32_t v : {t.team, t.kills, t.deaths, t.suicides, t.exits, t.score})
      mixInt(v, 4);
  }
  for (const Grenade& g : s_.grenades) {
    mix(g.live, 1);
    mix(g.thrower, 4);
    mix(g.weapon, 1);
    mix(static_cast<std::uint32_t>(g.fuse), 4);
    mix(static_cast<std::uint32_t>(g.bounces), 4);
  }
  return h;
}

}  // namespace game
