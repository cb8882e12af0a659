// Ricochet physics: the world of rigid bodies.
//
// Bodies (static, kinematic, dynamic) carry shapes; the world steps them with a fixed time step:
//
//   updatePairs   the quadtree reports the new pairs of proxies that moved (contacts created)
//   narrowphase   every contact's manifold from the current transforms, matched to last step's
//                 points by feature id (contacts whose fat AABBs parted are destroyed); points
//                 are kept while the shapes are within what their bodies can close this step
//                 (speculative contacts), so a fast body stops at the surface instead of
//                 sinking into it and bouncing from inside; a fast pair's points are taken
//                 where its motion makes them meet (the normal of the impact), or dropped if
//                 it never does (no ghost collisions between bodies that pass close by)
//   solve         prepare the contact constraints, then substeps of: free motion by the world's
//                 integrator (forces evaluated at its stages), warm start, solve contacts (soft),
//                 positions corrected by the velocity the contacts changed, relax; then
//                 restitution, and the impulses stored for the next step's warm start
//   continuous    fast bodies swept against static shapes and stopped at the first time of
//                 impact (what speculative contacts cannot foresee: a body deflected mid-step)
//   sensors       sensor overlaps from the new transforms, and visitors swept through them
//   refit         body transforms, shape AABBs and quadtree proxies updated, each fat AABB
//                 stretched along the body's next step (its velocity times dt), so the pairs a
//                 fast body will meet exist before it moves
//   sleep         islands of touching bodies that have been still long enough stop being
//                 simulated (they cost nothing per step until woken)
//
// Each phase is timed into profile(). Bodies are referred to by generational handles: a handle
// to a destroyed body is detected, never silently reused.
//
// The contact solver is the "soft step" of Catto's Solver2D study (Box2D v3): each contact is a
// soft constraint (a spring-damper with a stiffness tied to the substep rate), solved with
// substeps and a relax pass without bias, restitution applied once at the end. Chosen over
// Box2D 2.4's sequential impulses with a separate position pass because in that study it kept
// tall stacks and large mass ratios upright with a fraction of the iterations, it adds no energy
// when pushing overlapping bodies apart (the push-out speed is capped and removed by relax), and
// substeps keep the integrator's accuracy between contacts. Two additions of ours: a contact
// within the linear slop is rigid (no softness), so a stack carries its load without sinking
// (a soft spring must compress to push back: 19 cm at the top of a 40-box pyramid), and is
// pushed out towards half the slop, so what it took in while settling comes back out; and the
// two points of a manifold are solved together (a 2x2 complementarity problem), so that a
// symmetric stack stays symmetric.
//
// Integrators (physics/integrate.h): the world's integrator moves every body over each substep
// as if nothing touched it; the contact solver's velocity change dv then moves the body by
// h dv more. A body no contact pushes therefore follows its integrator exactly (RK4 stays fourth
// order on an orbit or a spring), and with semi-implicit Euler this is Box2D's update.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "physics/broadphase.h"
#include "physics/contact_solver.h"
#include "physics/integrate.h"
#include "physics/manifold.h"
#include "physics/shapes.h"
#include "physics/toi.h"

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

class World;

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
  friend class World;
  ForceStage(World& world, std::span<const double> q, std::span<const float> v, std::span<float> a,
             float time)
      : world_(world), q_(q), v_(v), a_(a), time_(time) {}
  int slot(BodyId id) const;
  World& world_;
  std::span<const double> q_;
  std::span<const float> v_;
  std::span<float> a_;
  float time_;
};

using ForceField = std::function<void(ForceStage&)>;

class World {
 public:
  explicit World(const WorldDef& def = {});

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
  int awakeBodyCount() const { return awakeCount_; }

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

  const ContactEvents& contactEvents() const { return events_; }
  const SensorEvents& sensorEvents() const { return sensorEvents_; }

  // A user force evaluated at every integrator stage (springs, drag, attractors).
  void addForceField(ForceField field) { fields_.push_back(std::move(field)); }

  int bodyCount() const { return bodyCount_; }
  int contactCount() const { return static_cast<int>(contacts_.size()); }
  int touchingContactCount() const;

  // Read-only views for tools that draw or inspect a world (the renderer's overlay).
  std::vector<BodyId> bodies() const;              // alive ones, by index
  std::vector<ShapeId> shapesOf(BodyId id) const;  // in creation order
  const Shape& shape(ShapeId id) const;
  bool isSensor(ShapeId id) const;
  struct ContactPointView {
    Vec2 point, normal;  // normal from shape A to shape B
    float separation;
    float normalImpulse;  // of the last step
  };
  std::vector<ContactPointView> contactPoints() const;  // of touching contacts
  const Quadtree& broadphase() const { return broadphase_; }
  const WorldDef& def() const { return def_; }
  const Profile& profile() const { return profile_; }
  double time() const { return time_; }

  // FNV-1a over the bits of every body's position, angle and velocities, in creation order:
  // equal hashes mean bit-identical states.
  std::uint64_t stateHash() const;

  // Total kinetic energy plus gravitational potential energy (relative to y = 0).
  double energy() const;

 private:
  friend class ForceStage;
  struct Body {
    BodyType type = BodyType::staticBody;
    bool alive = false;
    bool fixedRotation = false;
    bool bullet = false;
    std::uint32_t generation = 0;
    Transform xf;  // body origin and rotation (refreshed after every step)
    float angle = 0;
    Vec2 localCenter{};
    Vec2 force{};
    float torque = 0;
    float mass = 0, invMass = 0, inertia = 0, invInertia = 0;
    float linearDamping = 0, angularDamping = 0, gravityScale = 1;
    float minExtent = 0, maxExtent = 0;  // for continuous collision (see continuous())
    bool allowSleep = true;
    float sleepTime = 0;       // how long it has been slower than the sleep tolerances
    std::int32_t island = -1;  // its sleeping island, -1 while awake
    std::uint64_t userData = 0;
    std::int32_t slot = -1;  // in q_ and v_; -1 for static bodies
    // Every shape a circle about the centre of mass: turning moves none of its contact
    // geometry, so the solver does not rotate its contact anchors (see solve()).
    bool round = false;
    std::vector<std::int32_t> shapes;
  };
  struct ShapeRecord {
    Shape shape = Circle{};
    std::int32_t body = -1;
    std::uint32_t generation = 0;
    bool alive = false;
    bool isSensor = false;
    float density = 0, friction = 0, restitution = 0;
    ProxyId proxy = kNullProxy;
    std::uint64_t userData = 0;
    BoundingCircle bound{};  // in the body frame: how far the shape reaches as the body turns
  };
  struct Contact {
    std::int32_t shapeA = -1, shapeB = -1;  // shapeA < shapeB
    Manifold manifold;
    float normalImpulse[2] = {0, 0}, tangentImpulse[2] = {0, 0};
    float friction = 0, restitution = 0;
    bool touching = false;
  };

  std::size_t checked(BodyId id) const;
  const ShapeRecord& shapeRecord(ShapeId id) const;
  ShapeId shapeId(std::int32_t index) const {
    return {index, shapes_[static_cast<std::size_t>(index)].generation};
  }
  CastOutput rayAgainst(ProxyId proxy, const RayCastInput& ray) const;
  template <class Exact>
  std::optional<WorldHit> closest(const RayCastInput& in, float radius, ProxyFilter filter,
                                  Exact&& exact) const;
  Body& body(BodyId id) { return bodies_[checked(id)]; }
  const Body& body(BodyId id) const { return bodies_[checked(id)]; }
  Vec2 center(const Body& b) const;
  Vec2 velocityOf(const Body& b) const;
  template <class Solve>
  void forEachConstraint(Solve&& solve);
  void applyRestitution();
  void updateMass(Body& b);
  void refitBody(Body& b, Vec2 displacement);
  void updatePairs();
  void narrowphase(float dt);
  void foresee(Manifold& m, const ShapeRecord& ra, const Transform& xfA, const ShapeRecord& rb,
               const Transform& xfB, float dt) const;
  void solve(float h);
  void continuous();
  void updateSleep(float dt);
  void updateSensors();
  void destroySensorPair(std::size_t index);
  bool awake(const Body& b) const { return b.slot >= 0 && b.slot < awakeCount_; }
  void wakeBody(Body& b);
  void swapSlots(std::int32_t a, std::int32_t b);
  void destroyContact(std::size_t index);
  void accelerations(std::span<const double> q, std::span<const float> v, float t,
                     std::span<float> a);
  // The body's origin in double (its centre minus the turned local centre): what the
  // narrowphase takes differences of.
  std::array<double, 2> preciseOrigin(const Body& b) const;
  double preciseOrigin(const Body& b, int axis) const;  // one component: 0 x, 1 y
  // An awake body's motion over the step so far, from where it started (float: for sweeps).
  Sweep stepSweep(const Body& b) const;
  bool isRound(const Body& b) const;  // see Body::round
  void reserveTurns(std::size_t n);
  // Takes the queued angles' sines and cosines (turnAngles_) and hands each owner its rotation.
  template <class Apply>
  void applyTurns(Apply&& apply);

  WorldDef def_;
  Quadtree broadphase_;
  std::vector<Body> bodies_;
  std::vector<std::int32_t> freeBodies_;
  std::vector<ShapeRecord> shapes_;
  std::vector<Contact> contacts_;
  std::vector<ForceField> fields_;
  // Per simulated (kinematic and dynamic) body, three degrees of freedom: x, y and angle of the
  // centre of mass, and their velocities. Bodies hold their slot. Positions are doubles: 10 km
  // out a float position moves in steps of 1 mm and a settling pile cannot take the small steps
  // it needs (everything else, velocities, impulses, shapes and the narrowphase, which works
  // relative to body A, is float).
  std::vector<double> q_;
  std::vector<float> v_;
  std::vector<std::int32_t> slotBody_;
  // Slots [0, awakeCount_) are awake; sleeping bodies' slots follow, untouched by the step.
  int awakeCount_ = 0;
  std::vector<std::vector<std::int32_t>> islands_;  // sleeping islands: their bodies
  std::vector<std::int32_t> freeIslands_;
  std::vector<std::int32_t> islandParent_;  // union-find over awake slots, per step
  IntegratorScratch<float, double> scratch_;
  std::vector<ProxyPair> newPairs_;
  // Bodies created, moved or given a velocity since the last step: their proxies are stretched
  // along their first step's motion before pairs are found.
  std::vector<std::int32_t> pendingRefit_;
  // The step's constraints, in the solver's order: the contact and bodies of each, and what
  // the solver's colouring needs; the constraints with restitution, whole, and their indices.
  struct ConstraintSource {
    std::int32_t contact, bodyA, bodyB;
  };
  std::vector<ConstraintSource> constraintSources_;
  std::vector<ConstraintBodies> constraintBodies_;
  std::vector<ContactConstraint> bouncy_;
  std::vector<std::int32_t> bouncyIndex_;
  ContactSolver contactSolver_;
  // Per slot during the solve: the free-motion velocities of the substep, and the solver's
  // bodies (velocity, and how far each has moved and turned since the constraints were
  // prepared), plus the null body at the end.
  std::vector<float> freeV_;
  std::vector<SolverBody> solverBodies_;
  std::vector<SolverBody> freeMotion_;  // solverBodies_ before the warm start (restitution's)
  std::vector<double> startCenter_;     // x and y per slot
  std::vector<double> startAngle_;
  // Body::round per slot, read each substep (a byte each: reading it from the bodies instead
  // cost the 5000-circle arena 2.5%).
  std::vector<std::uint8_t> slotRound_;
  std::vector<float> baseAccel_;      // per awake slot: gravity, force and torque accelerations
  std::vector<std::int32_t> damped_;  // awake slots with linear or angular damping
  // Angles whose sine and cosine are wanted, taken in one batch (see rc::sincos), and the
  // bodies or slots they belong to.
  std::vector<float> turnAngles_;
  std::vector<SinCos> turnRotations_;
  std::vector<std::int32_t> turnOwners_;
  // Continuous collision: per shape, its index among the shapes whose candidates come from
  // their contacts (-1 otherwise; reset after each step), those shapes, and their candidate
  // lists (candidates_[candidateStart_[k] .. candidateStart_[k + 1]) for shape k).
  std::vector<std::int32_t> contactSwept_;
  std::vector<std::int32_t> sweptShapes_;
  std::vector<std::int32_t> fastSlots_;  // the slots of bodies that moved far enough to sweep
  std::vector<std::int32_t> candidateStart_, candidates_, fillCursor_;
  ContactEvents events_;
  SensorEvents sensorEvents_;
  // Sensor shapes and the shapes whose fat AABBs overlap them.
  struct SensorPair {
    std::int32_t sensor, visitor;
    bool overlapping = false;
  };
  std::vector<SensorPair> sensorPairs_;
  std::unordered_map<std::uint64_t, std::int32_t> sensorIndex_;
  // Contacts by their shape pair, for finding whether a new proxy pair already has one.
  std::unordered_map<std::uint64_t, std::int32_t> contactIndex_;
  Profile profile_;
  double time_ = 0;
  int bodyCount_ = 0;
};

// Runs a world at a fixed step from wall-clock time ("fix your timestep"): the elapsed time of
// each frame is banked and spent in whole steps of exactly dt, so the simulation (and its
// hashes) depend only on how many steps were taken, never on the frame rate. At most maxSteps
// are taken per call, so a frame that took too long cannot make the next one take longer still;
// the time over that is dropped (and counted). alpha() is the banked part of a step, for
// drawing bodies between their last two states.
class StepAccumulator {
 public:
  // dt finite and positive, maxSteps at least 1; otherwise InvalidDefinition.
  explicit StepAccumulator(float dt = 1.0f / 60.0f, int maxSteps = 8);
  // Banks elapsed seconds (finite, not negative) and steps the world for every whole step in
  // the bank, up to maxSteps. Returns the number of steps taken.
  int advance(World& world, double elapsedSeconds);
  float dt() const { return dt_; }
  double alpha() const { return banked_ / dt_; }      // in [0, 1) after advance()
  double droppedSeconds() const { return dropped_; }  // discarded by the step cap, in total
  long long steps() const { return steps_; }          // taken, in total

 private:
  float dt_;
  int maxSteps_;
  double banked_ = 0.0, dropped_ = 0.0;
  long long steps_ = 0;
};

}  // namespace rc
