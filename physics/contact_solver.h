// Ricochet physics: the contact solver's inner loop, four contacts at a time.
//
// The world prepares one ContactConstraint per touching contact (anchors, effective masses,
// warm-start impulses); this solver colours them so that no two constraints of one colour move
// the same body, packs each colour four or eight constraints to a batch (structure of arrays) and
// solves a batch's constraints side by side in vectors (GCC/Clang vector extensions: eight lanes
// in AVX2 code where the processor has it, chosen at run time; otherwise four, SSE2 on x86-64,
// NEON on ARM, plain scalar code elsewhere). Constraints of one colour are independent, so
// solving them together is exactly solving them one after the other: the results do not depend
// on the vector width, and they are bit-identical on every build and processor (element-wise
// IEEE operations, no fused multiply-add, no approximate reciprocals).
//
// A body with more contacts than there are colours puts its extra constraints in the overflow,
// solved one to a batch after the colours. Static bodies (and kinematic ones, whose velocity no
// contact changes) take no colour: any number of constraints of a colour may touch them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>

#include "physics/math.h"

namespace rc {

// One point of a touching contact, prepared for the substeps. The caller sets the anchors, the
// separation and the carried impulses (maxNormalImpulse and relativeVelocity start at 0: the
// warm start sets a point's approach speed until the solver first pushes it); the solver
// derives the lever arms and effective masses, eight (or four) constraints at a time.
struct ConstraintPoint {
  Vec2 rA, rB;  // anchors from the centres of mass at the start of the step
  // Derived: rA x n, rB x n, rA x t, rB x t: a point's velocity along n is dot(vB - vA, n) +
  // wB (rB x n) - wA (rA x n), and an impulse along n turns A by -iA (rA x n) per unit.
  float rnA, rnB, rtA, rtB;
  float baseSeparation;
  float normalMass, tangentMass;  // derived
  float normalImpulse, tangentImpulse, maxNormalImpulse;
  float relativeVelocity;  // normal velocity before the solve, for restitution (see warmStart)
};

struct ContactConstraint {
  std::int32_t contact;
  std::int32_t slotA, slotB;  // solver body indices; -1: a static (or sleeping) body
  float invMassA, invIA, invMassB, invIB;
  Vec2 normal;
  float friction, restitution;
  float maxPushout;  // the fastest it pushes overlapping points apart (m/s)
  int pointCount;
  ConstraintPoint points[2];
};

// What the colouring needs of a constraint: its bodies' solver indices (-1: static or asleep),
// whether contacts move them (dynamic: a kinematic body's velocity is not theirs to change), and
// its point count.
struct ConstraintBodies {
  std::int32_t slotA, slotB;
  int pointCount;
  bool movesA, movesB;
  // Named and zeroed, so that a list of them compares as its bytes (ContactSolver::prepare).
  std::uint8_t padding[2] = {};
};
static_assert(sizeof(ConstraintBodies) == 16, "no padding but the named bytes");

// A point's results after the solve.
struct SolvedPoint {
  float normalImpulse, tangentImpulse, maxNormalImpulse, relativeVelocity;
};

// What the solver reads and writes of a body: its velocity, and how far it has moved and
// turned since the constraints were prepared. 32 bytes, two vector rows.
struct SolverBody {
  Vec2 v{};
  float w = 0.0f;
  float unused = 0.0f;  // the contact solver writes it 0
  Vec2 dp{};
  Rot dq{};
};
// The solver loads and stores each 16-byte half whole (see contact_solver.cpp).
static_assert(sizeof(SolverBody) == 32 && std::is_standard_layout_v<SolverBody>);

// The soft contact (Catto, "Solver2D", 2024): a spring-damper of stiffness omega and damping
// ratio zeta, written as a bias and a mass / impulse scale for an implicit step of size h.
struct ContactSoftness {
  float invH = 0, biasRate = 0, massScale = 1, impulseScale = 0;
  // For the two-point block solve: 1 / s_m and (1 - s_i) / s_m.
  float invMassScale = 1, carry = 0;
  // s_i / s_m: the bias that holds an impulse l against the leak is leak l / m.
  float leak = 0;
  static ContactSoftness make(float h, float hertz, float dampingRatio);
};

class ContactSolver {
 public:
  ContactSolver();
  ~ContactSolver();
  ContactSolver(const ContactSolver&) = delete;
  ContactSolver& operator=(const ContactSolver&) = delete;

  // Colours the constraints and lays out their batches; each constraint is then written into
  // its lane by set(i, ...), before the first warmStart. bodyCount bodies are indexed by slotA /
  // slotB; the solver bodies passed to the calls below have one more entry at the end, the null
  // body (zero velocity, no motion), which static bodies and empty lanes point at.
  // maxLanes (4 or 8) caps the batch width: 8 is taken only where the processor has AVX2.
  // The same constraints as last time (a resting pile's, step after step) keep their layout:
  // returns true then.
  bool prepare(std::span<const ConstraintBodies> constraints, int bodyCount, int maxLanes);
  // Constraint i (in prepare's order), what the caller sets of it (see ConstraintPoint):
  // straight into the batch's lanes, with no array of constraints in between (copying one and
  // repacking it was a sixth of a pyramid's step).
  void set(std::size_t i, const ContactConstraint& constraint);
  // Constraint i when its lane, from an earlier set() in this layout, holds it as it is but for
  // what changes while a manifold is carried (recycled): its points' base separations and its
  // push-out speed, written here; its impulses are the lane's (the last solve's, which the
  // caller stored). False, writing nothing, where the lane was cleared since (a batch with an
  // empty lane): set() it then.
  bool refresh(std::size_t i, int pointCount, float separation0, float separation1,
               float maxPushout);
  // After the last set(): each point's lever arms and effective masses, and where a manifold's
  // two points can be solved together, their coupled mass and its inverse; a batch at a time
  // (scalar, with its divisions, this was a tenth of a pyramid's step), and only the batches a
  // set() wrote to since (a refreshed lane's masses are as they were).
  void computeMasses();
  // Applies the carried impulses. With `free` (the bodies' velocities before any warm start:
  // vx, vy and w of each body, the null body's zeros after them, and one float more, read but
  // not used, for a body's three are loaded as four), first lowers each point not yet pushed to
  // its normal velocity there (relativeVelocity: the approach speed restitution reverses);
  // empty: no restitution to feed.
  void warmStart(std::span<SolverBody> bodies, std::span<const float> free);
  // One pass of normal (the two points of a manifold together where that is well posed) and
  // friction impulses. useBias: push overlapping points apart (the relax pass has no bias).
  // backward: the colours in reverse order. Gauss-Seidel in one fixed order favours one side:
  // a base-20 pyramid's top slid 5 cm sideways while it settled when every pass ran forward,
  // 3 mm when each pass runs the other way from the one before (symmetric Gauss-Seidel).
  // sameMotion (a pass with bias only): every body's dp and dq are as the last relax pass, since
  // this layout's last set() or refresh(), saw them (no position update since): the separations
  // it measured are used, not worked out again. The same bits either way.
  void solve(std::span<SolverBody> bodies, const ContactSoftness& soft, bool useBias, bool backward,
             bool sameMotion = false);
  // Point `point` of constraint i after the solve: its impulses, maxNormalImpulse and
  // relativeVelocity.
  SolvedPoint solved(std::size_t i, int point) const;
  // Every constraint's impulses after the solve, in prepare's order, four floats each: the
  // normal impulses of its two points, then their tangent impulses (a missing point's are 0).
  // One pass for all (the warm start's store), where solved() per point was a call and a lane
  // lookup each.
  void impulses(std::span<float> out) const;
  // The other way: every constraint's impulses set from the same layout (a correction made
  // outside the passes: the stack solve's).
  void setImpulses(std::span<const float> in);
  // The whole point, derived fields included (restitution needs its lever arms and mass).
  ConstraintPoint point(std::size_t i, int point) const;

  int colourCount() const;    // colours in use
  int overflowCount() const;  // constraints solved one at a time
  // Per body (as prepare() numbered them): the colours its constraints took, a bit each. With
  // no overflow, a body moved by k constraints has k bits: two constraints of a colour never
  // move one body.
  std::span<const std::uint32_t> bodyColours() const;
  int laneCount() const;  // constraints per batch in the last prepare(): 4 or 8

  // The widest batch this processor takes: 8 (one AVX2 register) where it has AVX2, else 4
  // (SSE2, NEON). Either width gives bit-identical results.
  static int widestLanes();

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

}  // namespace rc
