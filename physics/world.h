// Ricochet physics: the world of rigid bodies, as a game sees it.
//
// Bodies (static, kinematic, dynamic) carry shapes; World::step(dt) advances them by a fixed
// time step in named phases, each timed into profile() when asked (physics/README.md describes
// them, in order). Bodies and shapes are referred to by generational handles: a handle to a
// destroyed body is detected, never silently reused. Events are read after the step; queries take a
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
  // Which events the shape takes part in. A contact reports begin and end when either shape
  // asks, and hits when either shape asks; a sensor reports a visitor when both ask.
  bool contactEvents = true;
  bool hitEvents = true;
  bool sensorEvents = true;
  std::uint64_t userData = 0;
};

inline constexpr int kMaxStackSolveDepth = 1000000;  // WorldDef::stackSolveDepth's largest

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
  // Contact recycling: a touching pair whose relative motion since its manifold was made is
  // below this (m, at the contact points and at the smaller body's reach as it turns) keeps the
  // manifold, its points carried by the bodies and its separations updated, instead of
  // colliding the shapes again: a resting pile's narrowphase costs next to nothing. 0: off.
  float contactRecycleDistance = 0.001f;  // see physics/README.md for why 1 mm
  // Piles: bodies resting through at least this many contacts on a static, sleeping or
  // kinematic body get their contacts solved exactly after each relax pass while any of them
  // moves faster than 0.4 of the sleep tolerances (until all are under a tenth of that): a tall
  // stack is still from its first steps instead of breathing for hundreds (physics/stack_solve.h,
  // physics/README.md "Piles"). 0: off.
  int stackSolveDepth = 3;  // 0 to kMaxStackSolveDepth
  // Continuous collision: contact points are kept while shapes are within what their bodies
  // can close in the step (speculative contacts), so fast bodies stop at surfaces instead of
  // passing through thin walls. Off: only within kSpeculativeDistance (shows the tunnelling).
  bool continuous = true;
  // Sleeping: an island of touching bodies whose every body has moved slower than the
  // tolerances for timeToSleep seconds (a third of it under a tenth of both) stops being
  // simulated until something wakes it (a contact with an awake body, a force, an impulse, a
  // velocity or transform set, wake()).
  bool enableSleep = true;
  float timeToSleep = 0.5f;                                   // s
  float linearSleepTolerance = 0.05f;                         // m/s
  float angularSleepTolerance = 2.0f * 3.14159265f / 180.0f;  // rad/s
  // The contact solver's widest batch, 4 or 8: eight lanes are taken where the processor has
  // AVX2, four otherwise. The results are bit-identical at either width (a colour's constraints
  // are independent), so this changes speed only.
  int maxSolverLanes = 8;
  // Time each phase of step() into profile(): fourteen clock reads a step, which on a virtual
  // machine's clock cost about a microsecond, a seventh of the shooter's whole step. Off, the
  // phases' times stay 0 (the solver's colours and lanes are kept either way).
  bool enableProfile = false;
  // A body found faster than this (m/s, or rad/s turning) or with a state that is not finite
  // is quarantined (QuarantineEvent): far above any game's bullets, far below what float
  // arithmetic on the contacts of such a body can carry without overflowing.
  float quarantineSpeed = 1e6f;
  // The region most bodies live in: the quadtree's world square. Bodies outside it still work,
  // but every query scans them (a list, not the tree): fit this to the level.
  AABB bounds{{-512.0f, -512.0f}, {512.0f, 512.0f}};
};

// A shape and its body, with both user data: what events and queries name. Taken when the
// event or hit was made, so it stays readable after the shape or body is destroyed.
struct ShapeRef {
  ShapeId shape;
  BodyId body;
  std::uint64_t shapeUserData = 0, bodyUserData = 0;
};

// What a cast hit.
struct WorldHit : ShapeRef {
  Vec2 point{};   // world frame
  Vec2 normal{};  // surface normal of the shape hit
  float fraction = 0.0f;
};

// Which shapes a query sees: the collision bitmask against the shapes' filters, and optionally
// a callback that can refuse any shape the bitmask lets through ("not the shooter's own
// body"). The callback must not change the world.
struct QueryFilter {
  ProxyFilter bits;
  std::function<bool(const ShapeRef&)> accept;
  QueryFilter() = default;
  QueryFilter(ProxyFilter filter) : bits(filter) {}  // NOLINT: a bitmask is a filter
  QueryFilter(ProxyFilter filter, std::function<bool(const ShapeRef&)> callback)
      : bits(filter), accept(std::move(callback)) {}
  // Everything but the shapes of one body.
  static QueryFilter ignoring(BodyId body, ProxyFilter filter = {}) {
    return {filter, [body](const ShapeRef& s) { return !(s.body == body); }};
  }
};

// Events of the last step, read after it: they stay unchanged until the next step, whatever
// the game destroys meanwhile. A contact begins when its manifold gets points: within the
// speculative margin, which for a fast body can be the step before the surfaces meet (then the
// point and normal are those where they will meet, and a fast pair that will not meet this step
// gets none); approachSpeed is measured then, before the solve. Contacts and sensor overlaps
// ended by a destroy, a disable or a change of filter between steps are reported with the next
// step's events (destroyed: true).
struct ContactBeginEvent {
  ShapeRef a, b;
  Vec2 point{}, normal{};   // normal from a to b
  float approachSpeed = 0;  // along the normal, positive when closing
};
struct ContactEndEvent {
  ShapeRef a, b;
  bool destroyed = false;  // ended by destroying or disabling a side, not by parting
};
// A contact that began closing faster than WorldDef::hitEventThreshold.
struct ContactHitEvent {
  ShapeRef a, b;
  Vec2 point{}, normal{};
  float approachSpeed = 0;
};
// A shape entered or left a sensor. A visitor that passes right through a sensor within one
// step (a bullet through a trip line) reports both in that step.
struct SensorEvent {
  ShapeRef sensor, visitor;
  bool destroyed = false;  // (end only) ended by destroying or disabling a side
};
struct SensorEvents {
  std::vector<SensorEvent> begin, end;
};

struct ContactEvents {
  std::vector<ContactBeginEvent> begin;
  std::vector<ContactEndEvent> end;
  std::vector<ContactHitEvent> hit;
};

// A body whose state became unusable during a step (not finite, or faster than
// WorldDef::quarantineSpeed) is taken out of the simulation before its contacts spread the
// value to its neighbours: it is disabled at where it was when the step began, at rest, and
// reported. Re-enable it (setEnabled) or destroy it.
enum class QuarantineCause : std::uint8_t {
  forceField,  // a force field gave it a force or torque that was not finite
  motion,      // its free motion (forces, gravity, its own velocity) left it not finite or too fast
  contact,     // the contact solve or continuous collision did
};
const char* quarantineCauseName(QuarantineCause cause);
struct QuarantineEvent {
  BodyId body;
  std::uint64_t userData = 0;
  QuarantineCause cause = QuarantineCause::motion;
};

// Wall-clock milliseconds of the last step, by phase.
struct Profile {
  double updatePairs = 0, narrowphase = 0, solve = 0, continuous = 0, refit = 0, sensors = 0,
         sleep = 0, total = 0;  // milliseconds
  // The contact solver's last step: colours in use, and constraints solved one at a time
  // because a body had more contacts than there are colours.
  int colours = 0, overflow = 0;
  int lanes = 0;  // constraints solved side by side: 4 or 8 (0 before the first solve)
  // The same constraints as the step before (a resting pile's): their colouring and lanes kept.
  bool layoutKept = false;
  // Of those, the constraints whose lanes were kept too (a recycled manifold's, rewritten only
  // where it changes: its separations).
  int lanesKept = 0;
  // The last narrowphase: touching contacts whose manifold was recycled (contactRecycleDistance)
  // and those made again.
  int recycled = 0, made = 0;
  // The last step's piles (stackSolveDepth): their bodies, and the substeps that corrected them.
  int pileBodies = 0, pileCorrections = 0;
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
  double time() const { return time_; }  // of the stage: seconds since the world began
  void addForce(BodyId id, Vec2 force);  // at the centre of mass
  void addTorque(BodyId id, float torque);
  void addForceAt(BodyId id, Vec2 force, Vec2 worldPoint);

 private:
  friend class WorldState;
  ForceStage(WorldState& world, std::span<const double> q, std::span<const float> v,
             std::span<float> a, double time)
      : world_(world), q_(q), v_(v), a_(a), time_(time) {}
  int slot(BodyId id) const;
  WorldState& world_;
  std::span<const double> q_;
  std::span<const float> v_;
  std::span<float> a_;
  double time_;
};

using ForceField = std::function<void(ForceStage&)>;

// A world's whole simulation state as bytes (World::snapshot): restored into a world made with
// the same force fields, it continues bit for bit as if never interrupted.
using WorldSnapshot = std::vector<std::uint8_t>;

class World {
 public:
  explicit World(const WorldDef& def = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Bodies and shapes. Ids are generational: a destroyed body's or shape's slot is reused with
  // a new generation, and the old id is refused (isValid false; other calls throw
  // std::invalid_argument). Destroying ends the contacts it had (end events, next step).
  BodyId createBody(const BodyDef& def);
  void destroyBody(BodyId id);
  ShapeId createShape(BodyId body, const Shape& shape, const ShapeDef& def = {});
  void destroyShape(ShapeId id);
  bool isValid(BodyId id) const;
  bool isValid(ShapeId id) const;

  void step(float dt);

  // Body state.
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
  float gravityScale(BodyId id) const;
  bool isBullet(BodyId id) const;
  bool isEnabled(BodyId id) const;
  void setLinearVelocity(BodyId id, Vec2 v);
  void setAngularVelocity(BodyId id, float w);
  void setTransform(BodyId id, Vec2 position, float angle);
  // A kinematic body moved to the target over the next step of dt: its velocities are set so
  // that it arrives there, pushing what is in its way (a door, a lift, a moving platform).
  void setTargetTransform(BodyId id, Vec2 position, float angle, float dt);
  // Changes what the body is; its mass, contacts and broadphase proxies follow.
  void setType(BodyId id, BodyType type);
  void setGravityScale(BodyId id, float scale);
  void setBullet(BodyId id, bool bullet);
  void setUserData(BodyId id, std::uint64_t userData);
  // A disabled body keeps its id, shapes and state but takes no part in anything: no contacts,
  // no queries, not stepped. Enabling puts it back where it was.
  void setEnabled(BodyId id, bool enabled);
  bool isAwake(BodyId id) const;
  // Wakes the body and every body asleep in its island.
  void wake(BodyId id);
  int awakeBodyCount() const;

  // Shape properties. Changes take effect at once, on existing contacts too.
  const Shape& shape(ShapeId id) const;
  std::uint64_t userData(ShapeId id) const;
  bool isSensor(ShapeId id) const;
  ProxyFilter filter(ShapeId id) const;
  float friction(ShapeId id) const;
  float restitution(ShapeId id) const;
  void setUserData(ShapeId id, std::uint64_t userData);
  void setFilter(ShapeId id, ProxyFilter filter);  // pairs the filter now refuses end
  void setFriction(ShapeId id, float friction);
  void setRestitution(ShapeId id, float restitution);
  void setSensor(ShapeId id, bool isSensor);
  void setEventFlags(ShapeId id, bool contactEvents, bool hitEvents, bool sensorEvents);

  // Forces and torques act for the next step, then are cleared. Impulses change the velocity
  // at once.
  void applyForce(BodyId id, Vec2 force, Vec2 worldPoint);
  void applyForceToCenter(BodyId id, Vec2 force);
  void applyTorque(BodyId id, float torque);
  void applyLinearImpulse(BodyId id, Vec2 impulse, Vec2 worldPoint);
  void applyAngularImpulse(BodyId id, float impulse);

  // Queries. Rays and casts go along origin + t * translation, t in [0, 1]; the closest hit
  // (ties to the lower shape id) or every hit sorted by fraction, then shape id. Sensors are
  // skipped. A ray starting inside a solid shape hits it at fraction 0 (see raycast.h).
  std::optional<WorldHit> castRay(Vec2 origin, Vec2 translation,
                                  const QueryFilter& filter = {}) const;
  std::vector<WorldHit> castRayAll(Vec2 origin, Vec2 translation,
                                   const QueryFilter& filter = {}) const;
  // A circle, or any shape placed at `start`, swept along the translation without turning
  // (bullets with a size, a character's movement, a grenade's next hop).
  std::optional<WorldHit> castCircle(Vec2 center, float radius, Vec2 translation,
                                     const QueryFilter& filter = {}) const;
  std::optional<WorldHit> castShape(const Shape& shape, const Transform& start, Vec2 translation,
                                    const QueryFilter& filter = {}) const;
  // Shapes whose AABB overlaps the box; that contain the point; that overlap the shape placed
  // at `where` (exactly, not by bounding boxes: a blast's circle, a melee swing's box). Sorted
  // by shape id; sensors included.
  std::vector<ShapeRef> overlapAABB(const AABB& box, const QueryFilter& filter = {}) const;
  std::vector<ShapeRef> overlapPoint(Vec2 point, const QueryFilter& filter = {}) const;
  std::vector<ShapeRef> overlapShape(const Shape& shape, const Transform& where,
                                     const QueryFilter& filter = {}) const;
  // The same queries for a caller that wants what they find disturbed (a blast that wakes the
  // crates in its area, a ray that should rouse what it touches): with Wake::yes every
  // sleeping body they report is woken, with its island.
  enum class Wake : std::uint8_t { no, yes };
  std::optional<WorldHit> castRay(Vec2 origin, Vec2 translation, const QueryFilter& filter,
                                  Wake wake);
  std::vector<ShapeRef> overlapAABB(const AABB& box, const QueryFilter& filter, Wake wake);
  std::vector<ShapeRef> overlapShape(const Shape& shape, const Transform& where,
                                     const QueryFilter& filter, Wake wake);
  BodyId bodyOf(ShapeId shape) const;
  ShapeRef ref(ShapeId shape) const;  // the shape, its body and their user data

  // The last step's events (see ContactBeginEvent): unchanged until the next step.
  const ContactEvents& contactEvents() const;
  const SensorEvents& sensorEvents() const;
  const std::vector<QuarantineEvent>& quarantineEvents() const;

  // A user force evaluated at every integrator stage (springs, drag, attractors). It sees
  // sleeping bodies at rest; a force on one wakes it after the step (it acts from the next).
  // A force field that names a body that does not exist makes step() throw once the step is
  // done (the world stays whole); a force that is not finite quarantines its body.
  void addForceField(ForceField field);

  int bodyCount() const;
  int shapeCount() const;
  int contactCount() const;
  int touchingContactCount() const;

  // Read-only views for tools that draw or inspect a world (the renderer's overlay).
  std::vector<BodyId> bodies() const;              // alive ones, by index
  std::vector<ShapeId> shapesOf(BodyId id) const;  // in creation order
  struct ContactPointView {
    Vec2 point, normal;  // normal from shape A to shape B
    float separation;
    float normalImpulse;  // of the last step's last substep (a bounce's not included)
  };
  std::vector<ContactPointView> contactPoints() const;  // of touching contacts
  const Quadtree& broadphase() const;
  const WorldDef& def() const;
  // Changes how the next steps are divided and integrated: a quality setting, or a study of the
  // error a setting adds from a state another reached (restore() takes only a snapshot of the
  // same definition: restore, then change). The contacts' carried impulses, which are per
  // substep, are scaled to the new substep so that a warm-started stack still holds. Throws
  // InvalidDefinition for substeps outside 1 to 64 or an integrator that is not one.
  void setStepping(int substeps, Integrator integrator);
  const Profile& profile() const;
  double time() const;

  // Everything that decides the next step, as bytes: bodies, shapes, contacts with their warm
  // starts, sleep timers and islands, sensor overlaps, the broadphase tree, pending events.
  // restore() takes a snapshot of a world with the same definition and force fields and
  // continues exactly as the snapshotted world would; a snapshot that is malformed or of
  // another format is refused with std::invalid_argument and the world left as it was.
  WorldSnapshot snapshot() const;
  void restore(std::span<const std::uint8_t> snapshot);

  // FNV-1a over the snapshot's bytes: equal hashes mean the next steps will be bit-identical.
  std::uint64_t stateHash() const;

  // Total kinetic energy plus gravitational potential energy (relative to y = 0).
  double energy() const;

 private:
  std::unique_ptr<WorldState> s_;
};

}  // namespace rc
