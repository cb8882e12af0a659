// Ricochet physics: the world's internal state and the functions of its step.
//
// Internal to physics/: a game includes world.h, which shows the API and holds a WorldState
// behind a pointer. The step's phases are member functions here, one file each (world.cpp reads
// as their list): bodies and mass (body.cpp), islands and sleep (island.cpp), pairs and the
// narrowphase (contact.cpp), the solver's stages (solver.cpp), continuous collision
// (continuous.cpp), sensors (sensor.cpp) and queries (query.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "physics/broadphase.h"
#include "physics/contact_solver.h"
#include "physics/integrate.h"
#include "physics/manifold.h"
#include "physics/shapes.h"
#include "physics/stack_solve.h"
#include "physics/toi.h"
#include "physics/trig.h"
#include "physics/world.h"

namespace rc {

// Definition checks shared by the world's files: each throws InvalidDefinition naming what
// was being defined and the field.
[[noreturn]] void failDefinition(const char* what, const char* field, const std::string& why);
void requireFinite(const char* what, const char* field, float v);
void requireFinite(const char* what, const char* field, Vec2 v);
void requireNonNegative(const char* what, const char* field, float v);
// A number as people read it (%g): "0.1", "1e+30", "nan".
std::string formatNumber(double v);

// Two shape indices as one key, for the pair maps (lookups only: never iterated).
inline std::uint64_t pairKey(std::int32_t a, std::int32_t b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// Friction and restitution of a pair, as Box2D mixes them: geometric mean, maximum.
inline float mixFriction(float a, float b) {
  return std::sqrt(a * b);
}
inline float mixRestitution(float a, float b) {
  return std::max(a, b);
}

class WorldState {
 public:
  // broadphaseDepth: the quadtree's (Quadtree::kAutoDepth: from the bounds).
  explicit WorldState(const WorldDef& def, int broadphaseDepth = Quadtree::kAutoDepth);

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
    bool enabled = true;
    float sleepTime = 0;       // how long it has been still (see updateSleep)
    std::int32_t island = -1;  // its sleeping island, -1 while awake
    std::uint64_t userData = 0;
    std::int32_t slot = -1;  // in q_ and v_; -1 for static bodies
    // Every shape a circle about the centre of mass: turning moves none of its contact
    // geometry, so the solver does not rotate its contact anchors (see integratePositions).
    bool round = false;
    std::vector<std::int32_t> shapes;
  };
  struct ShapeRecord {
    Shape shape = Circle{};
    std::int32_t body = -1;
    std::uint32_t generation = 0;
    bool alive = false;
    bool isSensor = false;
    bool contactEvents = true, hitEvents = true, sensorEvents = true;
    float density = 0, friction = 0, restitution = 0;
    ProxyFilter filter;
    ProxyId proxy = kNullProxy;  // kNullProxy while its body is disabled
    std::uint64_t userData = 0;
    BoundingCircle bound{};  // in the body frame: how far the shape reaches as the body turns
    // How far it reaches from its body's centre of mass: kept with the centre (massProperties,
    // and createShape where that is not called), so that the narrowphase's margins and the
    // refit take no square roots for it.
    float reach = 0;
    void setReach(Vec2 localCenter) { reach = length(bound.center - localCenter) + bound.radius; }
  };
  struct Contact {
    std::int32_t shapeA = -1, shapeB = -1;  // shapeA < shapeB
    Manifold manifold;
    float normalImpulse[2] = {0, 0}, tangentImpulse[2] = {0, 0};
    float friction = 0, restitution = 0;
    bool touching = false;
    // Recycling (narrowphase): the bodies' rotations when the manifold was made and its points'
    // separations then. `recyclable`: made by the plain manifold function (not foreseen nor
    // moved off a coincidence), so its anchors are one point on each body; `recycled`: this
    // step's manifold is that one carried along by the bodies.
    Rot madeQA, madeQB;
    float madeSeparation[2] = {0, 0};
    bool recyclable = false, recycled = false;
    // The stack solve's rows among its points last step (bit k; StackSolver::touchingPoints),
    // following the points by id when the manifold is made again.
    std::uint8_t stackRows = 0;
  };
  // A sensor shape and a shape whose fat AABB overlaps it.
  struct SensorPair {
    std::int32_t sensor, visitor;
    bool overlapping = false;
  };

  // ---- bodies and shapes (body.cpp)
  BodyId createBody(const BodyDef& def);
  void destroyBody(BodyId id);
  ShapeId createShape(BodyId body, const Shape& shape, const ShapeDef& def);
  void destroyShape(ShapeId id);
  const Body* find(BodyId id) const;  // nullptr for a stale or bad id
  ShapeRecord& shapeRecord(ShapeId id) {
    return const_cast<ShapeRecord&>(std::as_const(*this).shapeRecord(id));
  }
  ShapeRef ref(std::int32_t shape) const;
  // A body's shapes into the broadphase, or out of it with their contacts and sensor pairs
  // (enabling and disabling, changing type or sensor flag); out wakes what they touched.
  void addProxies(Body& b);
  void addProxy(Body& b, std::int32_t shape);
  void removeProxies(Body& b);
  void removeProxy(std::int32_t shape);
  // A simulated body's slot: taken into the awake slots, or given up (the body then has none).
  void takeSlot(std::int32_t index, Vec2 velocity, float angularVelocity);
  void releaseSlot(Body& b);
  void disable(Body& b);
  void enable(Body& b);
  std::size_t checked(BodyId id) const;  // the body's index; throws for a stale or bad id
  Body& body(BodyId id) { return bodies_[checked(id)]; }
  const Body& body(BodyId id) const { return bodies_[checked(id)]; }
  const ShapeRecord& shapeRecord(ShapeId id) const;  // throws for a stale or bad id
  ShapeId shapeId(std::int32_t index) const {
    return {index, shapes_[static_cast<std::size_t>(index)].generation};
  }
  BodyId bodyId(std::int32_t index) const {
    return {index, bodies_[static_cast<std::size_t>(index)].generation};
  }
  // (The accessors the phases call per body are defined here, so that every phase's file can
  // inline them.)
  Vec2 center(const Body& b) const {
    if (b.slot < 0) return apply(b.xf, b.localCenter);
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    return {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])};
  }
  Vec2 velocityOf(const Body& b) const {
    if (b.slot < 0) return {};
    const auto i = 3 * static_cast<std::size_t>(b.slot);
    return {v_[i], v_[i + 1]};
  }
  // The body's origin in double (its centre minus the turned local centre): what the
  // narrowphase takes differences of.
  // One component (0 x, 1 y), given the turned local centre rotate(b.xf.q, b.localCenter), which
  // a caller taking both turns once.
  double preciseOrigin(const Body& b, int axis, Vec2 turned) const {
    if (b.slot < 0) return axis == 0 ? b.xf.p.x : b.xf.p.y;
    return q_[3 * static_cast<std::size_t>(b.slot) + static_cast<std::size_t>(axis)] -
           static_cast<double>(axis == 0 ? turned.x : turned.y);
  }
  std::array<double, 2> preciseOrigin(const Body& b) const {
    const Vec2 turned = rotate(b.xf.q, b.localCenter);
    return {preciseOrigin(b, 0, turned), preciseOrigin(b, 1, turned)};
  }
  // An awake body's motion over the step so far, from where it started (float: for sweeps).
  Sweep stepSweep(const Body& b) const {
    const auto s = static_cast<std::size_t>(b.slot);
    const std::size_t i = 3 * s;
    return {b.localCenter,
            {static_cast<float>(startCenter_[2 * s]), static_cast<float>(startCenter_[2 * s + 1])},
            {static_cast<float>(q_[i]), static_cast<float>(q_[i + 1])},
            static_cast<float>(startAngle_[s]),
            static_cast<float>(q_[i + 2])};
  }
  bool isRound(const Body& b) const;  // see Body::round
  // Mass, inertia, centre of mass, extents and roundness from the body's shapes; updateMass
  // also keeps the body's origin and motion where they were when the centre moves.
  void updateMass(Body& b);
  void massProperties(Body& b);
  // The body's proxies from its transform, stretched along its next step: displacement, and
  // turn (radians) for the shapes the turn carries beyond the AABB margin.
  void refitBody(Body& b, Vec2 displacement, float turn = 0.0f);
  void swapSlots(std::int32_t a, std::int32_t b);

  // ---- islands and sleep (island.cpp)
  bool awake(const Body& b) const { return b.slot >= 0 && b.slot < awakeCount_; }
  void wakeBody(Body& b);
  void updateSleep(float dt);

  // ---- contacts (contact.cpp)
  void updatePairs();
  void narrowphase(float dt);
  bool recycle(Contact& c, const Body& a, const Body& b, Vec2 offset, float margin) const;
  void foresee(Manifold& m, const ShapeRecord& ra, const Transform& xfA, const ShapeRecord& rb,
               const Transform& xfB, float dt) const;
  // destroyed: ended by a destroy, disable or filter change, not by the shapes parting.
  void destroyContact(std::size_t index, bool destroyed = false);
  bool wantsContactEvents(const Contact& c) const {
    return shapes_[static_cast<std::size_t>(c.shapeA)].contactEvents ||
           shapes_[static_cast<std::size_t>(c.shapeB)].contactEvents;
  }
  // Where end events made now go: the step's own, or (between steps) the next step's.
  ContactEvents& contactSink() { return stepping_ ? events_ : pendingEvents_; }
  SensorEvents& sensorSink() { return stepping_ ? sensorEvents_ : pendingSensorEvents_; }

  // ---- the solver's stages (solver.cpp)
  void solve(float dt);
  void prepareContacts();
  void prepareBodies(float dt);
  void integrateFreeMotion(int substep, float h);
  void applyDamping(float h, bool move);
  void warmStart();
  void integratePositions(float h);
  void storeVelocities();
  void quarantineUnusable(QuarantineCause cause, bool inStep);
  void requestQuarantine(std::int32_t body, QuarantineCause cause);
  static void velocityRows(std::span<const float> v, std::size_t slots, std::vector<float>& rows);
  void storeImpulses();
  void applyRestitution();
  // A manifold point's part in restitution: not pushed (left alone), bouncing, or holding (see
  // applyRestitution).
  enum class Bounce : std::uint8_t { none, bounces, holds };
  bool bounceTogether(ContactConstraint& cc, const Bounce (&roles)[2], Vec2& vA, float& wA,
                      Vec2& vB, float& wB);
  void prepareBounceGroups();
  void advancePileLayout(bool sameAsLast);
  void correctPiles();
  void pileDetails();
  void pileConstraint(std::size_t i, const ContactConstraint& cc);
  void pileTouching(std::size_t i, Contact& c);
  void measureContactWork();
  void limitBounceEnergy();
  void accelerations(std::span<const double> q, std::span<const float> v, double t,
                     std::span<float> a);

  // ---- the step's bookends (world.cpp)
  void beginEvents();
  void endStep();

  // ---- after the solve (continuous.cpp, world.cpp, sensor.cpp)
  void continuous();
  void refit(float dt);
  void updateSensors();
  void destroySensorPair(std::size_t index, bool destroyed = false);
  bool wantsSensorEvents(const SensorPair& sp) const {
    return shapes_[static_cast<std::size_t>(sp.sensor)].sensorEvents &&
           shapes_[static_cast<std::size_t>(sp.visitor)].sensorEvents;
  }

  // ---- queries (query.cpp)
  bool accepts(const QueryFilter& filter, std::int32_t shape) const;
  const Transform& transformOf(const ShapeRecord& r) const;
  WorldHit hitOf(const ProxyHit& h) const;
  // The closest hit of a cast: exact(record, ray) tests one solid shape the filter accepts.
  template <class Exact>
  std::optional<WorldHit> closest(const RayCastInput& in, float radius, const QueryFilter& filter,
                                  Exact&& exact) const;
  // The shapes whose fat AABB meets the box, that exact(record) keeps and the filter accepts,
  // sorted by shape index.
  template <class Exact>
  std::vector<ShapeRef> overlapping(const AABB& box, const QueryFilter& filter,
                                    Exact&& exact) const;

  // ---- batched rotations: angles queued with their owners, their sines and cosines taken in
  // one batch (rc::sincos overlaps independent calls), each owner handed its rotation.
  // Room for n turns before any is queued, so that an allocation failure cannot leave the
  // angles and their owners of different lengths.
  void reserveTurns(std::size_t n) {
    turnAngles_.reserve(n);
    turnOwners_.reserve(n);
    turnRotations_.reserve(n);
  }
  template <class Apply>
  void applyTurns(Apply&& apply) {
    turnRotations_.resize(turnAngles_.size());
    sincos(turnAngles_, turnRotations_);
    for (std::size_t k = 0; k < turnAngles_.size(); ++k)
      apply(turnOwners_[k], Rot{turnRotations_[k].cosine, turnRotations_[k].sine});
    turnAngles_.clear();
    turnOwners_.clear();
  }

  WorldDef def_;
  Quadtree broadphase_;
  std::vector<Body> bodies_;
  std::vector<std::int32_t> freeBodies_;
  std::vector<ShapeRecord> shapes_;
  std::vector<std::int32_t> freeShapes_;
  std::vector<Contact> contacts_;
  // Contacts known to have nothing awake on either side (both bodies asleep, or asleep and
  // static), a byte each by index into contacts_, while the awake set is as it was when they
  // were marked (awakeEpoch_, bumped by every slot swap, equal to contactSleepEpoch_); 0, or an
  // index past the end, says nothing. From the marks, the list of the others in ascending
  // order, which the narrowphase, the constraints' preparation and the islands walk as they
  // would walk contacts_: a contact with nothing awake costs them nothing (skipping each by its
  // byte cost a far sleeping pile's 10,600 contacts 1 ns each in each of those loops). A
  // listed contact may have nothing awake (the loops look). A contact made is listed; a
  // destroyed one is mended in place (destroyContact), or, where that would take an entry moved
  // into the middle, has the list made again from the marks when next asked for
  // (contactListStale_). Not state: never saved, made again after a restore.
  std::vector<std::uint8_t> contactAsleep_;
  std::vector<std::int32_t> awakeContacts_;
  // Per awake slot, for a narrowphase with more contacts than awake bodies: the body's origin in
  // double (preciseOrigin) and its speed and turning speed (|v|, |w|), worked out once.
  struct SlotPose {
    double x, y;
    float speed, spin;
  };
  std::vector<SlotPose> slotPoses_;
  std::uint64_t awakeEpoch_ = 1, contactSleepEpoch_ = 0;
  bool contactListStale_ = true;
  bool contactMarksHold() const { return contactSleepEpoch_ == awakeEpoch_; }
  // The list, made again first if the awake set has changed (the marks too) or it is stale.
  const std::vector<std::int32_t>& awakeContactList();
  std::vector<ForceField> fields_;
  // Per simulated (kinematic and dynamic) body, three degrees of freedom: x, y and angle of the
  // centre of mass, and their velocities. Bodies hold their slot. Positions are doubles: 10 km
  // out a float position moves in steps of 1 mm and a settling pile cannot take the small steps
  // it needs (everything else, velocities, impulses, shapes and the narrowphase, which works
  // relative to body A, is float).
  std::vector<double> q_;
  std::vector<float> v_;
  std::vector<std::int32_t> slotBody_;
  // Per slot, x and y of the centre of mass where the body became still (see updateSleep): kept
  // with the slots, which the sleep pass walks, not in the bodies it would have to fetch.
  std::vector<double> stillFrom_;
  // Slots [0, awakeCount_) are awake; sleeping bodies' slots follow, untouched by the step.
  int awakeCount_ = 0;
  std::vector<std::vector<std::int32_t>> islands_;  // sleeping islands: their bodies
  std::vector<std::int32_t> freeIslands_;
  std::vector<std::int32_t> islandParent_;  // union-find over awake slots, per step
  std::vector<std::int32_t> islandSize_;    // the union-find's tree sizes
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
  // Per awake slot: how many constraints overlapping past the slop when the step began move it
  // (see prepareContacts: each pushes it out at its share of the push-out speed), and the slots
  // counted, zeroed again at the next prepareContacts.
  std::vector<std::int32_t> slotOverlaps_;
  std::vector<std::int32_t> overlapping_;
  std::vector<ContactConstraint> bouncy_;
  std::vector<std::int32_t> bouncyIndex_;
  std::vector<std::int32_t> bouncing_;  // bouncy_ that may bounce this step (applyRestitution)
  // Restitution's energy budget (limitBounceEnergy): the bodies joined to a bouncy constraint
  // by touching contacts, in groups; per group what the contacts did to its kinetic energy
  // over the substeps (J), the terms of its energy as a function of how much of the bounce is
  // applied, the fraction kept, its highest restitution, and whether a kinematic body drives
  // it. Per tracked body its slot, group, mass and rotational inertia; its velocity before
  // restitution (3 each). Per constraint its group (-1: none, -2: left out).
  struct BounceGroup {
    double work = 0, bounceSquare = 0, bounceCross = 0, kept = 1;
    float restitution = 0;
    bool driven = false;
  };
  struct TrackedBody {
    std::int32_t slot, group;
    float mass, inertia;
  };
  std::vector<BounceGroup> bounceGroups_;
  std::vector<TrackedBody> tracked_;
  std::vector<float> beforeBounce_;
  std::vector<std::int32_t> constraintGroup_;
  std::vector<std::int32_t> grouped_;                 // the constraints that are not lone
  std::vector<std::int32_t> slotParent_, rootGroup_;  // per awake slot, while grouping
  std::vector<std::uint8_t> slotDegree_;
  ContactSolver contactSolver_;
  // Per constraint, the contact its lane was last set() for; current (lanesCurrent_) until
  // something a lane is made from changes other than a manifold: a contact made or destroyed,
  // a body's mass, a material, the substeps (prepareContacts).
  std::vector<std::int32_t> laneContacts_;
  bool lanesCurrent_ = false;
  // The direct solve of piles (WorldDef::stackSolveDepth): its constraints in prepare's order,
  // the impulses it exchanges with the contact solver, and the slots' inverse masses (written for
  // the slots of constraints only: it reads no others).
  StackSolver stackSolver_;
  std::vector<StackSolver::Constraint> stackConstraints_;
  std::vector<float> stackImpulses_, slotInvMass_, slotInvInertia_;
  // A hash of last step's constraints (their slots and point counts) and the awake count:
  // whether a point's row may stay one apart (pileConstraint). Part of the state.
  std::uint64_t pileLayout_ = 0;
  std::uint32_t pileLayoutCount_ = 0;
  bool pileLayoutValid_ = false, pileLayoutKept_ = false;
  bool pileDetails_ = false;       // this step's constraints complete (pileDetails)
  bool pileTouchChanged_ = false;  // some constraint's touching points are not last step's
  // Per slot during the solve: the free-motion velocities of the substep (as velocityRows lays
  // them out), and the solver's bodies (velocity, and how far each has moved and turned since
  // the constraints were prepared), plus the null body at the end; with an integrator other
  // than semi-implicit Euler, the velocities before the free motion, which restitution reads
  // its approach from (semi-implicit Euler's is freeV_).
  std::vector<float> freeV_;
  std::vector<float> solvedImpulses_;  // storeImpulses' scratch: four floats a constraint
  std::vector<SolverBody> solverBodies_;
  std::vector<float> approachV_;
  std::vector<double> startCenter_;  // x and y per slot
  std::vector<double> startAngle_;
  // Body::round per slot, read each substep (a byte each, where the bodies are a cache miss).
  std::vector<std::uint8_t> slotRound_;
  // Per slot, for the continuous pass's first look: half the body's smallest extent (infinite
  // for a body it never sweeps) and its largest, from prepareBodies while the awake set is as
  // it was then (slotExtentsEpoch_): a body that moved less than that cannot be fast, and is
  // passed over without reading its record (a cache miss per awake body, 5% of an arena's step).
  std::vector<float> slotHalfMinExtent_, slotMaxExtent_;
  std::uint64_t slotExtentsEpoch_ = 0;
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
  ContactEvents events_, pendingEvents_;
  SensorEvents sensorEvents_, pendingSensorEvents_;
  std::vector<QuarantineEvent> quarantineEvents_;
  bool stepping_ = false;
  // Whether velocities may be unusable: the game set or pushed one since the last step (checked
  // before the step), forces or fields this step could make one so (checked every substep).
  bool velocitiesSet_ = true;
  bool checkFreeMotion_ = true;
  // Found during the step, acted on at its end: bodies to quarantine (with where they began the
  // step: centre and angle), bodies a force field pushed while they slept, and the first id a
  // force field named that is stale.
  struct Quarantined {
    std::int32_t body;
    QuarantineCause cause;
    std::array<double, 3> start;
  };
  std::vector<Quarantined> quarantine_;
  std::vector<std::int32_t> fieldWakes_;
  std::optional<BodyId> staleFieldId_;
  std::vector<SensorPair> sensorPairs_;
  std::unordered_map<std::uint64_t, std::int32_t> sensorIndex_;
  // Contacts by their shape pair, for finding whether a new proxy pair already has one.
  std::unordered_map<std::uint64_t, std::int32_t> contactIndex_;
  Profile profile_;
  double time_ = 0;
  int bodyCount_ = 0;
  int shapeCount_ = 0;
};

}  // namespace rc
