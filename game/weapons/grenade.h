// Grenades: thrown as dynamic circle bodies (bullets: continuous collision against walls and
// moving bodies alike) that bounce by their material (restitution and friction from the weapon
// table, mixed with what they meet as the engine mixes: the larger restitution, the geometric
// mean of frictions), roll to a stop by their damping, and explode when their fuse runs out.
// Created in the weapons phase and destroyed there, between steps; their bodies and shapes carry
// gameUserData(GameKind::projectile, slot).
//
// Their bounces are counted (Grenade::bounces). A direct hit hurts only as any impact does
// (rules/impacts.h, the thrower credited): a 0.094 kg grenade is a thrown stone, a few points
// (4 at 17 m/s against a standing actor, 6 against one running at it); the blast is what a grenade
// is for, and a direct hit that hurt more would make it a slow hitscan weapon with a cooldown.
#pragma once

#include <cstddef>

#include "game/match/match.h"

namespace game {

// The collision category of grenades: shots do not see them (hitscan.h), everything else does.
inline constexpr rc::ProxyFilter kProjectileFilter{1u << 4, 0xFFFFFFFFu};

// A grenade of weapon `weapon` thrown by the actor along its aim, at the weapon's muzzle velocity
// plus the thrower's own velocity. It leaves the hand just outside the thrower's disc, or nearer
// if a wall is closer than that (never inside the wall).
void throwGrenade(MatchState& s, std::size_t thrower, std::size_t weapon);

// Every live grenade's fuse shortened by a tick; those that reach zero leave the world and
// explode where they are, in slot order.
void explodeDueGrenades(MatchState& s);

// The step's hit events that involve a grenade, counted as its bounces (the rules phase).
void countGrenadeBounces(MatchState& s);

}  // namespace game
