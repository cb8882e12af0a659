// What the overlay shows of what an actor perceives: its sight cone, the line-of-sight rays its
// sight casts, the enemy it is after, where it is walking; and the slots for the senses still to
// come (hearing, memory, paths), so that each is a line in perceptionOf and nothing in the
// drawing. Players on autopilot perceive like bots and are shown alike.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "game/bots/sight.h"
#include "game/match/match.h"
#include "render/draw_list.h"

namespace game {

struct Perception {
  rc::Vec2 at{};     // the actor's centre
  float aim = 0.0f;  // radians: the cone's axis
  SightTuning sight;
  struct Ray {
    rc::Vec2 from{}, to{};
    bool clear = false;  // the ray reached what it was cast at
  };
  std::vector<Ray> sightRays;      // to every enemy inside the cone and range, seen or not
  std::optional<rc::Vec2> target;  // where the enemy it is after is (seen) or was (remembered)
  bool targetInSight = false;
  std::optional<rc::Vec2> goal;  // where it walks while it is after no one
  float hearingRadius = 0.0f;    // m; 0: no hearing circle
  std::vector<rc::Vec2> heard;   // where it heard something
  std::vector<rc::Vec2> path;    // the route it follows, from where it is
};

// Read from the match as the bots keep it today (game/bots: sight, BotMind), for a living actor.
// A player driven by recorded input has a mind the autopilot no longer updates: its target and
// goal are stale, its cone and rays still true.
Perception perceptionOf(const MatchState& s, std::size_t actor);

// Into the overlay, in the actor's team colour, the sight cone cut to `bounds` (the level's);
// `pixel` is a pixel's size in metres.
void drawPerception(render::DrawList& overlay, const Perception& p, render::Color team,
                    const rc::AABB& bounds, float pixel);

}  // namespace game
