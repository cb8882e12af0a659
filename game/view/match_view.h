// A match (game::MatchState) drawn as a render::Frame: the level (floor, merged tile walls,
// static walls, trigger zones), pickups, props by material (crates, barrels; darker as they are
// damaged; gone once destroyed), actors as discs in their team's colour with their facing and a
// health bar (the dead as a faint cross until they come back), grenades, shots as lines along
// their whole path (bounces and exits marked), explosions as rings of their blast radius, and a
// HUD band (tick, time, kills per team, the player's health, the top actors). The overlay adds
// what the autopilot perceives (perception_view.h). The renderer knows no game types: this is
// where the game and the renderer meet.
//
// The camera is fitted once to the level's bounds (Level::settings.bounds), below the HUD band;
// the view never moves. Shots and explosions last one tick in the match; a view fed every tick
// (observe) keeps them a few ticks more, fading, so that a frame shows what just happened.
#pragma once

#include <cstdint>
#include <deque>
#include <string>

#include "game/match/match.h"
#include "render/camera.h"
#include "render/draw_list.h"

namespace game {

struct MatchViewOptions {
  bool overlay = false;  // what bots perceive
  std::string caption;   // shown in the HUD band (the level's name)
};

class MatchView {
 public:
  // Ticks a shot and an explosion stay on screen (observe): 0.1 s and 0.4 s.
  static constexpr int kShotTicks = 6;
  static constexpr int kBlastTicks = 24;

  MatchView(const MatchState& s, int width, int height);

  const render::Camera& camera() const { return camera_; }
  // A pixel's size in metres.
  float pixel() const { return 1.0f / camera_.zoom; }
  // The HUD band's height in pixels (0 in frames too small for one).
  float bandHeight() const { return band_; }

  // After every tick: keeps this tick's shots and explosions for the next frames.
  void observe(const MatchState& s);
  // The match as it is now.
  render::Frame draw(const MatchState& s, const MatchViewOptions& options = {}) const;

 private:
  struct PastShot {
    std::int64_t tick = 0;
    Shot shot;
  };
  struct PastBlast {
    std::int64_t tick = 0;
    Explosion blast;
  };
  void drawProps(render::DrawList& list, const MatchState& s) const;
  void drawActors(render::DrawList& list, const MatchState& s) const;
  void drawShot(render::DrawList& list, const MatchState& s, const Shot& shot, float alpha) const;
  void drawBlast(render::DrawList& list, const Explosion& blast, float age) const;
  void drawHud(render::DrawList& hud, const MatchState& s, const MatchViewOptions& options) const;

  render::Camera camera_;
  rc::AABB bounds_{};  // what the camera was fitted to
  float band_ = 0.0f;
  render::DrawList statics_;  // the level's parts that never move (level_view.h)
  std::deque<PastShot> shots_;
  std::deque<PastBlast> blasts_;
  std::int64_t observed_ = -1;
};

}  // namespace game
