// Ricochet physics: the world of rigid bodies, as a game sees it.
//
// Bodies (static, kinematic, dynamic) carry shapes; World::step(dt) advances them by a fixed
// time step in named phases, each timed into profile() (physics/README.md describes them, in
// order). Bodies and shapes are referred to by generational handles: a handle to a destroyed
// body is detected, never silently reused. Events are read after the step; queries take a
// filter. The state and the step's functions live behind a pointer (world_state.h, internal).
//
// The contact solver is the "soft step" of Catto's Solver2D study (Box2D v3), with contacts
// within the slop solved rigidly and both points of a manifold solved together; the world's
// integrator (physics/integrate.h) moves each body as if nothing touched it and the contacts'
// velocity change moves it further, so a body nothing pushes follows its integrator exactly.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "physics/broadphase.h"
#include "physics/integrate.h"
#include "physics/shapes.h"
#include "physics/step_accumulator.h"

namespace rc {

// A definition field out of range or not finite; the message names the definition and field.
class InvalidDefinition : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct BodyId {
  std::int32_t index = -1;
  std::uint32_t generation = 0;
  friend constexpr bool operator==(BodyId, BodyId) = default;
};
struct ShapeId {
  std::int32_t index = -1;
  std::uint32_t generation = 0;
  friend constexpr bool operator==(ShapeId, ShapeId) = default;
};

enum class BodyType : std::uint8_t { staticBody, kinematicBody, dynamicBody };

struct BodyDef {
  BodyType type = BodyType::staticBody;
  Vec2 position{};  // body origin, world frame
  float angle = 0.0f;
  Vec2 linearVelocity{};  // of the centre of mass
  float angularVelocity = 0.0f;
  float linearDamping = 0.0f;  // 1/s, applied implicitly: v /= 1 + h c
  float angularDamping = 0.0f;
  float gravityScale = 1.0f;
  bool fixedRotation = false;
  bool bullet = false;  // continuous collision against moving bodies too, bullets included
  bool allowSleep = true;
  std::uint64_t userData = 0;
};

struct ShapeDef {
  float density = 1.0f;  // kg/m^2
  float friction = 0.6f;
  float restitution = 0.0f;
  ProxyFilter filter;
  bool isSensor = false;  // detects overlaps (sensorEvents()), never collides
  std::uint64_t userData = 0;
};

struct WorldDef {
  Vec2 gravity{0.0f, -10.0f};
  Integrator integrator = Integrator::semiImplicitEuler;
  int substeps = 4;
  // Approach speeds below this bounce with no restitution (m/s).
  float restitutionThreshold = 1.0f;
  // Contacts that begin closing faster than this report a hit event (m/s).
  float hitEventThreshold = 1.0f;
  // Contact stiffness in Hz, capped at a quarter of the substep rate; damping ratio.
  float contactHertz = 30.0f;
  float contactDampingRatio = 10.0f;
  // The fastest overlapping bodies are pushed apart (m/s).
  float maxPushoutSpeed = 3.0f;
  // Continuous collision: contact points are kept while shapes are within what their bodies
  // can close in the step (speculative contacts), so fast bodies stop at surfaces instead of
  // passing through thin walls. Off: only within kSpeculativeDistance (shows the tunnelling).
  bool continuous = true;
  // Sleeping: an island of touching bodies whose every body has moved slower than the
  // tolerances for timeToSleep seconds stops being simulated until something wakes it (a
  // contact with an awake body, a force, an impulse, a velocity or transform set, wake()).
  bool enableSleep = true;
  float timeToSleep = 0.5f;                                   // s
  float linearSleepTolerance = 0.05f;                         // m/s
  float angularSleepTolerance = 2.0f * 3.14159265f / 180.0f;  // rad/s
  // The region most bodies live in: the quadtree's world square. Bodies outside it still work.
  AABB bounds{{-512.0f, -512.0f}, {512.0f, 512.0f}};
};

// What a world query hit.
struct WorldHit {
  ShapeId shape;
  BodyId body;
  Vec2 point{};   // world frame
  Vec2 normal{};  // surface normal of the shape hit
  float fraction = 0.0f;
};

// Events of the last step, read after it (cleared at the start of the next). A contact begins
// when its manifold gets points: within the speculative margin, which for a fast body can be
// the step before the surfaces meet (then the point and normal are those where they will meet,
// and a fast pair that will not meet this step gets none); approachSpeed is measured then,
// before the solve.
struct ContactBeginEvent {
  ShapeId shapeA, shapeB;
  Vec2 point{}, normal{};   // normal from A to B
  float approachSpeed = 0;  // along the normal, positive when closing
};
struct ContactEndEvent {
  ShapeId shapeA, shapeB;
};
// A contact that began (or was hit again) faster than WorldDef::hitEventThreshold.
struct ContactHitEvent {
  ShapeId shapeA, shapeB;
  Vec2 point{}, normal{};
  float approachSpeed = 0;
};
// A shape entered or left a sensor. A visitor that passes right through a sensor within one
// step (a bullet through a trip line) reports both in that step.
struct SensorEvent {
  ShapeId sensor, visitor;
};
struct SensorEvents {
  std::vector<SensorEvent> begin, end;
};

struct ContactEvents {
  std::vector<ContactBeginEvent> begin;
  std::vector<ContactEndEvent> end;
  std::vector<ContactHitEvent> hit;
};

// Wall-clock milliseconds of the last step, by phase.
struct Profile {
  double updatePairs = 0, narrowphase = 0, solve = 0, continuous = 0, refit = 0, sensors = 0,
         sleep = 0, total = 0;  // milliseconds
  // The contact solver's last step: colours in use, and constraints solved one at a time
  // because a body had more contacts than there are colours.
  int colours = 0, overflow = 0;
};

class WorldState;

// What a force field sees at one stage of the integrator: the stage's state of every body and
// a place to add forces. Forces added here act for that stage only.
class ForceStage {
 public:
  Vec2 center(BodyId id) const;  // centre of mass
  float angle(BodyId id) const;
  Vec2 velocity(BodyId id) const;
  float angularVelocity(BodyId id) const;
  float time() const { return time_; }
  void addForce(BodyId id, Vec2 force);  // at the centre of mass
  void addTorque(BodyId id, float torque);
  void addForceAt(BodyId id, Vec2 force, Vec2 worldPoint);

 private:
  friend class WorldState;
  ForceStage(WorldState& world, std::span<const double> q, std::span<const float> v,
             std::span<float> a, float time)
      : world_(world), q_(q), v_(v), a_(a), time_(time) {}
  int slot(BodyId id) const;
  WorldState& world_;
  std::span<const double> q_;
  std::span<const float> v_;
  std::span<float> a_;
  float time_;
};

using ForceField = std::function<void(ForceStage&)>;

class World {
 public:
  explicit World(const WorldDef& def = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  BodyId createBody(const BodyDef& def);
  void destroyBody(BodyId id);
  ShapeId createShape(BodyId body, const Shape& shape, const ShapeDef& def = {});

  void step(float dt);

  // Body state.
  bool isValid(BodyId id) const;
  Vec2 position(BodyId id) const;  // body origin
  // The body origin as the world keeps it, in double: far from the world origin a float
  // position is coarse (1 mm apart 10 km out) and position() rounds to it.
  std::array<double, 2> precisePosition(BodyId id) const;
  float angle(BodyId id) const;
  Transform transform(BodyId id) const;
  Vec2 worldCenter(BodyId id) const;
  Vec2 linearVelocity(BodyId id) const;
  float angularVelocity(BodyId id) const;
  float mass(BodyId id) const;
  float rotationalInertia(BodyId id) const;  // about the centre of mass
  BodyType type(BodyId id) const;
  std::uint64_t userData(BodyId id) const;
  void setLinearVelocity(BodyId id, Vec2 v);
  void setAngularVelocity(BodyId id, float w);
  void setTransform(BodyId id, Vec2 position, float angle);
  bool isAwake(BodyId id) const;
  // Wakes the body and every body asleep in its island.
  void wake(BodyId id);
  int awakeBodyCount() const;

  // Forces and torques act for the next step, then are cleared. Impulses change the velocity
  // at once.
  void applyForce(BodyId id, Vec2 force, Vec2 worldPoint);
  void applyForceToCenter(BodyId id, Vec2 force);
  void applyTorque(BodyId id, float torque);
  void applyLinearImpulse(BodyId id, Vec2 impulse, Vec2 worldPoint);
  void applyAngularImpulse(BodyId id, float impulse);

  // The same queries for a caller that wants what they find disturbed (a blast that wakes the
  // crates in its area, a ray that should rouse what it touches): with Wake::yes every
  // sleeping body they report is woken, with its island.
  enum class Wake : std::uint8_t { no, yes };
  std::optional<WorldHit> castRay(Vec2 origin, Vec2 translation, ProxyFilter filter, Wake wake);
  std::vector<ShapeId> overlapAABB(const AABB& box, ProxyFilter filter, Wake wake);

  // Queries. Rays and casts go along origin + t * translation, t in [0, 1]; the closest hit
  // (ties to the lower shape id) or every hit sorted by fraction, then shape id. Sensors are
  // skipped. A ray starting inside a solid shape hits it at fraction 0 (see raycast.h).
  std::optional<WorldHit> castRay(Vec2 origin, Vec2 translation, ProxyFilter filter = {}) const;
  std::vector<WorldHit> castRayAll(Vec2 origin, Vec2 translation, ProxyFilter filter = {}) const;
  // A circle swept along the translation (bullets with a size, a character's movement).
  std::optional<WorldHit> castCircle(Vec2 center, float radius, Vec2 translation,
                                     ProxyFilter filter = {}) const;
  // Shapes whose AABB overlaps the box, or that contain the point; sorted by shape id.
  std::vector<ShapeId> overlapAABB(const AABB& box, ProxyFilter filter = {}) const;
  std::vector<ShapeId> overlapPoint(Vec2 point, ProxyFilter filter = {}) const;
  BodyId bodyOf(ShapeId shape) const;

  const ContactEvents& contactEvents() const;
  const SensorEvents& sensorEvents() const;

  // A user force evaluated at every integrator stage (springs, drag, attractors).
  void addForceField(ForceField field);

  int bodyCount() const;
  int contactCount() const;
  int touchingContactCount() const;

  // Read-only views for tools that draw or inspect a world (the renderer's overlay).
  std::vector<BodyId> bodies() const;              // alive ones, by index
  std::vector<ShapeId> shapesOf(BodyId id) const;  // in creation order
  const Shape& shape(ShapeId id) const;
  bool isSensor(ShapeId id) const;
  struct ContactPointView {
    Vec2 point, normal;  // normal from shape A to shape B
    float separation;
    float normalImpulse;  // of the last step's last substep (a bounce's not included)
  };
  std::vector<ContactPointView> contactPoints() const;  // of touching contacts
  const Quadtree& broadphase() const;
  const WorldDef& def() const;
  const Profile& profile() const;
  double time() const;

  // FNV-1a over the bits of every body's position, angle and velocities, in creation order:
  // equal hashes mean bit-identical states.
  std::uint64_t stateHash() const;

  // Total kinetic energy plus gravitational potential energy (relative to y = 0).
  double energy() const;

 private:
  std::unique_ptr<WorldState> s_;
};

}  // namespace rc
