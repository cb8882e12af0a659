// What the overlay shows of what an actor perceives: its sight cone, the line-of-sight rays its
// look cast, where it heard sounds, the enemy it acts on (seen or remembered), where it walks and
// the path there; and every sound's hearing circle. Players on autopilot perceive like bots and
// are shown alike.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "game/bots/sight.h"
#include "game/match/match.h"
#include "render/draw_list.h"

namespace game {

struct PerceptionOverlay {
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
  std::vector<rc::Vec2> heard;   // where it heard something
  std::vector<rc::Vec2> path;    // the route it follows, from where it is
};

// Read from the match as the bots keep it (game/bots/bot_state.h: this tick's sight rays and
// hearings, the mind's focus, goal and route), for a living actor. A player driven by given
// input perceives and decides all the same (the autopilot's choice is replaced): shown alike.
PerceptionOverlay perceptionOf(const MatchState& s, std::size_t actor);

// Hearing circles: every sound made this tick, as far as it carries in the open (walls halve it).
void drawSounds(render::DrawList& overlay, const MatchState& s);

// Into the overlay, in the actor's team colour, the sight cone cut to `bounds` (the level's);
// `pixel` is a pixel's size in metres.
void drawPerception(render::DrawList& overlay, const PerceptionOverlay& p, render::Color team,
                    const rc::AABB& bounds, float pixel);

}  // namespace game
