#include "game/weapons/shotgun.h"

#include "game/weapons/hitscan.h"
#include "physics/trig.h"

namespace game {

float pelletAngle(rc::Random& rng, float aim, const HitscanSpec& weapon) {
  if (weapon.spread == 0.0f) return aim;
  return aim + rng.uniform(-weapon.spread, weapon.spread);
}

void firePellets(MatchState& s, std::size_t shooter, std::size_t weapon) {
  const HitscanSpec& w = s.weapons.weapons[weapon].hitscan;
  const Actor& a = s.actors[shooter];
  const rc::Vec2 from = s.world->worldCenter(a.body);
  const float aim = a.aim;
  for (int pellet = 0; pellet < w.pellets; ++pellet) {
    const rc::SinCos sc = rc::sincos(pelletAngle(s.rng, aim, w));
    traceShot(s, shooter, weapon, pellet, from, {sc.cosine, sc.sine});
  }
}

}  // namespace game
