// The rules phase: what the step's events mean for the match, in this order: impacts (damage,
// deaths), trigger zones (kill zones, exits), grenades' bounces, pickups (back, then taken),
// then the respawns that are due.
#include "game/match/actors.h"
#include "game/rules/impacts.h"
#include "game/rules/pickups.h"
#include "game/rules/triggers.h"
#include "game/weapons/grenade.h"

namespace game {

void applyRules(MatchState& s) {
  applyImpacts(s);
  applyTriggers(s);
  countGrenadeBounces(s);
  updatePickups(s);
  for (std::size_t i = 0; i < s.actors.size(); ++i) {
    const Actor& a = s.actors[i];
    if (!a.alive && a.respawnTick >= 0 && a.respawnTick <= s.tick + 1)
      revive(s, i, respawnPoint(s, i));
  }
}

}  // namespace game
