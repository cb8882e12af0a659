// Hearing: sounds carry a loudness radius, walls shorten it, and a bot hears what reaches it.
//
// Sounds are made by the phases that cause them into MatchState::sounds: footsteps by movement
// (every kStrideTicks per actor, staggered by index, from kSilentSpeed on, their radius
// kFootstepSeconds times the speed: a running actor is heard 8 m away, a walking one not at all),
// shots by the weapons phase (kShotRadius, at the muzzle), blasts by explosions
// (kExplosionRadius). The next tick's decide phase hears them and the tick after forgets them.
//
// The rule for walls: a ray from the sound to the listener counts the static surfaces it enters
// (a wall, a block of tiles, a static prop; a wall made of several convex pieces counts each piece
// it crosses), and each one halves the radius. The listener hears the sound when its distance is
// within the halved radius: a shot 40 m loud is heard through one wall within 20 m, through three
// within 5 m. Listeners do not hear their own team (they know where their friends are) nor
// themselves. A sound heard is remembered as where its maker was (memory.h, kHeardStrength).
#pragma once

#include <cstddef>
#include <optional>

#include "game/match/match.h"

namespace game {

inline constexpr float kShotRadius = 40.0f;       // m
inline constexpr float kExplosionRadius = 60.0f;  // m
inline constexpr float kFootstepSeconds = 1.6f;   // radius per m/s of speed
inline constexpr float kSilentSpeed = 2.5f;       // m/s: slower is silent
inline constexpr int kStrideTicks = 20;
// Pieces of a wall closer than this along a ray (a seam between convex pieces, tiles side by
// side) count as one wall.
inline constexpr float kWallSeam = 0.01f;  // m

// Adds a sound made by actor `maker` now.
void makeSound(MatchState& s, SoundKind kind, std::size_t maker, rc::Vec2 position, float radius);

// The footstep of actor `actor` moving at `speed` this tick, if it is its stride's tick and it
// is fast enough to be heard (movement calls this).
void makeFootstep(MatchState& s, std::size_t actor, float speed);

// The walls between two points (static surfaces a ray from `from` enters on its way to `to`;
// pieces of one wall it crosses with no open space between, one wall), counted up to `limit`
// (more are not counted: the caller already knows enough).
int wallsBetween(const MatchState& s, rc::Vec2 from, rc::Vec2 to, int limit);

// Whether `listener` hears the sound (walls counted, the radius halved per wall); the walls when
// it does.
std::optional<int> hears(const MatchState& s, std::size_t listener, const Sound& sound);

// The listener's hearing this tick: every sound of MatchState::sounds it hears is remembered
// and listed in MatchState::heard.
void listen(MatchState& s, std::size_t listener);

}  // namespace game
