// A scene (game/scene.h) built in Box2D 2.4.1, for the oracle scenes and the box2d_sim tool:
// the same bodies, shapes, materials and filters as our World gets from the same file.
//
// What Box2D 2.4.1 cannot represent is refused with a SceneError naming the body and shape
// rather than approximated: capsules (no such shape), rounded polygons (its polygons have a fixed
// 0.01 m skin), filter bits above 16 (its filters are 16-bit), polygons of more than 8 vertices.
// Box2D has one integrator (semi-implicit Euler) and no substeps: those settings are ignored,
// and it steps with 8 velocity and 3 position iterations, its testbed's defaults, unless told
// otherwise. A body's constant force and torque are applied before every step (Box2D clears
// them after each), waking the body as a force field wakes ours.
#pragma once

#include <box2d/box2d.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "game/scene.h"

namespace rc::testing {

struct Box2DScene {
  std::unique_ptr<b2World> world;
  std::vector<b2Body*> bodies;  // bodies[i] is body i of the scene
  // The bodies with a constant force (at a point in the body's frame, or the centre) or torque.
  struct Push {
    b2Body* body;
    b2Vec2 force;
    float torque;
    std::optional<b2Vec2> point;
  };
  std::vector<Push> pushed;

  // Box2D's polygons carry a b2_polygonRadius (0.01 m) skin around the polygon they are given,
  // so its boxes are 0.02 m wider than ours and rest 0.015 m higher on each other. Skin::inside
  // gives it each box 0.01 m smaller (and denser by the area lost: the same mass), so that the
  // surfaces are where ours are: for comparing heights against geometry.
  enum class Skin { outside, inside };

  explicit Box2DScene(const game::SceneDesc& scene, Skin skin = Skin::outside) : skin_(skin) {
    world = std::make_unique<b2World>(b2Vec2(scene.world.gravity.x, scene.world.gravity.y));
    world->SetAllowSleeping(scene.world.enableSleep);
    world->SetContinuousPhysics(scene.world.continuous);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const game::BodyDesc& b = scene.bodies[i];
      const std::string where = scene.source + ": body " + std::to_string(i) +
                                (b.name.empty() ? "" : " (\"" + b.name + "\")");
      b2BodyDef bd;
      bd.type = b.def.type == BodyType::dynamicBody     ? b2_dynamicBody
                : b.def.type == BodyType::kinematicBody ? b2_kinematicBody
                                                        : b2_staticBody;
      bd.position.Set(b.def.position.x, b.def.position.y);
      bd.angle = b.def.angle;
      // Box2D's initial velocity is the body origin's; ours is the centre of mass's. The
      // scenes used with both put the centre of mass at the origin or spin nothing.
      bd.linearVelocity.Set(b.def.linearVelocity.x, b.def.linearVelocity.y);
      bd.angularVelocity = b.def.angularVelocity;
      bd.linearDamping = b.def.linearDamping;
      bd.angularDamping = b.def.angularDamping;
      bd.gravityScale = b.def.gravityScale;
      bd.fixedRotation = b.def.fixedRotation;
      bd.bullet = b.def.bullet;
      bd.allowSleep = b.def.allowSleep;
      b2Body* body = world->CreateBody(&bd);
      for (std::size_t s = 0; s < b.shapes.size(); ++s)
        addFixture(body, b.shapes[s], where + ", shapes[" + std::to_string(s) + "]");
      bodies.push_back(body);
      if (b.pushed()) {
        std::optional<b2Vec2> point;
        if (b.forcePoint) point = b2Vec2(b.forcePoint->x, b.forcePoint->y);
        pushed.push_back({body, b2Vec2(b.force.x, b.force.y), b.torque, point});
      }
    }
  }

  void step(float dt, int velocityIterations = 8, int positionIterations = 3) {
    for (const Push& p : pushed) {
      if (p.point)
        p.body->ApplyForce(p.force, p.body->GetWorldPoint(*p.point), true);
      else if (p.force != b2Vec2_zero)
        p.body->ApplyForceToCenter(p.force, true);
      if (p.torque != 0.0f) p.body->ApplyTorque(p.torque, true);
    }
    world->Step(dt, velocityIterations, positionIterations);
  }

  game::SceneState state(const game::SceneDesc& scene, int steps, double time) const {
    game::SceneState out;
    out.engine = "box2d 2.4.1";
    out.steps = steps;
    out.time = time;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const b2Body* b = bodies[i];
      out.bodies.push_back({scene.bodies[i].name,
                            {b->GetPosition().x, b->GetPosition().y},
                            b->GetAngle(),
                            {b->GetLinearVelocity().x, b->GetLinearVelocity().y},
                            b->GetAngularVelocity()});
    }
    return out;
  }

 private:
  Skin skin_;

  void addFixture(b2Body* body, const game::ShapeDesc& desc, const std::string& where) {
    const ShapeDef& d = desc.def;
    if (d.filter.category > 0xFFFFu || (d.filter.mask != 0xFFFFFFFFu && d.filter.mask > 0xFFFFu))
      throw game::SceneError(where + ": Box2D 2.4.1 filters have 16 bits");
    b2FixtureDef fd;
    fd.density = d.density;
    fd.friction = d.friction;
    fd.restitution = d.restitution;
    fd.isSensor = d.isSensor;
    fd.filter.categoryBits = static_cast<uint16>(d.filter.category);
    fd.filter.maskBits = static_cast<uint16>(d.filter.mask & 0xFFFFu);
    const Shape& s = desc.shape;
    b2CircleShape circle;
    b2PolygonShape polygon;
    b2EdgeShape edge;
    switch (s.type) {
      case ShapeType::circle:
        circle.m_p.Set(s.circle.center.x, s.circle.center.y);
        circle.m_radius = s.circle.radius;
        fd.shape = &circle;
        break;
      case ShapeType::box:
        if (skin_ == Skin::inside) {
          const float r = b2_polygonRadius, hx = s.box.halfExtents.x, hy = s.box.halfExtents.y;
          if (hx <= 2 * r || hy <= 2 * r)
            throw game::SceneError(where + ": too thin to lose Box2D's skin");
          polygon.SetAsBox(hx - r, hy - r, b2Vec2(s.box.center.x, s.box.center.y), 0.0f);
          fd.density = d.density * (hx * hy) / ((hx - r) * (hy - r));
        } else {
          polygon.SetAsBox(s.box.halfExtents.x, s.box.halfExtents.y,
                           b2Vec2(s.box.center.x, s.box.center.y), 0.0f);
        }
        fd.shape = &polygon;
        break;
      case ShapeType::polygon: {
        if (s.polygon.radius > 0.0f)
          throw game::SceneError(where + ": Box2D 2.4.1 has no rounded polygons");
        b2Vec2 points[b2_maxPolygonVertices];
        for (int k = 0; k < s.polygon.count; ++k)
          points[k].Set(s.polygon.vertices[k].x, s.polygon.vertices[k].y);
        polygon.Set(points, s.polygon.count);
        fd.shape = &polygon;
        break;
      }
      case ShapeType::capsule:
        throw game::SceneError(where + ": Box2D 2.4.1 has no capsules");
      case ShapeType::segment:
        edge.SetTwoSided(b2Vec2(s.segment.point1.x, s.segment.point1.y),
                         b2Vec2(s.segment.point2.x, s.segment.point2.y));
        fd.shape = &edge;
        break;
      case ShapeType::chainSegment: {
        const ChainSegment& c = s.chainSegment;
        const b2Vec2 p1(c.segment.point1.x, c.segment.point1.y);
        const b2Vec2 p2(c.segment.point2.x, c.segment.point2.y);
        // Our open ends repeat the endpoint; Box2D's chains extend the end link instead.
        const b2Vec2 g1 =
            c.ghost1 == c.segment.point1 ? 2.0f * p1 - p2 : b2Vec2(c.ghost1.x, c.ghost1.y);
        const b2Vec2 g2 =
            c.ghost2 == c.segment.point2 ? 2.0f * p2 - p1 : b2Vec2(c.ghost2.x, c.ghost2.y);
        if (c.oneSided)
          edge.SetOneSided(g1, p1, p2, g2);
        else
          edge.SetTwoSided(p1, p2);
        fd.shape = &edge;
        break;
      }
    }
    body->CreateFixture(&fd);
  }
};

}  // namespace rc::testing
