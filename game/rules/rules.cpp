// The rules phase: what the step's events mean for the match (trigger zones, grenades'
// bounces), then the respawns that are due.
#include <string>

#include "game/match/actors.h"
#include "game/rules/damage.h"
#include "game/weapons/grenade.h"

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

}  // namespace

void applyRules(MatchState& s) {
  // Events are copies made by the step: acting on them (killing, disabling bodies) is safe.
  for (const rc::SensorEvent& e : s.world->sensorEvents().begin) {
    const BuiltTrigger* trigger = triggerOf(s, e.sensor);
    const std::optional<GameRef> visitor = gameRefOf(e.visitor.bodyUserData);
    if (trigger == nullptr || !visitor || visitor->kind != GameKind::actor) continue;
    if (trigger->action == "kill") killActor(s, visitor->index, std::nullopt);
  }
  countGrenadeBounces(s);
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    const Actor& a = s.actors[i];
    if (!a.alive && a.respawnTick >= 0 && a.respawnTick <= s.tick + 1)
      revive(s, i, respawnPoint(s, i));
  }
}

}  // namespace game
