// The world race: our World (physics/world.h) against Box2D 2.4.1's b2World stepping the same
// seeded scenes at 60 Hz, in the same run. Not part of ctest; run
//   ./build/release/tests/world_bench [--benchmark_filter=...] [--table=FILE.md]
//
// Scenes (the issue's), built from one description so both engines get the same bodies:
//   arena/N      a 200 m box of walls with 20 static box obstacles, N circles of radius 0.5 m
//                at 5 m/s, restitution 0.5, friction 0.2, no gravity. Time per step.
//   bullets      the 1000-circle arena plus 500 circles of radius 0.05 m at 100 m/s with
//                continuous collision (Box2D: bullet bodies), respawned when slower than
//                20 m/s. Counter: bullets that left the arena (escapes: the centre more than
//                the radius past a wall's inner face). Time per step.
//   pyramid/B    touching 1 m boxes, base B, friction 0.6, on a static ground box, gravity -10,
//                1000 steps, sleeping off (and again with sleeping on in both engines). Counter:
//                the top box's drift from its exact resting height (m). Time per step.
// What a scene lacks costs nothing (the rows to read against arena/N=1000 and pyramid/base 20):
//   arena, 20k static boxes outside   20,000 more static boxes beyond the walls
//   arena, continuous off             no continuous collision in either engine
//   arena, fixed rotation             every circle with fixed rotation
//   pyramid asleep/base 20            the base-20 pyramid after it has fallen asleep
// Each engine runs with its defaults: Box2D 8 velocity and 3 position iterations, ours 4
// substeps.
#include <benchmark/benchmark.h>
#include <box2d/box2d.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bench/ratio_table.h"
#include "physics/random.h"
#include "physics/world.h"

namespace {

using rc::Vec2;

// One scene for both engines.
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
  std::vector<BoxDesc> statics;
  std::vector<BodyDesc> bodies;
  int bulletCount = 0;  // the last bulletCount bodies are bullets
};

Vec2 randomDirection(rc::Random& rng, float speed) {
  const float a = rng.uniform(0.0f, 6.2831853f);
  return speed * Vec2{std::cos(a), std::sin(a)};
}

SceneDesc arena(int circles, int bullets, float bulletSpeed, std::uint64_t seed) {
  SceneDesc s;
  rc::Random rng(seed);
  s.statics = {
      {{0, -101}, {101, 1}}, {{0, 101}, {101, 1}}, {{-101, 0}, {1, 101}}, {{101, 0}, {1, 101}}};
  for (int i = 0; i < 20; ++i)
    s.statics.push_back({rng.inBox({-80, -80}, {80, 80}), rng.inBox({1, 1}, {4, 4})});
  for (int i = 0; i < circles + bullets; ++i) {
    BodyDesc b;
    b.position = rng.inBox({-95, -95}, {95, 95});
    const bool bullet = i >= circles;
    b.radius = bullet ? 0.05f : 0.5f;
    b.velocity = randomDirection(rng, bullet ? bulletSpeed : 5.0f);
    b.bullet = bullet;
    s.bodies.push_back(b);
  }
  s.bulletCount = bullets;
  return s;
}

SceneDesc pyramid(int base) {
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
    def.bounds = {{-128, -128}, {128, 128}};
    world = std::make_unique<rc::World>(def);
    rc::ShapeDef sd;
    sd.friction = s.friction;
    sd.restitution = s.restitution;
    const rc::BodyId ground = world->createBody({});
    for (const BoxDesc& b : s.statics)
      world->createShape(ground, rc::makeBox(b.half.x, b.half.y, b.center), sd);
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
    for (const BoxDesc& b : s.statics) {
      b2PolygonShape box;
      box.SetAsBox(b.half.x, b.half.y, b2Vec2(b.center.x, b.center.y), 0.0f);
      b2FixtureDef fd;
      fd.shape = &box;
      fd.friction = s.friction;
      fd.restitution = s.restitution;
      ground->CreateFixture(&fd);
    }
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
};

// ------------------------------------------------------------------------------- benchmarks

template <class Engine>
void runArena(benchmark::State& state, const SceneDesc& scene, int steps) {
  double escapes = 0;
  const float bulletSpeed = scene.bulletCount > 0 ? rc::length(scene.bodies.back().velocity) : 0.0f;
  for (auto _ : state) {
    state.PauseTiming();
    Engine engine(scene);
    rc::Random rng(99);
    std::vector<bool> escaped(scene.bodies.size(), false);
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k) {
      engine.step();
      // Bullets that slowed down are fired again (the same draws for both engines).
      for (std::size_t i = scene.bodies.size() - static_cast<std::size_t>(scene.bulletCount);
           i < scene.bodies.size(); ++i) {
        // Escaped: the centre more than the bullet's radius past a wall's inner face.
        const Vec2 p = engine.position(i);
        const float limit = 100.0f + scene.bodies[i].radius;
        if (std::abs(p.x) > limit || std::abs(p.y) > limit) {
          escaped[i] = true;
          continue;
        }
        if (!escaped[i] && rc::length(engine.velocity(i)) < 20.0f)
          engine.respawn(i, rng.inBox({-95, -95}, {95, 95}), randomDirection(rng, bulletSpeed));
      }
    }
    state.PauseTiming();
    for (bool e : escaped)
      escapes += e;
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * steps);
  if (scene.bulletCount > 0)
    state.counters["escapes"] = escapes / static_cast<double>(state.iterations());
}

template <class Engine>
void runPyramid(benchmark::State& state, const SceneDesc& scene, int steps) {
  double drift = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Engine engine(scene);
    for (int k = 0; k < scene.settleSteps; ++k)
      engine.step();
    state.ResumeTiming();
    for (int k = 0; k < steps; ++k)
      engine.step();
    state.PauseTiming();
    const Vec2 top = engine.position(scene.bodies.size() - 1);
    drift += std::abs(top.y - scene.bodies.back().position.y);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations() * steps);
  state.counters["top_drift_m"] = drift / static_cast<double>(state.iterations());
}

enum class Kind { arena, pyramid };

// Registers "name/ours" and "name/box2d" on the same scene (or ours alone).
void race(const std::string& name, const SceneDesc* s, Kind kind, bool withBox2D = true) {
  auto run = [s, kind]<class Engine>(benchmark::State& st) {
    if (kind == Kind::arena)
      runArena<Engine>(st, *s, 300);
    else
      runPyramid<Engine>(st, *s, 1000);
  };
  auto* ours = benchmark::RegisterBenchmark(
      (name + (withBox2D ? "/ours" : "")).c_str(),
      [run](benchmark::State& st) { run.template operator()<Ours>(st); });
  ours->Unit(benchmark::kMillisecond);
  if (kind == Kind::pyramid) ours->Iterations(1);  // 1000 steps of a pyramid is long enough
  if (!withBox2D) return;
  auto* theirs = benchmark::RegisterBenchmark(
      (name + "/box2d").c_str(),
      [run](benchmark::State& st) { run.template operator()<Box2D>(st); });
  theirs->Unit(benchmark::kMillisecond);
  if (kind == Kind::pyramid) theirs->Iterations(1);
}

void registerAll() {
  static std::vector<std::unique_ptr<SceneDesc>> scenes;
  auto add = [](SceneDesc s) {
    scenes.push_back(std::make_unique<SceneDesc>(std::move(s)));
    return scenes.back().get();
  };
  for (int n : {100, 1000, 5000})
    race("arena/N=" + std::to_string(n), add(arena(n, 0, 0, 7)), Kind::arena);
  // What a scene that does not turn saves: the same 1000-circle arena with fixed rotation.
  SceneDesc still = arena(1000, 0, 0, 7);
  still.fixedRotation = true;
  race("arena, fixed rotation/N=1000", add(still), Kind::arena);
  // Static geometry never enters a per-step loop: 20,000 more static boxes outside the walls,
  // where nothing reaches them, should cost nothing per step.
  SceneDesc decorated = arena(1000, 0, 0, 7);
  for (float x = -126.5f; x <= 126.5f; x += 1.0f)
    for (float y = -126.5f; y <= 126.5f; y += 1.0f)
      if (std::max(std::abs(x), std::abs(y)) > 103.0f)
        decorated.statics.push_back({{x, y}, {0.2f, 0.2f}});
  race("arena, 20k static boxes outside/N=1000", add(decorated), Kind::arena);
  // No fast bodies, no continuous work: the same arena with continuous collision off.
  SceneDesc discrete = arena(1000, 0, 0, 7);
  discrete.continuous = false;
  race("arena, continuous off/N=1000", add(discrete), Kind::arena);
  race("bullets/100 m per s", add(arena(1000, 500, 100.0f, 8)), Kind::arena);
  // Ours alone at 1000 m/s (Box2D 2.4.1 caps motion at 2 m per step: 120 m/s).
  race("bullets 1000 m per s (ours alone)", add(arena(1000, 500, 1000.0f, 8)), Kind::arena, false);
  for (int base : {20, 40}) {
    race("pyramid/base " + std::to_string(base), add(pyramid(base)), Kind::pyramid);
    // The same pyramid with sleeping on in both engines: what a scene at rest costs.
    SceneDesc sleeping = pyramid(base);
    sleeping.sleep = true;
    race("pyramid, sleeping on/base " + std::to_string(base), add(sleeping), Kind::pyramid);
  }
  // Nothing awake costs almost nothing: the base-20 pyramid once it has fallen asleep in both
  // engines (untimed 1200 steps first), then 1000 timed steps.
  SceneDesc asleep = pyramid(20);
  asleep.sleep = true;
  asleep.settleSteps = 1200;
  race("pyramid asleep/base 20", add(asleep), Kind::pyramid);
}

}  // namespace

int main(int argc, char** argv) {
  return rc::bench::runWithRatioTable(argc, argv, "world_bench", registerAll);
}
