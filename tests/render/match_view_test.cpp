// The match view (game/view/match_view): pixel probes that an actor's disc, a shot's line, a
// health bar and a blast's ring land where the camera puts them, that the dead and the destroyed
// are not drawn, that the camera shows the level's bounds below the HUD band, that the overlay
// shows a bot's sight cone only when asked; and the fill of merged tile loops.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "game/match/match.h"
#include "game/rules/damage.h"
#include "game/view/level_view.h"
#include "game/view/match_view.h"
#include "game/view/palette.h"
#include "render_support.h"

// Named, not anonymous: the test files compile in unity batches, and their helpers' names repeat.
namespace match_view_test {

using game::Level;
using game::Match;
using game::MatchView;
using rc::Vec2;
using render::Color;
using render_test::sharedRenderer;

namespace pal = game::palette;

// A 20 x 10 m room (bounds (0, -10) to (20, 0), as a Tiled map's), walled by merged tiles (a
// one-sided loop around the inside of the room's border, its hole the floor), a crate at
// (15, -7), the player spawn at (4, -5) and one bot spawn at (16, -3).
Level room() {
  Level level;
  level.source = "room";
  level.settings.bounds = {{0, -10}, {20, 0}};
  level.settings.width = 20;
  level.settings.height = 10;
  level.settings.tileWidth = level.settings.tileHeight = 1.0f;
  game::LevelObject tiles;
  tiles.kind = game::LevelObjectKind::tiles;
  // The border ring, a tile thick: the outer loop counter-clockwise, the hole clockwise.
  const Vec2 outer[] = {{0, -10}, {20, -10}, {20, 0}, {0, 0}};
  const Vec2 inner[] = {{1, -9}, {1, -1}, {19, -1}, {19, -9}};
  for (const rc::ChainSegment& link : rc::makeChain(outer, true, true))
    tiles.shapes.push_back(link);
  for (const rc::ChainSegment& link : rc::makeChain(inner, true, true))
    tiles.shapes.push_back(link);
  level.objects.push_back(tiles);
  game::LevelObject crate;
  crate.kind = game::LevelObjectKind::prop;
  crate.type = "crate";
  crate.bodyType = rc::BodyType::dynamicBody;
  crate.position = {15, -7};
  crate.linearDamping = crate.angularDamping = 3.0f;
  crate.material.health = 40.0f;
  crate.material.hard = false;
  crate.shapes.push_back(rc::makeBox(0.5f, 0.5f));
  level.objects.push_back(crate);
  game::LevelSpawn p;
  p.kind = game::SpawnKind::player;
  p.position = {4, -5};
  level.spawns.push_back(p);
  game::LevelSpawn b;
  b.kind = game::SpawnKind::bot;
  b.position = {16, -3};
  b.team = 1;
  level.spawns.push_back(b);
  return level;
}

game::MatchConfig oneBot() {
  game::MatchConfig c;
  c.bots = 1;
  c.players = 1;
  return c;
}

struct Probe {
  int x, y;
};
Probe at(const render::Camera& camera, Vec2 world) {
  const Vec2 p = camera.worldToPixel(world);
  return {static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y))};
}

TEST(MatchView, CameraShowsTheLevelsBoundsBelowTheHudBand) {
  Match match(room(), oneBot());
  const MatchView view(match.state(), 640, 360);
  const render::Camera& camera = view.camera();
  EXPECT_GT(view.bandHeight(), 0.0f);
  const Vec2 topLeft = camera.worldToPixel({0, 0});
  const Vec2 bottomRight = camera.worldToPixel({20, -10});
  EXPECT_GE(topLeft.y, view.bandHeight());
  EXPECT_GE(topLeft.x, 0.0f);
  EXPECT_LE(bottomRight.x, 640.0f);
  EXPECT_LE(bottomRight.y, 360.0f);
  // It fills the width or the height left under the band, but for a margin of a few pixels.
  EXPECT_TRUE(bottomRight.x - topLeft.x > 640.0f - 20.0f ||
              bottomRight.y - topLeft.y > 360.0f - view.bandHeight() - 20.0f);
  // Frames too small for a band still show the whole level.
  const MatchView tiny(match.state(), 32, 16);
  EXPECT_EQ(tiny.bandHeight(), 0.0f);
  EXPECT_LE(tiny.camera().worldToPixel({20, -10}).x, 32.0f);
}

TEST(MatchView, ActorsDiscSitsWhereTheCameraPutsIt) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  s.world->setTransform(s.actors[1].body, {10.5f, -4.5f}, 0.0f);
  s.actors[1].aim = 0.0f;  // facing +x: the barrel is to the right of the centre
  const MatchView view(s, 640, 360);
  const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
  const Color team = pal::team(s.actors[1].team);
  const Probe c = at(view.camera(), {10.5f, -4.5f});
  EXPECT_PIXEL(image, c.x, c.y, team, 4);
  // Half the radius to the left, still the disc; twice the radius below, the floor.
  const Probe left = at(view.camera(), {10.5f - 0.5f * s.tuning.radius, -4.5f});
  EXPECT_PIXEL(image, left.x, left.y, team, 4);
  const Probe below = at(view.camera(), {10.5f, -4.5f - 2.0f * s.tuning.radius});
  EXPECT_PIXEL(image, below.x, below.y, pal::kFloor, 4);
  // The merged tiles' ring is filled with the wall's colour; the room inside is floor.
  const Probe wall = at(view.camera(), {0.5f, -5.2f});
  EXPECT_PIXEL(image, wall.x, wall.y, pal::kWall, 4);
  const Probe floor = at(view.camera(), {3.3f, -7.6f});
  EXPECT_PIXEL(image, floor.x, floor.y, pal::kFloor, 4);
}

TEST(MatchView, ShotIsALineAlongItsWholePath) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  // The player's shot along y = -7.6 to a bounce at (12, -7.6), then up to (14, -2.4) (off the
  // floor's tile grid, whose lines would tint the probes).
  game::Shot shot;
  shot.shooter = 0;
  shot.weapon = 0;
  shot.path = {{3, -7.6f}, {12, -7.6f}, {14, -2.4f}};
  s.shots.push_back(shot);
  const MatchView view(s, 640, 360);
  const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
  const Color tracer = pal::mix(pal::team(s.actors[0].team), pal::kShot, 0.6f);
  // On both legs of the path, the tracer's colour (blended over the floor by its anti-aliased
  // 1.5 px width: the centre pixel is nearly covered, so its colour is close to the tracer's).
  for (Vec2 p : {Vec2{7.5f, -7.6f}, Vec2{13, -5}}) {
    const Probe q = at(view.camera(), p);
    const Color c = image.pixel(q.x, q.y);
    const Color floorC = pal::kFloor;
    EXPECT_GT(c.g, floorC.g + 60) << "at (" << p.x << ", " << p.y << ") "
                                  << render_test::describe(c) << " tracer "
                                  << render_test::describe(tracer);
  }
  // A few pixels off the line, the floor.
  const Probe off = at(view.camera(), {7.5f, -7.9f});
  EXPECT_PIXEL(image, off.x, off.y, pal::kFloor, 4);
  // The bounce is a white spark.
  const Probe spark = at(view.camera(), {12, -7.6f});
  EXPECT_PIXEL(image, spark.x, spark.y, pal::kSpark, 40);
}

TEST(MatchView, HealthBarShowsWhatIsLeftAboveTheDisc) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  s.world->setTransform(s.actors[1].body, {10.5f, -4.5f}, 0.0f);
  s.actors[1].health = 0.5f * s.tuning.health;
  const MatchView view(s, 640, 360);
  const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
  // The bar: 2.4 radii wide (or 16 px), 3 px high, 2 px above the disc; the left half filled
  // (half health: yellow), the right half the dark back.
  const float r = s.tuning.radius, px = view.pixel();
  const float w = std::max(2.4f * r, 16.0f * px);
  const float y = -4.5f + r + 3.5f * px;
  const Probe filled = at(view.camera(), {10.5f - 0.25f * w, y});
  EXPECT_PIXEL(image, filled.x, filled.y, pal::kAmmoPickup, 6);
  const Probe empty = at(view.camera(), {10.5f + 0.25f * w, y});
  EXPECT_LE(render_test::channelDistance(image.pixel(empty.x, empty.y), Color{20, 20, 20, 255}), 30)
      << render_test::describe(image.pixel(empty.x, empty.y));
}

TEST(MatchView, DeadActorsAndDestroyedPropsAreNotDrawn) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  s.world->setTransform(s.actors[1].body, {10.5f, -4.5f}, 0.0f);
  const MatchView view(s, 640, 360);
  // Above the centre, clear of the cross a dead actor leaves.
  const Probe bot = at(view.camera(), {10.5f, -4.5f + 0.5f * s.tuning.radius});
  const Probe crate = at(view.camera(), {15.2f, -7.2f});
  {
    const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
    EXPECT_PIXEL(image, bot.x, bot.y, pal::team(1), 4);
    EXPECT_GT(render_test::channelDistance(image.pixel(crate.x, crate.y), pal::kFloor), 40);
  }
  game::killActor(s, 1, std::nullopt);
  game::damageProp(s, 1, 1000.0f);
  const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
  // The dead bot's disc and the crate are gone.
  EXPECT_PIXEL(image, bot.x, bot.y, pal::kFloor, 4);
  EXPECT_PIXEL(image, crate.x, crate.y, pal::kFloor, 4);
}

TEST(MatchView, ExplosionIsARingOfItsBlastRadius) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  game::Explosion blast;
  blast.center = {10.5f, -4.5f};
  blast.radius = 3.0f;
  s.explosions.push_back(blast);
  const MatchView view(s, 640, 360);
  const render::Image image = sharedRenderer().render(view.draw(s), view.camera());
  // Just inside the ring's edge (it is 2.5 px wide, inside the radius), the blast's colour.
  const Probe ring = at(view.camera(), {10.5f, -4.5f - 3.0f + 1.2f * view.pixel()});
  EXPECT_PIXEL(image, ring.x, ring.y, pal::kBlast, 30);
  const Probe outside = at(view.camera(), {10.5f, -4.5f - 3.0f - 3.0f * view.pixel()});
  EXPECT_PIXEL(image, outside.x, outside.y, pal::kFloor, 4);
}

TEST(MatchView, ObservedShotsFadeOverTheNextTicks) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  MatchView view(s, 640, 360);
  game::Shot shot;
  shot.path = {{3, -7.6f}, {12, -7.6f}};
  s.shots.push_back(shot);
  view.observe(s);
  const Probe p = at(view.camera(), {7.5f, -7.6f});
  const int fresh = sharedRenderer().render(view.draw(s), view.camera()).pixel(p.x, p.y).g;
  // Two ticks later (the match has cleared its shots): still there, fainter.
  s.shots.clear();
  s.tick += 2;
  const int older = sharedRenderer().render(view.draw(s), view.camera()).pixel(p.x, p.y).g;
  EXPECT_LT(older, fresh);
  EXPECT_GT(older, pal::kFloor.g + 20);
  // Past its trail, gone.
  s.tick += MatchView::kShotTicks;
  view.observe(s);
  const Color gone = sharedRenderer().render(view.draw(s), view.camera()).pixel(p.x, p.y);
  EXPECT_LE(render_test::channelDistance(gone, pal::kFloor), 4) << render_test::describe(gone);
}

TEST(MatchView, OverlayShowsTheSightConeOnlyWhenAsked) {
  Match match(room(), oneBot());
  game::MatchState& s = match.state();
  // The bot at (16, -3) looks left (+pi): the filled wedge near it covers (15.1, -2.7), clear of
  // its disc, health bar, label and sight ray.
  // The player at (3, -8.5) looks down, away from both probes.
  s.actors[1].aim = 3.14159265f;
  s.actors[0].aim = -1.5707963f;
  s.world->setTransform(s.actors[0].body, {3, -8.5f}, 0.0f);
  const MatchView view(s, 640, 360);
  const Probe inCone = at(view.camera(), {15.1f, -2.7f});
  game::MatchViewOptions options;
  const render::Image plain = sharedRenderer().render(view.draw(s, options), view.camera());
  EXPECT_PIXEL(plain, inCone.x, inCone.y, pal::kFloor, 4);
  options.overlay = true;
  const render::Image overlay = sharedRenderer().render(view.draw(s, options), view.camera());
  EXPECT_GT(render_test::channelDistance(overlay.pixel(inCone.x, inCone.y), pal::kFloor), 2);
  // Behind the bot, outside its cone: still the floor.
  const Probe behind = at(view.camera(), {17.5f, -6.4f});
  EXPECT_PIXEL(overlay, behind.x, behind.y, pal::kFloor, 4);
}

// The HUD's kills per team name every team present, whatever its number: a bot on team 7 gets a
// line beside the player's team 0.
TEST(MatchView, HudNamesEveryTeamPresent) {
  Level level = room();
  level.spawns[1].team = 7;
  Match match(level, oneBot());
  const MatchView view(match.state(), 640, 360);
  const render::Frame frame = view.draw(match.state());
  auto shown = [&frame](const std::string& line) {
    for (const render::Text& t : frame.hud.texts)
      if (t.text == line) return true;
    return false;
  };
  EXPECT_TRUE(shown("players 0"));
  EXPECT_TRUE(shown("bots 0"));
}

TEST(LevelView, FillLoopsCoversARingAndLeavesItsHole) {
  const Vec2 outer[] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const Vec2 hole[] = {{1, 1}, {1, 3}, {3, 3}, {3, 1}};
  std::vector<rc::Segment> links;
  for (const Vec2* loop : {outer, hole})
    for (int i = 0; i < 4; ++i)
      links.push_back({loop[i], loop[(i + 1) % 4]});
  const std::vector<rc::AABB> rects = game::fillLoops(links);
  float area = 0.0f;
  for (const rc::AABB& r : rects) {
    area += (r.upper.x - r.lower.x) * (r.upper.y - r.lower.y);
    EXPECT_FALSE(r.contains(Vec2{2, 2})) << "the hole is filled";
  }
  EXPECT_FLOAT_EQ(area, 16.0f - 4.0f);
  EXPECT_EQ(rects.size(), 4u);  // the band under the hole, two beside it, the band above
}

}  // namespace match_view_test
