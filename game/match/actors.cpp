#include "game/match/actors.h"

#include <limits>
#include <stdexcept>

#include "game/weapons/weapons.h"

namespace game {
namespace {

std::vector<const LevelSpawn*> spawnsOf(const MatchState& s, SpawnKind kind) {
  std::vector<const LevelSpawn*> out;
  for (const LevelSpawn& spawn : s.built.spawns)
    if (spawn.kind == kind) out.push_back(&spawn);
  return out;
}

SpawnKind spawnKindOf(ActorKind kind) {
  return kind == ActorKind::player ? SpawnKind::player : SpawnKind::bot;
}

}  // namespace

void spawnActors(MatchState& s) {
  const std::vector<const LevelSpawn*> players = spawnsOf(s, SpawnKind::player);
  const std::vector<const LevelSpawn*> bots = spawnsOf(s, SpawnKind::bot);
  if (s.config.players > 0 && players.empty())
    throw std::invalid_argument(s.level.source + ": the level has no player spawn");
  const int botCount = s.config.bots < 0 ? static_cast<int>(bots.size()) : s.config.bots;
  if (botCount > 0 && bots.empty())
    throw std::invalid_argument(s.level.source + ": the level has no bot spawn");
  auto add = [&](ActorKind kind, const LevelSpawn& spawn, int number) {
    Actor a;
    a.kind = kind;
    // The spawn's team (a level can set bots against bots, or a bot on the player's side);
    // without one, players are team 0 and bots team 1.
    a.team = spawn.team >= 0 ? spawn.team : defaultTeam(spawn.kind);
    a.name = (kind == ActorKind::player ? "player " : "bot ") + std::to_string(number + 1);
    a.health = s.tuning.health;
    arm(a, s.weapons);
    a.aim = spawn.facing;
    const std::size_t index = s.actors.size();
    rc::BodyDef def;
    def.type = rc::BodyType::dynamicBody;
    def.position = spawn.position;
    def.fixedRotation = true;
    def.userData = gameUserData(GameKind::actor, index);
    a.body = s.world->createBody(def);
    rc::ShapeDef sd;
    sd.density = s.tuning.density;
    sd.friction = 0.0f;  // actors slide along walls
    sd.filter = kActorFilter;
    sd.userData = def.userData;
    s.world->createShape(a.body, rc::makeCircle({}, s.tuning.radius), sd);
    s.actors.push_back(a);
    s.minds.emplace_back();
  };
  for (int i = 0; i < s.config.players; ++i)
    add(ActorKind::player, *players[static_cast<std::size_t>(i) % players.size()], i);
  for (int i = 0; i < botCount; ++i)
    add(ActorKind::bot, *bots[static_cast<std::size_t>(i) % bots.size()], i);
}

rc::Vec2 respawnPoint(const MatchState& s, std::size_t actor) {
  const Actor& me = s.actors[actor];
  const std::vector<const LevelSpawn*> spawns = spawnsOf(s, spawnKindOf(me.kind));
  const LevelSpawn* best = spawns.front();
  float bestDistance = -1.0f;
  for (const LevelSpawn* spawn : spawns) {
    // Its distance to the nearest living enemy.
    float nearest = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < s.actors.size(); ++i) {
      const Actor& other = s.actors[i];
      if (i == actor || !other.alive || other.team == me.team) continue;
      nearest =
          std::min(nearest, rc::distanceSquared(spawn->position, s.world->worldCenter(other.body)));
    }
    if (nearest > bestDistance) {
      bestDistance = nearest;
      best = spawn;
    }
  }
  return best->position;
}

void revive(MatchState& s, std::size_t actor, rc::Vec2 where) {
  Actor& a = s.actors[actor];
  a.alive = true;
  a.health = s.tuning.health;
  a.respawnTick = -1;
  a.cooldown = 0;
  a.blamed = -1;
  a.blamedTick = -1;
  arm(a, s.weapons);
  s.minds[actor] = BotMind{};
  s.world->setTransform(a.body, where, 0.0f);
  s.world->setLinearVelocity(a.body, {});
  s.world->setEnabled(a.body, true);
}

}  // namespace game
