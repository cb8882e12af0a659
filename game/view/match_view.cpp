#include "game/view/match_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "game/view/level_view.h"
#include "game/view/palette.h"
#include "game/view/perception_view.h"
#include "game/view/shape_draw.h"

namespace game {
namespace {

namespace pal = palette;
using render::Color;
using render::Style;

rc::Vec2 unit(float angle) {
  return {std::cos(angle), std::sin(angle)};
}

// The level's area, or (a level without bounds) what its static bodies cover.
rc::AABB viewBounds(const MatchState& s) {
  const rc::AABB b = s.level.settings.bounds;
  if (b.isValid() && b.lower.x < b.upper.x && b.lower.y < b.upper.y) return b;
  rc::AABB box{{-10.0f, -10.0f}, {10.0f, 10.0f}};
  bool any = false;
  for (rc::BodyId id : s.world->bodies())
    for (rc::ShapeId sid : s.world->shapesOf(id)) {
      const rc::AABB a = rc::computeAABB(s.world->shape(sid), s.world->transform(id));
      box = any ? rc::unionOf(box, a) : a;
      any = true;
    }
  return box;
}

// "players" or "bots" when a team is all one kind, else "team N".
std::string teamName(const MatchState& s, int team) {
  bool players = false, bots = false;
  for (const Actor& a : s.actors)
    if (a.team == team) (a.kind == ActorKind::player ? players : bots) = true;
  if (players != bots) return players ? "players" : "bots";
  return "team " + std::to_string(team);
}

// A line's width in pixels, estimated: DejaVu Sans averages about 0.55 of its size per character
// in digits and lower case; 0.6 errs on the wide side.
float textWidth(const std::string& text, float size) {
  return 0.6f * size * static_cast<float>(text.size());
}

Color healthColor(float fraction) {
  return fraction > 0.5f ? pal::mix(pal::kAmmoPickup, pal::kHealthFull, 2.0f * fraction - 1.0f)
                         : pal::mix(pal::kHealthLow, pal::kAmmoPickup, 2.0f * fraction);
}

}  // namespace

MatchView::MatchView(const MatchState& s, int width, int height) {
  const float h = static_cast<float>(height);
  // The band and its text scale with the frame, as if it were 16:9 at most (a tall, narrow frame
  // has no room for large text).
  const float scale = std::min(h, 0.5625f * static_cast<float>(width));
  band_ = scale >= 120.0f ? std::clamp(std::round(0.06f * scale), 14.0f, 48.0f) : 0.0f;
  const float margin = std::min(8.0f, 0.05f * std::min(static_cast<float>(width), h - band_));
  bounds_ = viewBounds(s);
  camera_ = render::Camera::fit(bounds_, width, height - static_cast<int>(band_), margin);
  // The level centred in the frame below the band.
  camera_.height = height;
  camera_.center.y += 0.5f * band_ / camera_.zoom;
  // The whole frame's world rectangle, the band included.
  statics_ = drawLevelStatics(s.level, s.built, *s.world, camera_.visibleWorld(), pixel());
}

void MatchView::observe(const MatchState& s) {
  if (s.tick == observed_) return;
  observed_ = s.tick;
  for (const Shot& shot : s.shots)
    shots_.push_back({s.tick, shot});
  for (const Explosion& blast : s.explosions)
    blasts_.push_back({s.tick, blast});
  while (!shots_.empty() && s.tick - shots_.front().tick > kShotTicks)
    shots_.pop_front();
  while (!blasts_.empty() && s.tick - blasts_.front().tick > kBlastTicks)
    blasts_.pop_front();
}

void MatchView::drawProps(render::DrawList& list, const MatchState& s) const {
  std::vector<const PropState*> propOf(s.level.objects.size(), nullptr);
  for (const PropState& p : s.props)
    if (p.object < propOf.size()) propOf[p.object] = &p;
  for (std::size_t i = 0; i < s.level.objects.size() && i < s.built.bodies.size(); ++i) {
    const LevelObject& o = s.level.objects[i];
    const rc::BodyId body = s.built.bodies[i];
    const PropState* prop = propOf[i];
    if (prop && prop->destroyed) continue;
    if (!s.world->isValid(body)) continue;
    const bool moves = s.world->type(body) != rc::BodyType::staticBody;
    if (o.kind != LevelObjectKind::prop && !moves) continue;  // drawn once, with the level
    const rc::Transform xf = s.world->transform(body);
    if (o.kind != LevelObjectKind::prop) {  // a wall that moves
      for (const rc::Shape& shape : o.shapes)
        drawShape(list, shape, xf, Style::both(pal::kWall, pal::kWallEdge, 1.5f));
      continue;
    }
    const bool barrel = o.type == "barrel";
    Color fill = !prop ? pal::kSturdyProp : barrel ? pal::kBarrel : pal::kCrate;
    const Color edge = barrel ? pal::kBarrelEdge : pal::kCrateEdge;
    // Darker as it is damaged: 60% of the way to the edge's brown when it is about to break.
    if (prop && o.material.health > 0.0f)
      fill = pal::mix(fill, pal::kCrateEdge, 0.6f * (1.0f - prop->health / o.material.health));
    for (const rc::Shape& shape : o.shapes) {
      drawShape(list, shape, xf, Style::both(fill, edge, 1.5f));
      // A mark that turns with it: a crate's brace, a barrel's lid seam.
      if (shape.type == rc::ShapeType::box) {
        const rc::Vec2 c = shape.box.center, e = 0.7f * shape.box.halfExtents;
        list.segment(rc::apply(xf, c - e), rc::apply(xf, c + e), 1.5f, edge);
      } else if (shape.type == rc::ShapeType::circle) {
        const rc::Vec2 c = shape.circle.center;
        const rc::Vec2 d{0.6f * shape.circle.radius, 0.0f};
        list.segment(rc::apply(xf, c - d), rc::apply(xf, c + d), 1.5f, edge);
      }
    }
  }
}

void MatchView::drawActors(render::DrawList& list, const MatchState& s) const {
  const float r = s.tuning.radius, px = pixel();
  for (const Actor& a : s.actors) {
    const rc::Vec2 at = s.world->worldCenter(a.body);
    const Color team = pal::team(a.team);
    if (!a.alive) {  // a faint cross where it fell, until it comes back
      const float k = 0.6f * r;
      list.segment(at + rc::Vec2{-k, -k}, at + rc::Vec2{k, k}, 1.5f, pal::fade(team, 0.5f));
      list.segment(at + rc::Vec2{-k, k}, at + rc::Vec2{k, -k}, 1.5f, pal::fade(team, 0.5f));
      continue;
    }
    const bool player = a.kind == ActorKind::player;
    list.circle(at, r,
                player ? Style::both(team, pal::kSpark, 2.0f)
                       : Style::both(team, pal::mix(team, pal::kOutside, 0.7f), 1.0f));
    const rc::Vec2 d = unit(a.aim);
    list.segment(at + 0.3f * r * d, at + (r + std::max(0.25f * r, 3.0f * px)) * d, 2.0f,
                 pal::mix(team, pal::kSpark, 0.75f));
  }
}

void MatchView::drawShot(render::DrawList& list, const MatchState& s, const Shot& shot,
                         float alpha) const {
  const std::vector<rc::Vec2>& path = shot.path;
  if (path.size() < 2) return;
  const Color tracer = pal::fade(
      pal::mix(shot.shooter < s.actors.size() ? pal::team(s.actors[shot.shooter].team) : pal::kShot,
               pal::kShot, 0.6f),
      alpha);
  const bool pellet =
      shot.weapon < s.weapons.weapons.size() && s.weapons.weapons[shot.weapon].hitscan.pellets > 1;
  const float width = pellet ? 1.0f : 1.5f;
  // A vertex where the path turns is a ricochet (a spark); where it goes straight on, the shot
  // entered or left something it crossed (the part inside drawn faint).
  bool inside = false;
  float length = 0.0f;
  std::vector<rc::Vec2> sparks;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const rc::Vec2 a = path[k], b = path[k + 1];
    length += rc::length(b - a);
    list.segment(a, b, width, inside ? pal::fade(tracer, 0.35f) : tracer);
    if (k + 2 < path.size()) {
      const rc::Vec2 d1 = b - a, d2 = path[k + 2] - b;
      const bool straight =
          std::abs(rc::cross(d1, d2)) <= 1e-3f * rc::length(d1) * rc::length(d2) &&
          rc::dot(d1, d2) > 0.0f;
      inside = straight && !inside;
      if (!straight) sparks.push_back(b);
    }
  }
  for (rc::Vec2 p : sparks)  // over the lines
    list.dot(p, 2.5f, pal::fade(pal::kSpark, alpha));
  // Where it stopped, unless it ran out of range in the open.
  const float range =
      shot.weapon < s.weapons.weapons.size() ? s.weapons.weapons[shot.weapon].hitscan.range : 0.0f;
  if (length < range - 1e-3f) list.dot(path.back(), 2.0f, pal::fade(pal::kSpark, 0.8f * alpha));
}

void MatchView::drawBlast(render::DrawList& list, const Explosion& blast, float age) const {
  // age in [0, 1]: the fireball grows and fades inside the ring of the blast's radius.
  const float fade = 1.0f - age;
  list.circle(
      blast.center, blast.radius * (0.45f + 0.55f * std::sqrt(age)),
      Style::filled(pal::fade(pal::mix(pal::kBlast, pal::kSpark, 0.3f * fade), 0.45f * fade)));
  list.circle(blast.center, blast.radius, Style::outlined(pal::fade(pal::kBlast, fade), 2.5f));
}

void MatchView::drawHud(render::DrawList& hud, const MatchState& s,
                        const MatchViewOptions& options) const {
  const float width = static_cast<float>(camera_.width);
  const float band = band_ > 0.0f ? band_ : 14.0f;
  const float text = std::max(10.0f, std::round(0.62f * band));
  const float mid = 0.5f * band;
  if (band_ > 0.0f) hud.rect({{0.0f, 0.0f}, {width, band_}}, Style::filled(pal::kHudBand));
  char line[128];
  const double seconds = static_cast<double>(s.tick) / kTicksPerSecond;
  std::snprintf(line, sizeof line, "tick %lld  %.1f s", static_cast<long long>(s.tick), seconds);
  hud.text({8.0f, mid}, line, text, pal::kHudText, render::HAlign::kLeft, render::VAlign::kMiddle);
  if (band_ == 0.0f) return;  // a frame too small for more
  // Laid out left to right by estimated widths (no font here): what does not fit is left out,
  // the player's health last.
  const float left = 8.0f + textWidth(line, text);
  // The first player's health, with a bar, at the right; without players, the caption.
  const auto player = std::find_if(s.actors.begin(), s.actors.end(),
                                   [](const Actor& a) { return a.kind == ActorKind::player; });
  const float right = width - 8.0f;
  float rightStart = right;
  if (player != s.actors.end()) {
    const float barW = std::round(4.0f * text), barH = std::round(0.45f * text);
    if (right - barW > left + text) {
      const rc::AABB bar{{right - barW, mid - 0.5f * barH}, {right, mid + 0.5f * barH}};
      const float fraction = std::clamp(player->health / s.tuning.health, 0.0f, 1.0f);
      hud.rect(bar, Style::filled(pal::kHealthBack));
      if (fraction > 0.0f)
        hud.rect({bar.lower, {bar.lower.x + fraction * barW, bar.upper.y}},
                 Style::filled(healthColor(fraction)));
      hud.rect(bar, Style::outlined(pal::kHudDim, 1.0f));
      rightStart = right - barW;
    }
    if (player->alive)
      std::snprintf(line, sizeof line, "%s %.0f", player->name.c_str(),
                    static_cast<double>(player->health));
    else
      std::snprintf(line, sizeof line, "%s down", player->name.c_str());
    if (rightStart - 6.0f - textWidth(line, text) > left + text) {
      rightStart -= 6.0f + textWidth(line, text);
      hud.text({rightStart + textWidth(line, text), mid}, line, text, pal::kHudText,
               render::HAlign::kRight, render::VAlign::kMiddle);
    }
  } else if (!options.caption.empty() && right - textWidth(options.caption, text) > left + text) {
    rightStart = right - textWidth(options.caption, text);
    hud.text({right, mid}, options.caption, text, pal::kHudDim, render::HAlign::kRight,
             render::VAlign::kMiddle);
  }
  // Kills per team, in the team's colour, between the two: the first four teams present, by
  // number (a level may number them from 0 to 255).
  std::vector<int> present;
  for (const Actor& a : s.actors)
    if (std::find(present.begin(), present.end(), a.team) == present.end())
      present.push_back(a.team);
  std::sort(present.begin(), present.end());
  float x = std::max(left + 2.0f * text, std::round(0.27f * width));
  for (std::size_t k = 0; k < present.size() && k < 4; ++k) {
    const int t = present[k];
    int kills = 0;
    for (const Actor& a : s.actors)
      kills += a.team == t ? a.kills : 0;
    std::snprintf(line, sizeof line, "%s %d", teamName(s, t).c_str(), kills);
    if (x + textWidth(line, text) > rightStart - text) break;
    hud.text({x, mid}, line, text, pal::team(t), render::HAlign::kLeft, render::VAlign::kMiddle);
    x += std::max(std::round(5.5f * text), textWidth(line, text) + text);
  }
  // The top three by kills (then fewest deaths), under the band at the right.
  std::vector<std::size_t> order(s.actors.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const Actor &p = s.actors[a], &q = s.actors[b];
    return p.kills != q.kills ? p.kills > q.kills : p.deaths < q.deaths;
  });
  const std::size_t shown = std::min<std::size_t>(3, order.size());
  if (shown == 0 || s.actors[order[0]].kills == 0) return;
  const float small = std::max(10.0f, std::round(0.5f * band));
  const float lineH = std::round(1.2f * small);
  float boxW = std::round(7.0f * small);  // wider when names and scores need it
  for (std::size_t k = 0; k < shown; ++k) {
    const Actor& a = s.actors[order[k]];
    std::snprintf(line, sizeof line, "%d/%d", a.kills, a.deaths);
    boxW = std::max(boxW, std::round(textWidth(a.name, small) + textWidth(line, small) + small));
  }
  // Beside the level when the frame has room there, else over its top-right corner.
  const float levelRight = camera_.worldToPixel(bounds_.upper).x;
  const float boxRight = width - 4.0f;
  const rc::AABB box{{boxRight - boxW, band_ + 4.0f},
                     {boxRight, band_ + 8.0f + lineH * static_cast<float>(shown)}};
  if (box.lower.x < levelRight + 4.0f)
    hud.rect(box, Style::filled(pal::fade(pal::kHudBand, 0.85f)));
  for (std::size_t k = 0; k < shown; ++k) {
    const Actor& a = s.actors[order[k]];
    const float y = band_ + 6.0f + lineH * static_cast<float>(k);
    hud.text({box.lower.x + 3.0f, y}, a.name, small, pal::team(a.team));
    std::snprintf(line, sizeof line, "%d/%d", a.kills, a.deaths);
    hud.text({boxRight - 3.0f, y}, line, small, pal::kHudText, render::HAlign::kRight);
  }
}

render::Frame MatchView::draw(const MatchState& s, const MatchViewOptions& options) const {
  const float px = pixel();
  render::Frame frame;
  frame.background = pal::kFloor;  // the level's statics cover what lies beyond the map
  frame.showOverlay = options.overlay;
  render::DrawList& world = frame.world;
  world = statics_;
  for (const LevelPickup& p : s.built.pickups) {
    const Color c = p.item == "health" ? pal::kHealthPickup
                    : p.item == "ammo" ? pal::kAmmoPickup
                                       : pal::kOtherPickup;
    const float r = std::max(0.6f * p.radius, 4.0f * px);
    world.circle(p.position, r, Style::both(pal::fade(c, 0.25f), c, 1.5f));
    const float k = 0.55f * r;
    if (p.item == "health") {
      world.segment(p.position - rc::Vec2{k, 0}, p.position + rc::Vec2{k, 0}, 2.0f, c);
      world.segment(p.position - rc::Vec2{0, k}, p.position + rc::Vec2{0, k}, 2.0f, c);
    } else {
      world.rect({p.position - rc::Vec2{0.6f * k, k}, p.position + rc::Vec2{0.6f * k, k}},
                 Style::filled(c));
    }
  }
  drawProps(world, s);
  for (const Grenade& g : s.grenades) {
    if (!g.live || !s.world->isValid(g.body)) continue;
    const float r = std::max(s.weapons.weapons[g.weapon].grenade.radius, 3.0f * px);
    // Its fuse shows in the last 40 ticks: a red blink, faster towards the end.
    const bool blink = g.fuse < 40 && (g.fuse / (g.fuse < 15 ? 3 : 6)) % 2 == 0;
    world.circle(s.world->worldCenter(g.body), r,
                 Style::both(blink ? pal::kHealthLow : pal::kGrenade, pal::kSpark, 1.0f));
  }
  drawActors(world, s);
  for (const PastShot& past : shots_) {
    const auto age = static_cast<float>(s.tick - past.tick);
    if (age >= 1.0f && age <= kShotTicks)
      drawShot(world, s, past.shot, 1.0f - age / (kShotTicks + 1.0f));
  }
  for (const Shot& shot : s.shots)
    drawShot(world, s, shot, 1.0f);
  for (const PastBlast& past : blasts_) {
    const auto age = static_cast<float>(s.tick - past.tick);
    if (age >= 1.0f && age <= kBlastTicks) drawBlast(world, past.blast, age / (kBlastTicks + 1.0f));
  }
  for (const Explosion& blast : s.explosions)
    drawBlast(world, blast, 0.0f);
  // Health bars on top of everything in the world, a fixed size on screen over each disc.
  const float r = s.tuning.radius;
  for (const Actor& a : s.actors) {
    if (!a.alive) continue;
    const rc::Vec2 at = s.world->worldCenter(a.body);
    const float w = std::max(2.4f * r, 16.0f * px), h = 3.0f * px;
    const rc::Vec2 lower{at.x - 0.5f * w, at.y + r + 2.0f * px};
    const float fraction = std::clamp(a.health / s.tuning.health, 0.0f, 1.0f);
    world.rect({lower - rc::Vec2{px, px}, lower + rc::Vec2{w + px, h + px}},
               Style::filled(pal::kHealthBack));
    if (fraction > 0.0f)
      world.rect({lower, lower + rc::Vec2{fraction * w, h}}, Style::filled(healthColor(fraction)));
  }
  if (options.overlay) {
    drawSounds(frame.overlay, s);
    for (std::size_t i = 0; i < s.actors.size(); ++i) {
      const Actor& a = s.actors[i];
      if (!a.alive) continue;
      drawPerception(frame.overlay, perceptionOf(s, i), pal::team(a.team), bounds_, px);
      frame.overlay.text(s.world->worldCenter(a.body) - rc::Vec2{0.0f, r + 2.0f * px}, a.name,
                         10.0f, pal::fade(pal::kHudText, 0.8f), render::HAlign::kCenter,
                         render::VAlign::kTop);
    }
    for (const Grenade& g : s.grenades)
      if (g.live && s.world->isValid(g.body))
        frame.overlay.circle(s.world->worldCenter(g.body),
                             s.weapons.weapons[g.weapon].grenade.blastRadius,
                             Style::outlined(pal::fade(pal::kBlast, 0.5f), 1.0f));
    for (const Explosion& blast : s.explosions)
      for (std::size_t hit : blast.actorsHit)
        if (hit < s.actors.size())
          frame.overlay.segment(blast.center, s.world->worldCenter(s.actors[hit].body), 1.0f,
                                pal::kBlast);
  }
  drawHud(frame.hud, s, options);
  return frame;
}

}  // namespace game
