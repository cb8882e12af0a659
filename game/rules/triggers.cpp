#include "game/rules/triggers.h"

#include <optional>
#include <vector>

#include "game/match/actors.h"
#include "game/match/input.h"
#include "game/rules/damage.h"
#include "game/rules/score.h"

namespace game {
namespace {

// The level trigger a sensor shape belongs to, if any.
const BuiltTrigger* triggerOf(const MatchState& s, const rc::ShapeRef& sensor) {
  const std::optional<LevelRef> ref = levelRefOf(sensor.bodyUserData);
  if (!ref || ref->kind != LevelObjectKind::trigger) return nullptr;
  for (const BuiltTrigger& t : s.built.triggers)
    if (t.object == ref->index) return &t;
  return nullptr;
}

// The actor leaves through the exit and comes back in at its respawn point.
void leaveThroughExit(MatchState& s, std::size_t actor) {
  scoreExit(s, actor);
  const Actor& a = s.actors[actor];
  s.world->setTransform(a.body, respawnPoint(s, actor), 0.0f);
  s.world->setLinearVelocity(a.body, {});
  s.minds[actor] = BotMind{};
}

}  // namespace

void applyTriggers(MatchState& s) {
  // Events are copies made by the step: acting on them (killing, moving bodies) is safe. An
  // actor entering two shapes of one exit in a step leaves once.
  std::vector<bool> exited;
  for (const rc::SensorEvent& e : s.world->sensorEvents().begin) {
    const BuiltTrigger* trigger = triggerOf(s, e.sensor);
    const std::optional<GameRef> visitor = gameRefOf(e.visitor.bodyUserData);
    if (trigger == nullptr || !visitor || visitor->kind != GameKind::actor ||
        visitor->index >= s.actors.size() || !s.actors[visitor->index].alive)
      continue;
    if (trigger->action == "kill") {
      killActor(s, visitor->index, std::nullopt);
    } else if (trigger->action == "exit") {
      exited.resize(s.actors.size());
      if (exited[visitor->index]) continue;
      exited[visitor->index] = true;
      leaveThroughExit(s, visitor->index);
    }
  }
  // Hurt zones act on whoever is inside now, not on who entered: a tick's worth of the zone's
  // damage for each zone an actor overlaps, in actor order; dying of it is a suicide. Asked of
  // the world each tick, so nothing is kept.
  std::vector<bool> inside;
  for (const BuiltTrigger& t : s.built.triggers) {
    if (t.action != "hurt" || !(t.damagePerSecond > 0.0f)) continue;
    actorsInside(s, t.body, inside);
    const float perTick = t.damagePerSecond / static_cast<float>(kTicksPerSecond);
    for (std::size_t i = 0; i < s.actors.size(); ++i)
      if (inside[i] && s.actors[i].alive) damageActor(s, i, perTick, std::nullopt);
  }
}

void actorsInside(const MatchState& s, rc::BodyId zone, std::vector<bool>& inside) {
  // The query sees only actors' shapes, not the walls and props round the zone.
  constexpr rc::ProxyFilter kActorsOnly{0xFFFFFFFFu, kActorFilter.category};
  inside.assign(s.actors.size(), false);
  const rc::Transform at = s.world->transform(zone);
  for (const rc::ShapeId shape : s.world->shapesOf(zone)) {
    for (const rc::ShapeRef& r : s.world->overlapShape(s.world->shape(shape), at, kActorsOnly)) {
      const std::optional<GameRef> actor = gameRefOf(r.bodyUserData);
      if (actor && actor->kind == GameKind::actor && actor->index < s.actors.size())
        inside[actor->index] = true;
    }
  }
}

}  // namespace game
