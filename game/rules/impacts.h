// Impacts: bodies that meet fast hurt each other. A contact hit event (rc::ContactHitEvent) whose
// approach speed v is above RuleTuning::impactSpeed v0 deals to each side that can be hurt (a
// living actor, a destructible prop)
//
//     D = k * mu * (v - v0),   mu = m_a m_b / (m_a + m_b)   (the dynamic side's mass against a
//                                                              static or kinematic body)
//
// k = RuleTuning::impactDamage: D is k per N s of the impulse a perfectly inelastic collision at
// the speed above the threshold transfers, so a heavy crate hurts more than a light grenade and
// an actor thrown against a wall is hurt by its own mass. Two actors meeting never hurt each
// other (walking head on closes at 10 m/s: that is movement, not an impact). One crash per pair
// of bodies per step, the fastest of their shapes' contacts.
//
// The credit for a kill (score.h): the thrower of a grenade that struck; otherwise the thrower of
// the latest blast that pushed either body within RuleTuning::blameTicks (a crate a blast threw,
// an actor it threw against a wall); otherwise no one (a suicide).
#pragma once

#include <cstddef>
#include <cstdint>

#include "game/match/match.h"

namespace game {

// The pair's reduced mass; a mass of 0 (static, kinematic) counts as infinite.
float reducedMass(float massA, float massB);
// D above for an approach speed `speed` (m/s) and reduced mass `mu` (kg); 0 at or below v0.
float impactDamage(const RuleTuning& rules, float mu, float speed);

// The body with user data `userData` (an actor or a level prop) was pushed by a blast of
// `thrower`'s grenade now: `thrower` is credited with its impacts for a while.
void blameBlast(MatchState& s, std::uint64_t userData, std::size_t thrower);

// The step's hit events turned into damage (recorded in MatchState::crashes), in the order the
// world reports them.
void applyImpacts(MatchState& s);

}  // namespace game
