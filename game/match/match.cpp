#include "game/match/match.h"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "game/level/level_hash.h"
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
  rc::WorldDef def = levelWorldDef(s_.level);
  def.maxSolverLanes = config.solverLanes;
  s_.world = std::make_unique<rc::World>(def);
  s_.built = buildLevel(s_.level, *s_.world);
  s_.levelHash = levelContentHash(s_.level, s_.world->stateHash());
  s_.nav = buildNavGrid(s_.level, s_.built, *s_.world, s_.tuning.radius);
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
  s.sightRays.clear();
  s.heard.clear();
  if (!s.config.profile) {
    decideBots(s, inputs);
    s.sounds.clear();  // heard (or not) by now; this tick's are made from here on
    moveActors(s);
    fireWeapons(s);
    s.world->step(kTickSeconds);
    applyRules(s);
  } else {
    // The same phases, each timed (decideBots times its senses apart from its decisions).
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point& t) {
      const Clock::time_point now = Clock::now();
      const double seconds = std::chrono::duration<double>(now - t).count();
      t = now;
      return seconds;
    };
    MatchProfile& p = s.profile;
    Clock::time_point t = Clock::now();
    const double perceptionBefore = p.perception;
    decideBots(s, inputs);
    s.sounds.clear();
    p.decisions += since(t) - (p.perception - perceptionBefore);
    moveActors(s);
    p.movement += since(t);
    fireWeapons(s);
    p.weapons += since(t);
    s.world->step(kTickSeconds);
    p.physics += since(t);
    applyRules(s);
    p.rules += since(t);
    ++p.ticks;
  }
  ++s.tick;
  if (s.config.testHook) s.config.testHook(s);
}

}  // namespace game
