// Everything bots keep in MatchState, in one place: what each bot remembers and plans
// (BotMind), the sounds made in the last tick (Sound), and what perception did this tick for the
// view (SightRay, HeardSound).
//
// All of it is plain data (fixed-size fields, no pointers; vectors of these structs live in
// MatchState), so that a snapshot can copy it and a hash can walk it. forEachField() lists every
// field of each struct once: Match::hash() walks those lists, and a serializer should too (a
// field added to a struct and not to its list is a bug the static_asserts on sizes catch).
//
// The navigation grid (navigation.h) is not here: it is derived from the level, rebuilt
// identically by every match on it, and so needs neither hashing nor saving.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "physics/math.h"

namespace game {

// What a bot is doing (brain.cpp says when each applies).
enum class Behaviour : std::uint8_t {
  patrol,       // nothing perceived: walking between places of the level
  investigate,  // an enemy heard, not seen: going to where the sound came from
  chase,        // an enemy seen, now out of sight: going to where it was last seen
  attack,       // an enemy in sight: shooting it, with aim error, at a fighting distance
  takeCover,    // hurt and hit again: going to a place the enemy cannot see, firing back
  flee,         // hurt and hit again, no cover near: running away from the enemy
  fetch,        // hurt or short of rounds, no enemy in sight: going to a pickup that gives it
};
const char* behaviourName(Behaviour behaviour);

// How a memory entry was last perceived.
enum class Sense : std::uint8_t { none, seen, heard };

// One thing a bot remembers about one actor (memory.h: how confidence fades).
struct MemoryEntry {
  std::int32_t actor = -1;    // whom; -1: an empty slot
  Sense sense = Sense::none;  // how it was last perceived
  rc::Vec2 position{};        // where it was then
  rc::Vec2 velocity{};        // how it moved then (seen only; zero when heard)
  std::int64_t tick = -1;     // when
  float strength = 0.0f;      // the confidence it had then (sight 1, hearing less)
};

inline constexpr std::size_t kMemorySlots = 4;
inline constexpr std::size_t kRouteWaypoints = 24;

// A planned walk: the waypoints of a smoothed grid path (navigation.h), the first
// kRouteWaypoints of it; `partial` when the path had more (the walk is planned again from its end).
struct NavRoute {
  std::array<rc::Vec2, kRouteWaypoints> points{};
  std::uint8_t length = 0;  // waypoints in use
  std::uint8_t next = 0;    // the one it walks to
  std::uint8_t partial = 0;
  rc::Vec2 target{};          // where it was planned to go
  std::int64_t planned = -1;  // the tick it was planned; -1: no route
};

// What a bot (or a player on autopilot) keeps between ticks: only what it perceived or chose.
struct BotMind {
  Behaviour behaviour = Behaviour::patrol;
  std::int64_t behaviourSince = 0;  // the tick it started what it is doing
  std::int64_t lastLook = -1;       // the last tick its sight ran (memory.h: "in sight")
  std::array<MemoryEntry, kMemorySlots> memory{};
  std::int32_t focus = -1;  // the memory slot it acts on this tick; -1: none
  NavRoute route;
  rc::Vec2 goal{};              // patrol: where it walks; cover, flee: the spot it chose
  std::int64_t goalTick = -1;   // when it chose that goal; -1: none
  float strafe = 1.0f;          // which way it sidesteps while shooting
  std::int32_t stuckTicks = 0;  // ticks it has wanted to move and barely moved
  float health = 0.0f;          // its health at its last decision (less now: it was hit)
};

enum class SoundKind : std::uint8_t { footstep, shot, explosion };
const char* soundKindName(SoundKind kind);

// A sound, made by the phase that causes it (hearing.h: how far it carries).
struct Sound {
  SoundKind kind = SoundKind::footstep;
  std::int32_t maker = -1;  // the actor who made it
  std::int32_t team = -1;   // the maker's team
  rc::Vec2 position{};
  float radius = 0.0f;  // m: heard within this in the open (walls between shorten it)
};

// For the view: a line-of-sight ray a bot cast this tick (to an enemy inside its cone).
struct SightRay {
  std::int32_t viewer = -1, target = -1;
  rc::Vec2 from{}, to{};  // to: where it stopped (the target's centre when clear; a point
                          // inside the wall when the grid knew the wall was there)
  bool clear = false;     // it reached the target: seen
};

// For the view: a sound a listener heard this tick (sounds it did not hear are not listed). The
// sound is copied: MatchState::sounds holds, once the tick is over, the sounds made during it.
struct HeardSound {
  std::int32_t listener = -1;
  Sound sound;
  std::int32_t walls = 0;  // walls between the sound and the listener
  float radius = 0.0f;     // the sound's radius once the walls halved it
};

// Every field, once, in declaration order; const or not (the hash reads, a snapshot writes).
template <class T, class U>
concept Either = std::is_same_v<std::remove_const_t<T>, U>;

template <Either<MemoryEntry> E, class F>
void forEachField(E& e, F&& f) {
  f(e.actor), f(e.sense), f(e.position), f(e.velocity), f(e.tick), f(e.strength);
}
template <Either<NavRoute> R, class F>
void forEachField(R& r, F&& f) {
  for (auto& p : r.points)
    f(p);
  f(r.length), f(r.next), f(r.partial), f(r.target), f(r.planned);
}
template <Either<BotMind> M, class F>
void forEachField(M& m, F&& f) {
  f(m.behaviour), f(m.behaviourSince), f(m.lastLook);
  for (auto& e : m.memory)
    forEachField(e, f);
  f(m.focus);
  forEachField(m.route, f);
  f(m.goal), f(m.goalTick), f(m.strafe), f(m.stuckTicks), f(m.health);
}
template <Either<Sound> S, class F>
void forEachField(S& s, F&& f) {
  f(s.kind), f(s.maker), f(s.team), f(s.position), f(s.radius);
}

// Plain data, and the sizes the field lists above were written for: a new field changes a size
// and stops the build here until it is listed.
static_assert(std::is_trivially_copyable_v<BotMind> && std::is_trivially_copyable_v<Sound>);
static_assert(sizeof(MemoryEntry) == 40);
static_assert(sizeof(NavRoute) == kRouteWaypoints * 8 + 24);
static_assert(sizeof(BotMind) == 24 + kMemorySlots * 40 + 8 + sizeof(NavRoute) + 32);
static_assert(sizeof(Sound) == 24);

}  // namespace game
