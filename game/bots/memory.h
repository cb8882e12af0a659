// Memory: what a bot perceived, and how sure it still is. Bots act on this, never on the match's
// state: an enemy it has not seen or heard does not exist for it.
//
// A bot remembers up to kMemorySlots actors, one entry each: where the actor was, how it moved,
// when and how it was perceived. Confidence starts at the perception's strength (sight 1,
// hearing kHeardStrength: a sound gives a place, not a sight of who made it) and fades linearly to
// zero over kSeenFadeTicks or kHeardFadeTicks; at zero the entry is forgotten. A new perception of
// an actor replaces its entry when it is at least as strong as what the entry is still worth
// (what a bot sees overrides what it heard; a sound does not override a fresh sighting); an
// actor not yet remembered takes a free slot, or the weakest (ties to the lower slot).
#pragma once

#include <cstdint>

#include "game/bots/bot_state.h"
#include "game/match/input.h"

namespace game {

inline constexpr float kHeardStrength = 0.75f;
inline constexpr std::int64_t kSeenFadeTicks = 6 * kTicksPerSecond;
inline constexpr std::int64_t kHeardFadeTicks = 4 * kTicksPerSecond;

// What a sense reports.
struct Perception {
  std::int32_t actor = -1;
  Sense sense = Sense::seen;
  rc::Vec2 position{}, velocity{};
  float strength = 1.0f;
};

// An entry's confidence at tick `now`: its strength fading to 0 (0 for an empty slot).
float confidence(const MemoryEntry& entry, std::int64_t now);

// Records a perception made at tick `now`.
void remember(BotMind& mind, const Perception& p, std::int64_t now);

// Empties the slots whose confidence has faded to zero.
void forgetFaded(BotMind& mind, std::int64_t now);

// The slot with the highest confidence now (ties to the lower slot), or -1 when it remembers
// nothing.
std::int32_t strongestMemory(const BotMind& mind, std::int64_t now);

// Whether the entry was seen by the bot's latest look: the thing is in sight as far as it knows.
bool inSight(const BotMind& mind, const MemoryEntry& entry);

// Where the entry's actor is expected at tick `now`: seen ones moved on by their velocity for up
// to `horizon` ticks.
rc::Vec2 expectedPosition(const MemoryEntry& entry, std::int64_t now, std::int64_t horizon);

}  // namespace game
