// Small scenes and closed forms shared by the world API tests (body_test, body_shape_test,
// query_test): the ground, bodies placed by definition, fixed-rate stepping, and where a free
// body is after n steps of the world's integrator.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "physics/world.h"

namespace rc::testing {

inline constexpr float kStep = 1.0f / 60.0f;

inline BodyDef bodyAt(BodyType type, Vec2 p, float angle = 0.0f) {
  BodyDef def;
  def.type = type;
  def.position = p;
  def.angle = angle;
  return def;
}
inline BodyDef dynamicAt(Vec2 p, float angle = 0.0f) {
  return bodyAt(BodyType::dynamicBody, p, angle);
}

// A static 100 x 20 m slab whose top face is y = 0.
inline BodyId ground(World& w, float friction = 0.6f, float restitution = 0.0f) {
  BodyId g = w.createBody(bodyAt(BodyType::staticBody, {0, -10}));
  ShapeDef sd;
  sd.friction = friction;
  sd.restitution = restitution;
  w.createShape(g, makeBox(50, 10), sd);
  return g;
}

// A dynamic box of half-size `half` centred at p, with the given shape definition.
inline BodyId boxAt(World& w, Vec2 p, float half = 0.5f, const ShapeDef& sd = {}) {
  BodyId b = w.createBody(dynamicAt(p));
  w.createShape(b, makeBox(half, half), sd);
  return b;
}

// A pyramid of touching 1 m boxes, `base` wide, standing on y = origin.y and centred on
// origin.x (the ground is the caller's): its bodies row by row from the bottom, left to right.
inline std::vector<BodyId> pyramidOfBoxes(World& w, int base, Vec2 origin = {}) {
  std::vector<BodyId> boxes;
  for (int row = 0; row < base; ++row)
    for (int i = 0; i < base - row; ++i)
      boxes.push_back(
          boxAt(w, origin + Vec2{static_cast<float>(i) - 0.5f * static_cast<float>(base - row - 1),
                                 0.5f + static_cast<float>(row)}));
  return boxes;
}

inline void stepN(World& w, int n, float dt = kStep) {
  for (int i = 0; i < n; ++i)
    w.step(dt);
}

// How far a free body falls in `steps` world steps of dt under acceleration g (positive down),
// starting at rest: semi-implicit Euler with `substeps` substeps of h = dt / substeps gives
// v_k = -k g h and y_k = -g h^2 k (k + 1) / 2 after k substeps (the world's default
// integrator; FreeBodiesFollowTheIntegratorExactly checks that free bodies follow it). The
// continuous g t^2 / 2 is less by g h t / 2.
inline double eulerFall(double g, float dt, int substeps, int steps) {
  const double h = static_cast<double>(dt) / substeps;
  const double k = static_cast<double>(steps) * substeps;
  return g * h * h * k * (k + 1.0) / 2.0;
}

// Ground and `count` 1 m boxes resting on it, `spacing` apart from x = 0 (each its own island),
// stepped for 1 s: long enough for all of them to fall asleep.
inline std::vector<BodyId> restingRow(rc::World& w, int count, float spacing) {
  ground(w);
  std::vector<BodyId> row;
  for (int i = 0; i < count; ++i) {
    BodyId b = w.createBody(dynamicAt({spacing * static_cast<float>(i), 0.5f}));
    w.createShape(b, rc::makeBox(0.5f, 0.5f));
    row.push_back(b);
  }
  for (int i = 0; i < 60; ++i)
    w.step(1.0f / 60.0f);
  return row;
}

// Every body's position, angle and velocities are finite (the "no NaN in any test":
// the checks below compare with std::max and friends, which would pass a NaN by).
inline ::testing::AssertionResult finiteState(const rc::World& w) {
  for (BodyId b : w.bodies()) {
    const Vec2 p = w.position(b), v = w.linearVelocity(b);
    if (!(rc::isFinite(p) && rc::isFinite(v) && std::isfinite(w.angle(b)) &&
          std::isfinite(w.angularVelocity(b))))
      return ::testing::AssertionFailure()
             << "body " << b.index << " at (" << p.x << ", " << p.y << ") angle " << w.angle(b)
             << " velocity (" << v.x << ", " << v.y << ") " << w.angularVelocity(b);
  }
  return ::testing::AssertionSuccess();
}

// Steps `w` at 60 Hz `steps` times, watching its total energy: the start, the highest seen (the
// start included), and the first step whose state was not finite (-1: none; it stops there).
struct EnergyRun {
  double start = 0, highest = 0;
  int nonFiniteStep = -1;
};

inline EnergyRun stepWatchingEnergy(rc::World& w, int steps) {
  EnergyRun run;
  run.start = run.highest = w.energy();
  for (int i = 0; i < steps; ++i) {
    w.step(1.0f / 60.0f);
    if (!finiteState(w)) {
      run.nonFiniteStep = i;
      break;
    }
    run.highest = std::max(run.highest, w.energy());
  }
  return run;
}

}  // namespace rc::testing
