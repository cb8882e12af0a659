// Free fall against Box2D 2.4.1: one dynamic body under gravity for 1 s at 60 Hz. Box2D's
// integrator is semi-implicit Euler (v += h g, then x += h v), so ours must follow it step by
// step to rounding, and both are off the closed form by g h t / 2. Box2D forms the velocity
// change as h * invMass * (mass * g), an ulp or two from our h * g: the tolerances are a few
// ulps of the values reached (|v| <= 10 m/s, ulp 1e-6; |y| <= 100 m, ulp 8e-6).
#include <box2d/box2d.h>
#include <gtest/gtest.h>

#include <span>

#include "physics/integrate.h"

namespace {

TEST(IntegratorOracle, FreeFallMatchesBox2D) {
  const float g = -10.0f, h = 1.0f / 60.0f;
  b2World world(b2Vec2(0.0f, g));
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position.Set(0.0f, 100.0f);
  b2Body* body = world.CreateBody(&def);
  b2CircleShape circle;
  circle.m_radius = 0.5f;
  body->CreateFixture(&circle, 1.0f);

  float q[2] = {0.0f, 100.0f}, v[2] = {0.0f, 0.0f};
  rc::IntegratorScratch<float> scratch;
  auto gravity = [g](std::span<const float>, std::span<const float>, float, std::span<float> a) {
    a[0] = 0.0f;
    a[1] = g;
  };
  for (int k = 0; k < 60; ++k) {
    world.Step(h, 8, 3);
    rc::integrate<float>(rc::Integrator::semiImplicitEuler, q, v, static_cast<float>(k) * h, h,
                         gravity, scratch);
    // Every step, not only the last.
    ASSERT_NEAR(body->GetPosition().y, q[1], 4e-5f) << "step " << k;
    ASSERT_NEAR(body->GetLinearVelocity().y, v[1], 4e-6f) << "step " << k;
  }
  const double t = 1.0, exact = 100.0 + 0.5 * g * t * t;
  EXPECT_NEAR(static_cast<double>(body->GetPosition().y) - exact, 0.5 * g * h * t, 1e-5);
}

}  // namespace
