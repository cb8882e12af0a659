// Whole-world scenes for the benchmarks that step both engines (world_bench, skip_bench,
// scaling_bench): one seeded description of a scene, built into our World (physics/world.h) and
// into Box2D 2.4.1's b2World, so that both engines get the same bodies.
//   arena    a square box of walls (200 m by default) with static box obstacles and circles of
//            radius 0.5 m at 5 m/s, restitution 0.5, friction 0.2, no gravity; optionally
//            bullets (radius 0.05 m, continuous collision) fired again when slower than 20 m/s.
//   pyramid  touching 1 m boxes on a static ground box, friction 0.6, gravity -10.
// Each engine runs with its defaults: Box2D 8 velocity and 3 position iterations, ours 4
// substeps.
#pragma once

#include <box2d/box2d.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "physics/random.h"
#include "physics/world.h"

namespace world_scenes {

using rc::Vec2;

struct BoxDesc {
  Vec2 center, half;
};
struct BodyDesc {
  Vec2 position, velocity;
  float radius = 0;  // a circle when > 0, else a box of half extents `half`
  Vec2 half{};
  bool bullet = false;
};
struct SceneDesc {
  Vec2 gravity{};
  bool sleep = false;
  bool fixedRotation = false;  // every dynamic body
  bool continuous = true;      // continuous collision (Box2D: SetContinuousPhysics)
  int settleSteps = 0;         // untimed steps before the timed ones (a pyramid falling asleep)
  float friction = 0.2f, restitution = 0.5f;
  // Our quadtree's world square (Box2D's tree needs none): fitted to what the scene holds.
  rc::AABB bounds{{-128, -128}, {128, 128}};
  std::vector<BoxDesc> statics;
  std::vector<BoxDesc> sensors;  // static sensor boxes (trigger zones)
  std::vector<BodyDesc> bodies;
  int bulletCount = 0;   // the last bulletCount bodies are bullets
  bool profile = false;  // ours: time the step's phases (WorldDef::enableProfile; off by default)
};

inline Vec2 randomDirection(rc::Random& rng, float speed) {
  const float a = rng.uniform(0.0f, 6.2831853f);
  return speed * Vec2{std::cos(a), std::sin(a)};
}

// The arena: walls around a square of `side` metres, `obstacles` static boxes, then the circles
// and the bullets, all drawn from one seed (side 200 m, 20 obstacles: world_bench's arena; the
// same draws in the same order for any side, so a larger arena is the same recipe).
inline SceneDesc arena(int circles, int bullets, float bulletSpeed, std::uint64_t seed,
                       float side = 200.0f, int obstacles = 20) {
  SceneDesc s;
  rc::Random rng(seed);
  const float h = 0.5f * side, wall = h + 1.0f;
  s.bounds = {{-h - 28.0f, -h - 28.0f}, {h + 28.0f, h + 28.0f}};
  s.statics = {{{0, -wall}, {wall, 1}},
               {{0, wall}, {wall, 1}},
               {{-wall, 0}, {1, wall}},
               {{wall, 0}, {1, wall}}};
  const float o = 0.8f * h, c = h - 5.0f;
  for (int i = 0; i < obstacles; ++i)
    s.statics.push_back({rng.inBox({-o, -o}, {o, o}), rng.inBox({1, 1}, {4, 4})});
  for (int i = 0; i < circles + bullets; ++i) {
    BodyDesc b;
    b.position = rng.inBox({-c, -c}, {c, c});
    const bool bullet = i >= circles;
    b.radius = bullet ? 0.05f : 0.5f;
    b.velocity = randomDirection(rng, bullet ? bulletSpeed : 5.0f);
    b.bullet = bullet;
    s.bodies.push_back(b);
  }
  s.bulletCount = bullets;
  return s;
}

inline SceneDesc pyramid(int base) {
  SceneDesc s;
  s.gravity = {0, -10};
  s.friction = 0.6f;
  s.restitution = 0.0f;
  s.statics = {{{0, -1}, {100, 1}}};
  for (int row = 0; row < base; ++row)
    for (int i = 0; i < base - row; ++i) {
      BodyDesc b;
      b.position = {static_cast<float>(i) - 0.5f * static_cast<float>(base - row - 1),
                    0.5f + static_cast<float>(row)};
      b.half = {0.5f, 0.5f};
      s.bodies.push_back(b);
    }
  return s;
}

// ----------------------------------------------------------------------------------- engines

struct Ours {
  std::unique_ptr<rc::World> world;
  std::vector<rc::BodyId> bodies;
  explicit Ours(const SceneDesc& s) {
    rc::WorldDef def;
    def.gravity = s.gravity;
    def.enableSleep = s.sleep;
    def.continuous = s.continuous;
    def.bounds = s.bounds;
    def.enableProfile = s.profile;
    world = std::make_unique<rc::World>(def);
    rc::ShapeDef sd;
    sd.friction = s.friction;
    sd.restitution = s.restitution;
    const rc::BodyId ground = world->createBody({});
    for (const BoxDesc& b : s.statics)
      world->createShape(ground, rc::makeBox(b.half.x, b.half.y, b.center), sd);
    rc::ShapeDef sensor = sd;
    sensor.isSensor = true;
    for (const BoxDesc& b : s.sensors)
      world->createShape(ground, rc::makeBox(b.half.x, b.half.y, b.center), sensor);
    for (const BodyDesc& b : s.bodies) {
      rc::BodyDef bd;
      bd.type = rc::BodyType::dynamicBody;
      bd.position = b.position;
      bd.linearVelocity = b.velocity;
      bd.bullet = b.bullet;
      bd.fixedRotation = s.fixedRotation;
      const rc::BodyId id = world->createBody(bd);
      if (b.radius > 0)
        world->createShape(id, rc::makeCircle({}, b.radius), sd);
      else
        world->createShape(id, rc::makeBox(b.half.x, b.half.y), sd);
      bodies.push_back(id);
    }
  }
  void step() { world->step(1.0f / 60.0f); }
  Vec2 position(std::size_t i) const { return world->position(bodies[i]); }
  Vec2 velocity(std::size_t i) const { return world->linearVelocity(bodies[i]); }
  void respawn(std::size_t i, Vec2 p, Vec2 v) {
    world->setTransform(bodies[i], p, 0.0f);
    world->setLinearVelocity(bodies[i], v);
  }
  int awakeCount() const { return world->awakeBodyCount(); }
  int contactCount() const { return world->contactCount(); }
};

struct Box2D {
  std::unique_ptr<b2World> world;
  std::vector<b2Body*> bodies;
  explicit Box2D(const SceneDesc& s) {
    world = std::make_unique<b2World>(b2Vec2(s.gravity.x, s.gravity.y));
    world->SetAllowSleeping(s.sleep);
    world->SetContinuousPhysics(s.continuous);
    b2BodyDef gd;
    b2Body* ground = world->CreateBody(&gd);
    auto addBox = [&](const BoxDesc& b, bool sensor) {
      b2PolygonShape box;
      box.SetAsBox(b.half.x, b.half.y, b2Vec2(b.center.x, b.center.y), 0.0f);
      b2FixtureDef fd;
      fd.shape = &box;
      fd.friction = s.friction;
      fd.restitution = s.restitution;
      fd.isSensor = sensor;
      ground->CreateFixture(&fd);
    };
    for (const BoxDesc& b : s.statics)
      addBox(b, false);
    for (const BoxDesc& b : s.sensors)
      addBox(b, true);
    for (const BodyDesc& b : s.bodies) {
      b2BodyDef bd;
      bd.type = b2_dynamicBody;
      bd.position.Set(b.position.x, b.position.y);
      bd.linearVelocity.Set(b.velocity.x, b.velocity.y);
      bd.bullet = b.bullet;
      bd.fixedRotation = s.fixedRotation;
      b2Body* body = world->CreateBody(&bd);
      b2CircleShape circle;
      circle.m_radius = b.radius;
      b2PolygonShape box;
      box.SetAsBox(b.half.x, b.half.y);
      b2FixtureDef fd;
      fd.shape = b.radius > 0 ? static_cast<const b2Shape*>(&circle) : &box;
      fd.density = 1.0f;
      fd.friction = s.friction;
      fd.restitution = s.restitution;
      body->CreateFixture(&fd);
      bodies.push_back(body);
    }
  }
  void step() { world->Step(1.0f / 60.0f, 8, 3); }
  Vec2 position(std::size_t i) const {
    return {bodies[i]->GetPosition().x, bodies[i]->GetPosition().y};
  }
  Vec2 velocity(std::size_t i) const {
    return {bodies[i]->GetLinearVelocity().x, bodies[i]->GetLinearVelocity().y};
  }
  void respawn(std::size_t i, Vec2 p, Vec2 v) {
    bodies[i]->SetTransform(b2Vec2(p.x, p.y), 0.0f);
    bodies[i]->SetLinearVelocity(b2Vec2(v.x, v.y));
  }
  int awakeCount() const {
    int n = 0;
    for (const b2Body* b : bodies)
      n += b->IsAwake();
    return n;
  }
  int contactCount() const { return world->GetContactCount(); }
};

// A scene being stepped: the engine, and its bullets fired again when they slow down (the same
// draws for both engines). Escaped: a bullet's centre more than its radius past a wall's inner
// face (the arena's half side plus the radius); an escaped bullet is not fired again.
template <class Engine>
struct Run {
  const SceneDesc& scene;
  Engine engine;
  rc::Random rng{99};
  std::vector<bool> escaped;
  float bulletSpeed = 0, halfSide = 0;

  explicit Run(const SceneDesc& s, float arenaHalfSide = 100.0f)
      : scene(s), engine(s), escaped(s.bodies.size(), false), halfSide(arenaHalfSide) {
    bulletSpeed = s.bulletCount > 0 ? rc::length(s.bodies.back().velocity) : 0.0f;
  }
  void step() {
    engine.step();
    for (std::size_t i = scene.bodies.size() - static_cast<std::size_t>(scene.bulletCount);
         i < scene.bodies.size(); ++i) {
      const Vec2 p = engine.position(i);
      const float limit = halfSide + scene.bodies[i].radius;
      if (std::abs(p.x) > limit || std::abs(p.y) > limit) {
        escaped[i] = true;
        continue;
      }
      if (!escaped[i] && rc::length(engine.velocity(i)) < 20.0f) {
        const float c = halfSide - 5.0f;  // where arena() places bodies
        engine.respawn(i, rng.inBox({-c, -c}, {c, c}), randomDirection(rng, bulletSpeed));
      }
    }
  }
  int escapes() const {
    int n = 0;
    for (bool e : escaped)
      n += e;
    return n;
  }
};

// Our step's phases over many steps (a world made with SceneDesc::profile). Profile's times are
// wall clock: a step the shared machine
// preempted shows the time it waited in some phase. Such steps are left out: those whose
// profile total exceeds the step's CPU time (the caller's, around the step) by more than 5% and
// 2 us. total is the sum of the phases' means over the steps kept.
class PhaseSamples {
 public:
  static constexpr std::array<double rc::Profile::*, 7> kPhases = {
      &rc::Profile::updatePairs, &rc::Profile::narrowphase, &rc::Profile::solve,
      &rc::Profile::continuous,  &rc::Profile::refit,       &rc::Profile::sensors,
      &rc::Profile::sleep};
  void add(const rc::Profile& p, double cpuSeconds) {
    if (p.total > 1.05e3 * cpuSeconds + 2e-3) return;
    ++kept_;
    for (std::size_t k = 0; k < kPhases.size(); ++k)
      sums_[k] += p.*kPhases[k];
  }
  rc::Profile means() const {
    rc::Profile m;
    for (std::size_t k = 0; k < kPhases.size(); ++k) {
      m.*kPhases[k] = kept_ > 0 ? sums_[k] / kept_ : 0.0;
      m.total += m.*kPhases[k];
    }
    return m;
  }

 private:
  std::array<double, kPhases.size()> sums_{};
  double kept_ = 0;
};

}  // namespace world_scenes
