#include "game/view/perception_view.h"

#include "game/bots/memory.h"

#include <algorithm>
#include <cmath>

#include "game/view/palette.h"

namespace game {
namespace {

rc::Vec2 unit(float angle) {
  return {std::cos(angle), std::sin(angle)};
}

// A line drawn as dashes `dash` long with `gap` between them (metres).
void dashed(render::DrawList& list, rc::Vec2 a, rc::Vec2 b, float dash, float gap,
            float widthPixels, render::Color color) {
  const float length = rc::length(b - a);
  if (!(length > 0.0f)) return;
  const rc::Vec2 d = (1.0f / length) * (b - a);
  for (float t = 0.0f; t < length; t += dash + gap)
    list.segment(a + t * d, a + std::min(t + dash, length) * d, widthPixels, color);
}

// The part of segment ab inside `box` (Liang and Barsky's clipping), if any.
bool clipSegment(rc::Vec2& a, rc::Vec2& b, const rc::AABB& box) {
  float t0 = 0.0f, t1 = 1.0f;
  const rc::Vec2 d = b - a;
  // Each side as p t <= q.
  const float p[4] = {-d.x, d.x, -d.y, d.y};
  const float q[4] = {a.x - box.lower.x, box.upper.x - a.x, a.y - box.lower.y, box.upper.y - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0f) {
      if (q[k] < 0.0f) return false;
      continue;
    }
    const float t = q[k] / p[k];
    if (p[k] < 0.0f)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const rc::Vec2 start = a;
  a = start + t0 * d;
  b = start + t1 * d;
  return true;
}

// A convex polygon cut to `box` (Sutherland and Hodgman: one side of the box at a time); fewer
// than 3 points when nothing is left.
std::vector<rc::Vec2> clipToBox(std::vector<rc::Vec2> points, const rc::AABB& box) {
  for (int side = 0; side < 4 && points.size() >= 3; ++side) {
    const int axis = side / 2;
    const bool upper = side % 2 == 1;
    const float bound =
        upper ? (axis == 0 ? box.upper.x : box.upper.y) : (axis == 0 ? box.lower.x : box.lower.y);
    auto coord = [axis](rc::Vec2 p) { return axis == 0 ? p.x : p.y; };
    auto inside = [&](rc::Vec2 p) { return upper ? coord(p) <= bound : coord(p) >= bound; };
    std::vector<rc::Vec2> out;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const rc::Vec2 a = points[i], b = points[(i + 1) % points.size()];
      if (inside(a)) out.push_back(a);
      if (inside(a) != inside(b))
        out.push_back(a + (bound - coord(a)) / (coord(b) - coord(a)) * (b - a));
    }
    points = std::move(out);
  }
  return points;
}

// A sight cone: a wedge near the apex, filled, that shows where it looks at a glance, and the
// whole cone's outline (its two edges and the arc at its range) in thin lines cut to `box`.
// Filling the whole cone would tint the level with every bot's cone and cost every pixel of it.
void cone(render::DrawList& list, rc::Vec2 apex, float range, float axis, float halfAngle,
          const rc::AABB& box, render::Color color, float wedge) {
  constexpr int kArcPoints = 17;
  std::vector<rc::Vec2> near{apex}, arc;
  for (int k = 0; k < kArcPoints; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(kArcPoints - 1);
    const rc::Vec2 d = unit(axis + (2.0f * t - 1.0f) * halfAngle);
    arc.push_back(apex + range * d);
    if (k % 2 == 0) near.push_back(apex + std::min(wedge, range) * d);
  }
  // The wedge in two convex halves (a cone wider than half a turn is not convex).
  const std::size_t mid = near.size() / 2;
  std::vector<rc::Vec2> half1(near.begin(), near.begin() + static_cast<long>(mid) + 1);
  std::vector<rc::Vec2> half2{apex};
  half2.insert(half2.end(), near.begin() + static_cast<long>(mid), near.end());
  for (std::vector<rc::Vec2>* h : {&half1, &half2}) {
    *h = clipToBox(std::move(*h), box);
    if (h->size() >= 3) list.polygon(*h, render::Style::filled(palette::fade(color, 0.18f)));
  }
  std::vector<rc::Vec2> outline{apex};
  outline.insert(outline.end(), arc.begin(), arc.end());
  outline.push_back(apex);
  for (std::size_t k = 0; k + 1 < outline.size(); ++k) {
    rc::Vec2 a = outline[k], b = outline[k + 1];
    if (clipSegment(a, b, box)) list.segment(a, b, 1.0f, palette::fade(color, 0.3f));
  }
}

}  // namespace

PerceptionOverlay perceptionOf(const MatchState& s, std::size_t actor) {
  const Actor& me = s.actors[actor];
  const BotMind& mind = s.minds[actor];
  PerceptionOverlay p;
  p.at = s.world->worldCenter(me.body);
  p.aim = me.aim;
  // Sight: the line-of-sight rays its look cast this tick (it looks every few ticks).
  for (const SightRay& ray : s.sightRays)
    if (ray.viewer == static_cast<std::int32_t>(actor))
      p.sightRays.push_back({ray.from, ray.to, ray.clear});
  // Hearing: where the sounds it heard this tick came from.
  for (const HeardSound& h : s.heard)
    if (h.listener == static_cast<std::int32_t>(actor)) p.heard.push_back(h.sound.position);
  // The enemy it acts on: in sight (its latest look saw it) or remembered (where it expects it).
  if (mind.focus >= 0) {
    const MemoryEntry& entry = mind.memory[static_cast<std::size_t>(mind.focus)];
    p.targetInSight = inSight(mind, entry);
    p.target = p.targetInSight && entry.actor >= 0 &&
                       static_cast<std::size_t>(entry.actor) < s.actors.size()
                   ? s.world->worldCenter(s.actors[static_cast<std::size_t>(entry.actor)].body)
                   : entry.position;
  }
  if (mind.behaviour == Behaviour::patrol || mind.behaviour == Behaviour::takeCover ||
      mind.behaviour == Behaviour::flee || mind.behaviour == Behaviour::fetch)
    p.goal = mind.goal;
  // The path it follows: from where it is through the waypoints it has not reached.
  if (mind.route.planned >= 0 && mind.route.next < mind.route.length) {
    p.path.push_back(p.at);
    for (std::size_t k = mind.route.next; k < mind.route.length; ++k)
      p.path.push_back(mind.route.points[k]);
  }
  return p;
}

void drawSounds(render::DrawList& overlay, const MatchState& s) {
  for (const Sound& sound : s.sounds)
    overlay.circle(sound.position, sound.radius,
                   render::Style::outlined(palette::fade(palette::kSpark, 0.25f), 1.0f));
}

void drawPerception(render::DrawList& overlay, const PerceptionOverlay& p, render::Color team,
                    const rc::AABB& bounds, float pixel) {
  namespace pal = palette;
  cone(overlay, p.at, p.sight.range, p.aim, p.sight.halfAngle, bounds, team, 30.0f * pixel);
  for (rc::Vec2 h : p.heard)
    overlay.dot(h, 2.5f, pal::mix(team, pal::kSpark, 0.5f));
  for (const PerceptionOverlay::Ray& ray : p.sightRays)
    overlay.segment(ray.from, ray.to, ray.clear ? 1.5f : 1.0f,
                    ray.clear ? render::Color{120, 255, 140, 220} : render::Color{255, 90, 90, 70});
  if (p.path.size() >= 2) {
    overlay.polyline(p.path, 1.5f, pal::fade(team, 0.7f));
    for (rc::Vec2 w : p.path)
      overlay.dot(w, 2.0f, pal::fade(team, 0.9f));
  }
  if (p.target) {
    const render::Color c{255, 70, 70, 255};
    if (p.targetInSight) {
      overlay.arrow(p.at, *p.target, 1.5f, c, 7.0f);
    } else {
      dashed(overlay, p.at, *p.target, 5.0f * pixel, 4.0f * pixel, 1.0f, pal::fade(c, 0.8f));
      overlay.circle(*p.target, 6.0f * pixel, render::Style::outlined(c, 1.5f));
    }
  }
  if (p.goal) {
    const render::Color c = pal::fade(pal::mix(team, pal::kSpark, 0.4f), 0.6f);
    dashed(overlay, p.at, *p.goal, 3.0f * pixel, 5.0f * pixel, 1.0f, c);
    const float r = 4.0f * pixel;
    const rc::Vec2 diamond[4] = {*p.goal + rc::Vec2{r, 0}, *p.goal + rc::Vec2{0, r},
                                 *p.goal - rc::Vec2{r, 0}, *p.goal - rc::Vec2{0, r}};
    overlay.polygon(diamond, render::Style::outlined(c, 1.5f));
  }
}

}  // namespace game
